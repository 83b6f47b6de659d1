#pragma once
// RAII owners for the CUDA runtime objects a denoiser holds: a stream, events, pinned host
// memory. Host-compilable. Destructors ignore errors: they may run while an exception from a
// failed CUDA call is already unwinding.
#include <cstddef>
#include <string>
#include <utility>

#include "kernels_cuda/cuda_check.h"

namespace svgf::cuda {

class Stream {
 public:
  Stream() {
    SVGF_CUDA_CHECK(cudaStreamCreateWithFlags(&s_, cudaStreamNonBlocking), "cudaStreamCreate");
  }
  ~Stream() {
    if (s_) cudaStreamDestroy(s_);
  }
  Stream(const Stream&) = delete;
  Stream& operator=(const Stream&) = delete;
  cudaStream_t get() const { return s_; }

 private:
  cudaStream_t s_ = nullptr;
};

class Event {
 public:
  Event() { SVGF_CUDA_CHECK(cudaEventCreate(&e_), "cudaEventCreate"); }
  ~Event() {
    if (e_) cudaEventDestroy(e_);
  }
  Event(const Event&) = delete;
  Event& operator=(const Event&) = delete;
  Event(Event&& o) noexcept : e_(std::exchange(o.e_, nullptr)) {}
  Event& operator=(Event&& o) noexcept {
    std::swap(e_, o.e_);
    return *this;
  }
  cudaEvent_t get() const { return e_; }

 private:
  cudaEvent_t e_ = nullptr;
};

// Page-locked host memory: the staging area of the per-frame uploads and downloads, so that
// cudaMemcpyAsync runs as one DMA transfer instead of being staged by the driver.
template <class T>
class PinnedBuffer {
 public:
  PinnedBuffer() = default;
  ~PinnedBuffer() { release(); }
  PinnedBuffer(const PinnedBuffer&) = delete;
  PinnedBuffer& operator=(const PinnedBuffer&) = delete;

  void resize(size_t n, const char* what) {
    if (n == size_) return;
    release();
    if (n)
      SVGF_CUDA_CHECK(cudaMallocHost(reinterpret_cast<void**>(&ptr_), n * sizeof(T)),
                      "cudaMallocHost of " + std::to_string(n * sizeof(T)) + " bytes for " + what);
    size_ = n;
  }
  T* get() const { return ptr_; }
  size_t size() const { return size_; }

 private:
  void release() {
    if (ptr_) cudaFreeHost(ptr_);
    ptr_ = nullptr;
    size_ = 0;
  }
  T* ptr_ = nullptr;
  size_t size_ = 0;
};

}  // namespace svgf::cuda
