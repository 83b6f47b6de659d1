// Exact mode: every core/ pixel kernel runs through one generic launcher, so the GPU executes
// the very functions the CPU does. Compiled with -fmad=false -prec-div=true -prec-sqrt=true
// -ftz=false (kernels_cuda/CMakeLists.txt): with those, each float operation rounds exactly as
// on the CPU and the results are bitwise equal.
#include "kernels_cuda/exact_launch.h"
#include "kernels_cuda/launch_config.h"
#include "kernels_cuda/pixel_kernels.cuh"

namespace svgf::cuda {
namespace {

// The kernel struct travels by value as a launch parameter (a few hundred bytes of views and
// parameters, well under the 4 KB limit).
template <class K>
__global__ void pixel_kernel(const K k, int width, int height) {
  const int x = device::pixel_x();
  const int y = device::pixel_y();
  if (x < width && y < height) k(x, y);
}

// For kernels returning bool: counts the pixels that returned true.
template <class K>
__global__ void counting_pixel_kernel(const K k, int width, int height,
                                      unsigned long long* count) {
  const int x = device::pixel_x();
  const int y = device::pixel_y();
  const bool flag = x < width && y < height && k(x, y);
  device::count_block(flag, count);
}

__global__ void demodulate_reproject_kernel(const DemodulateKernel demodulate,
                                            const ReprojectKernel reproject,
                                            float4* __restrict__ packed_guides,
                                            unsigned long long* count) {
  const GuideView& g = reproject.guides;
  const int x = device::pixel_x();
  const int y = device::pixel_y();
  bool replaced = false;
  if (x < g.width && y < g.height) {
    replaced = demodulate(x, y);
    reproject(x, y);  // reads back this thread's own illumination write
    const int i = g.index(x, y);
    packed_guides[i] = make_float4(g.depth[i], g.normal.r[i], g.normal.g[i], g.normal.b[i]);
  }
  device::count_block(replaced, count);
}

template <class K>
void launch_pixels(const K& k, int width, int height, LaunchShape shape, cudaStream_t stream) {
  if (width <= 0 || height <= 0) return;
  const LaunchGeometry g = launch_geometry(width, height, shape);
  pixel_kernel<K><<<g.grid, g.block, 0, stream>>>(k, width, height);
  check_launch(kernel_name(k), g);
}

}  // namespace

void launch(const DemodulateKernel& k, int width, int height, LaunchShape shape,
            cudaStream_t stream, unsigned long long* count) {
  if (width <= 0 || height <= 0) return;
  const LaunchGeometry g = launch_geometry(width, height, shape);
  counting_pixel_kernel<DemodulateKernel><<<g.grid, g.block, 0, stream>>>(k, width, height, count);
  check_launch(kernel_name(k), g);
}
void launch_demodulate_reproject(const DemodulateKernel& demodulate,
                                 const ReprojectKernel& reproject, float* packed_guides,
                                 LaunchShape shape, cudaStream_t stream,
                                 unsigned long long* count) {
  const int width = reproject.guides.width, height = reproject.guides.height;
  if (width <= 0 || height <= 0) return;
  const LaunchGeometry g = launch_geometry(width, height, shape);
  demodulate_reproject_kernel<<<g.grid, g.block, 0, stream>>>(
      demodulate, reproject, reinterpret_cast<float4*>(packed_guides), count);
  check_launch("demodulate+reproject", g);
}
void launch(const ReprojectKernel& k, int width, int height, LaunchShape shape,
            cudaStream_t stream) {
  launch_pixels(k, width, height, shape, stream);
}
void launch(const VarianceKernel& k, int width, int height, LaunchShape shape,
            cudaStream_t stream) {
  launch_pixels(k, width, height, shape, stream);
}
void launch(const AtrousKernel& k, int width, int height, LaunchShape shape, cudaStream_t stream) {
  launch_pixels(k, width, height, shape, stream);
}
void launch(const RemodulateKernel& k, int width, int height, LaunchShape shape,
            cudaStream_t stream) {
  launch_pixels(k, width, height, shape, stream);
}
void launch(const TonemapKernel& k, int width, int height, LaunchShape shape,
            cudaStream_t stream) {
  launch_pixels(k, width, height, shape, stream);
}
void launch(const CopyRgbKernel& k, int width, int height, LaunchShape shape,
            cudaStream_t stream) {
  launch_pixels(k, width, height, shape, stream);
}

}  // namespace svgf::cuda
