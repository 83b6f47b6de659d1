#pragma once
// Device memory owned RAII-style. Host-compilable (CUDA runtime API only), so tests and tools
// written in plain C++ can stage data for single-stage runs.
#include <cstddef>
#include <string>
#include <vector>

#include "kernels_cuda/cuda_check.h"

namespace svgf::cuda {

template <class T>
class DeviceArray {
 public:
  DeviceArray() = default;
  explicit DeviceArray(size_t n) { resize(n); }
  DeviceArray(const T* host, size_t n) { resize(n); upload(host, n); }
  ~DeviceArray() { release(); }
  DeviceArray(const DeviceArray&) = delete;
  DeviceArray& operator=(const DeviceArray&) = delete;
  DeviceArray(DeviceArray&& o) noexcept : ptr_(o.ptr_), size_(o.size_) { o.ptr_ = nullptr; o.size_ = 0; }
  DeviceArray& operator=(DeviceArray&& o) noexcept {
    if (this != &o) { release(); ptr_ = o.ptr_; size_ = o.size_; o.ptr_ = nullptr; o.size_ = 0; }
    return *this;
  }

  void resize(size_t n) { resize(n, nullptr); }
  // `what` names the buffer in the error message (e.g. out of device memory).
  void resize(size_t n, const char* what) {
    if (n == size_) return;
    release();
    if (n) {
      std::string msg = "cudaMalloc of " + std::to_string(n * sizeof(T)) + " bytes";
      if (what) msg += std::string(" for ") + what;
      SVGF_CUDA_CHECK(cudaMalloc(reinterpret_cast<void**>(&ptr_), n * sizeof(T)), msg);
    }
    size_ = n;
  }
  void upload(const T* host, size_t n) {
    SVGF_CUDA_CHECK(cudaMemcpy(ptr_, host, n * sizeof(T), cudaMemcpyHostToDevice), "upload");
  }
  void download(T* host, size_t n) const {
    SVGF_CUDA_CHECK(cudaMemcpy(host, ptr_, n * sizeof(T), cudaMemcpyDeviceToHost), "download");
  }
  // Stream-ordered copies; the host memory should be pinned for them to overlap.
  void upload_async(const T* host, size_t n, cudaStream_t stream) {
    SVGF_CUDA_CHECK(cudaMemcpyAsync(ptr_, host, n * sizeof(T), cudaMemcpyHostToDevice, stream),
                    "upload");
  }
  void download_async(T* host, size_t n, cudaStream_t stream) const {
    SVGF_CUDA_CHECK(cudaMemcpyAsync(host, ptr_, n * sizeof(T), cudaMemcpyDeviceToHost, stream),
                    "download");
  }
  std::vector<T> to_host() const { std::vector<T> v(size_); download(v.data(), size_); return v; }
  T* get() const { return ptr_; }
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }

 private:
  void release() {
    if (ptr_) cudaFree(ptr_);
    ptr_ = nullptr;
    size_ = 0;
  }
  T* ptr_ = nullptr;
  size_t size_ = 0;
};

}  // namespace svgf::cuda
