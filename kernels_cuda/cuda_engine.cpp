#include "kernels_cuda/cuda_engine.h"

namespace svgf::cuda {

// counter_[b]: run_tallying's count of bit b.
constexpr size_t kCounters = kTallyBits;

CudaEngine::CudaEngine(LaunchShape shape) : shape_(shape), counter_(kCounters) {
  counter_host_.resize(kCounters, "the frame's counters");
}

void CudaEngine::begin_frame() {
  marks_.clear();
  times_.clear();
  tallies_ = Tallies{};
  SVGF_CUDA_CHECK(cudaMemsetAsync(counter_.get(), 0, kCounters * sizeof(unsigned long long),
                                  stream_.get()),
                  "cudaMemsetAsync of the frame's counters");
}

void CudaEngine::mark(const char* stage) {
  if (events_.size() <= marks_.size()) events_.emplace_back();
  SVGF_CUDA_CHECK(cudaEventRecord(events_[marks_.size()].get(), stream_.get()),
                  std::string("cudaEventRecord before ") + stage);
  marks_.push_back(stage);
}

void CudaEngine::end_frame() {
  SVGF_CUDA_CHECK(cudaMemcpyAsync(counter_host_.get(), counter_.get(),
                                  kCounters * sizeof(unsigned long long), cudaMemcpyDeviceToHost,
                                  stream_.get()),
                  "download of the frame's counters");
  if (events_.size() <= marks_.size()) events_.emplace_back();
  const cudaEvent_t last = events_[marks_.size()].get();
  SVGF_CUDA_CHECK(cudaEventRecord(last, stream_.get()), "cudaEventRecord at the frame's end");
  const cudaError_t e = cudaStreamSynchronize(stream_.get());
  if (e != cudaSuccess) {
    // Kernels run asynchronously: a fault is seen here, after the fact. Name them all.
    std::string names;
    for (const char* m : marks_) names += (names.empty() ? "" : ", ") + std::string(m);
    check(e, "executing the frame's kernels (" + names + ")");
  }
  for (size_t i = 0; i < marks_.size(); ++i) {
    float ms = 0.f;
    SVGF_CUDA_CHECK(cudaEventElapsedTime(&ms, events_[i].get(), events_[i + 1].get()),
                    "cudaEventElapsedTime");
    times_.add(marks_[i], static_cast<double>(ms));
  }
  for (int b = 0; b < kTallyBits; ++b)
    tallies_.count[b] = static_cast<int64_t>(counter_host_.get()[b]);
}

}  // namespace svgf::cuda
