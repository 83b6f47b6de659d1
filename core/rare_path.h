#pragma once
// Pixel kernels with a cheap common case and an expensive rare one (SVGF's variance estimate:
// most pixels pass their temporal variance through, young histories gather a 7x7 neighbourhood).
// Such a kernel offers, besides operator()(x, y):
//
//   bool common_path(int x, int y) const;  // does the pixel's work and returns true, or does
//                                          // nothing and returns false
//   void rare_path(int x, int y) const;    // the pixel's work where common_path returned false
//
// and operator() must be exactly `if (!common_path(x, y)) rare_path(x, y);`. The CPU runs
// operator(). The CUDA launcher (kernels_cuda/cuda_launch.cuh) runs common_path on every thread of
// a block, collects the block's rare pixels and runs rare_path on as few threads as there are
// rare pixels: the expensive path then occupies ceil(rare / 32) warps of the block instead of
// every warp holding one rare pixel. Each pixel's result is computed by the same code either
// way, so exact mode keeps its bits (the order the rare pixels are taken in decides nothing).
#include <type_traits>
#include <utility>

namespace svgf {

template <class K, class = void>
struct HasRarePath : std::false_type {};
template <class K>
struct HasRarePath<K, std::void_t<decltype(std::declval<const K&>().rare_path(0, 0)),
                                  decltype(bool{std::declval<const K&>().common_path(0, 0)})>>
    : std::true_type {};

}  // namespace svgf
