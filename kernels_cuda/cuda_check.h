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

// Clears the runtime's last-error slot before throwing, so a non-sticky error (a refused
// allocation, a bad launch configuration) is not reported again by the next unrelated check.
inline void check(cudaError_t e, const char* what) {
  if (e != cudaSuccess) {
    (void)cudaGetLastError();
    throw CudaError(what, e);
  }
}
inline void check(cudaError_t e, const std::string& what) { check(e, what.c_str()); }

}  // namespace svgf::cuda

#define SVGF_CUDA_CHECK(call, what) ::svgf::cuda::check((call), (what))
