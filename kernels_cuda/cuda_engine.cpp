#include "kernels_cuda/cuda_engine.h"

namespace svgf::cuda {

// counter_[b]: run_tallying's count of bit b.
constexpr size_t kCounters = kTallyBits;

CudaEngine::CudaEngine(LaunchShape shape)
    : shape_(shape), stream_(own_stream_.get()), last_stream_(own_stream_.get()),
      counter_(kCounters) {
  counter_host_.resize(kCounters, "the frame's counters");
}

void CudaEngine::begin_frame() { begin_frame(own_stream_.get()); }

void CudaEngine::begin_frame(cudaStream_t stream) {
  stream_ = stream;
  if (ended_ && stream != last_stream_)
    SVGF_CUDA_CHECK(cudaStreamWaitEvent(stream, frame_end_.get(), 0),
                    "cudaStreamWaitEvent on the previous frame's end");
  pending_ = false;
  marks_.clear();
  times_.clear();
  tallies_ = Tallies{};
  SVGF_CUDA_CHECK(cudaMemsetAsync(counter_.get(), 0, kCounters * sizeof(unsigned long long),
                                  stream_),
                  "cudaMemsetAsync of the frame's counters");
}

void CudaEngine::mark(const char* stage) {
  if (events_.size() <= marks_.size()) events_.emplace_back();
  SVGF_CUDA_CHECK(cudaEventRecord(events_[marks_.size()].get(), stream_),
                  std::string("cudaEventRecord before ") + stage);
  marks_.push_back(stage);
}

// The counters' download and the end event, enqueued behind the frame's work.
void CudaEngine::record_end() {
  SVGF_CUDA_CHECK(cudaMemcpyAsync(counter_host_.get(), counter_.get(),
                                  kCounters * sizeof(unsigned long long), cudaMemcpyDeviceToHost,
                                  stream_),
                  "download of the frame's counters");
  SVGF_CUDA_CHECK(cudaEventRecord(frame_end_.get(), stream_), "cudaEventRecord at the frame's end");
  last_stream_ = stream_;
  ended_ = true;
}

void CudaEngine::end_frame() {
  record_end();
  pending_ = true;
  read_results();
}

void CudaEngine::end_frame_async() {
  record_end();
  pending_ = true;
}

void CudaEngine::wait_frame() const {
  if (!ended_) return;
  const cudaError_t e = cudaEventSynchronize(frame_end_.get());
  if (e != cudaSuccess) {
    // Kernels run asynchronously: a fault is seen here, after the fact. Name them all.
    std::string names;
    for (const char* m : marks_) names += (names.empty() ? "" : ", ") + std::string(m);
    check(e, "executing the frame's kernels (" + names + ")");
  }
}

void CudaEngine::read_results() const {
  if (!pending_) return;
  wait_frame();
  for (size_t i = 0; i < marks_.size(); ++i) {
    const cudaEvent_t to = i + 1 < marks_.size() ? events_[i + 1].get() : frame_end_.get();
    float ms = 0.f;
    SVGF_CUDA_CHECK(cudaEventElapsedTime(&ms, events_[i].get(), to), "cudaEventElapsedTime");
    times_.add(marks_[i], static_cast<double>(ms));
  }
  for (int b = 0; b < kTallyBits; ++b)
    tallies_.count[b] = static_cast<int64_t>(counter_host_.get()[b]);
  pending_ = false;
}

const StageTimes& CudaEngine::times() const {
  read_results();
  return times_;
}

const Tallies& CudaEngine::tallies() const {
  read_results();
  return tallies_;
}

}  // namespace svgf::cuda
