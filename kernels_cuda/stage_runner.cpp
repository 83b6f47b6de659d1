// Single stages for tests and tools: launch on the default stream, wait, and name the kernel in
// any error, whether the launch was refused or the kernel faulted while running.
#include "kernels_cuda/stage_runner.h"

#include <string>

#include "kernels_cuda/cuda_check.h"
#include "kernels_cuda/device_array.h"
#include "kernels_cuda/exact_launch.h"

namespace svgf::cuda {
namespace {

template <class K>
void wait_for(const K& k) {
  SVGF_CUDA_CHECK(cudaStreamSynchronize(nullptr),
                  std::string("kernel '") + kernel_name(k) + "' execution");
}

template <class K>
void run_and_wait(const K& k, int width, int height, LaunchShape shape) {
  launch(k, width, height, shape, nullptr);
  wait_for(k);
}

}  // namespace

int64_t run(const DemodulateKernel& k, int width, int height, LaunchShape shape) {
  DeviceArray<unsigned long long> count(1);
  SVGF_CUDA_CHECK(cudaMemsetAsync(count.get(), 0, sizeof(unsigned long long), nullptr),
                  "cudaMemset of the demodulate counter");
  launch(k, width, height, shape, nullptr, count.get());
  wait_for(k);
  unsigned long long n = 0;
  count.download(&n, 1);
  return static_cast<int64_t>(n);
}
void run(const ReprojectKernel& k, int width, int height, LaunchShape shape) {
  run_and_wait(k, width, height, shape);
}
void run(const VarianceKernel& k, int width, int height, LaunchShape shape) {
  run_and_wait(k, width, height, shape);
}
void run(const AtrousKernel& k, int width, int height, LaunchShape shape) {
  run_and_wait(k, width, height, shape);
}
void run(const RemodulateKernel& k, int width, int height, LaunchShape shape) {
  run_and_wait(k, width, height, shape);
}
void run(const TonemapKernel& k, int width, int height, LaunchShape shape) {
  run_and_wait(k, width, height, shape);
}
void run(const CopyRgbKernel& k, int width, int height, LaunchShape shape) {
  run_and_wait(k, width, height, shape);
}

}  // namespace svgf::cuda
