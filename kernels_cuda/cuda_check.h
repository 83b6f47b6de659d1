#pragma once
// Every CUDA call and launch is checked; failures become CudaError naming what failed.
#include <stdexcept>
#include <string>

#include <cuda_runtime_api.h>

namespace svgf::cuda {

class CudaError : public std::runtime_error {
 public:
  CudaError(const std::string& what, cudaError_t e)
      : std::runtime_error(what + ": " + cudaGetErrorName(e) + " (" + cudaGetErrorString(e) + ")"),
        code_(e) {}
  cudaError_t code() const { return code_; }

 private:
  cudaError_t code_;
};

inline void check(cudaError_t e, const char* what) {
  if (e != cudaSuccess) throw CudaError(what, e);
}

}  // namespace svgf::cuda

#define SVGF_CUDA_CHECK(call, what) ::svgf::cuda::check((call), (what))
