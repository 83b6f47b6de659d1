#pragma once
// Support for svgf_gpu_tests: run options, fixture discovery, a tally of what was compared, and
// the "arena": one host allocation holding every plane a stage touches, named by region, which
// the StageRunner of tests/test_device.h mirrors on the device, so the CPU and the GPU run the
// same kernel struct on the same bytes and the whole arena is compared afterwards.
#include <cstdint>
#include <cstring>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <catch2/catch.hpp>

#include "core/image.h"
#include "core/tonemap.h"
#include "kernels_cpu/parallel_for.h"
#include "kernels_cuda/cuda_launch.cuh"
#include "kernels_cuda/device_array.h"
#include "methods/svgf/pipeline.h"
#include "test_device.h"
#include "gpu_test_options.h"
#include "test_support.h"

namespace svgf::gpu_test {

// Frames of a sequence to use under the current options.
inline int frames_to_use(int available, int reduced_cap) {
  int n = available;
  if (options().max_frames > 0 && n > options().max_frames) n = options().max_frames;
  if (options().reduced && n > reduced_cap) n = reduced_cap;
  return n;
}

// ---------------------------------------------------------------------------------------------

class Arena {
 public:
  struct Region {
    std::string name;
    size_t offset;  // in floats
    int channels;   // planes of width*height values
    bool bytes;     // uint8 data (tonemap output): compared byte-wise
  };

  Arena(int width, int height, int max_planes)
      : w_(width), h_(height), host_(static_cast<size_t>(max_planes) * pixels(), 0.f) {}

  int width() const { return w_; }
  int height() const { return h_; }
  size_t pixels() const { return static_cast<size_t>(w_) * static_cast<size_t>(h_); }
  std::vector<float>& host() { return host_; }
  const std::vector<float>& host() const { return host_; }
  const std::vector<Region>& regions() const { return regions_; }

  // Whole planes covering every region (and the pads before packed ones).
  int planes_used() const { return static_cast<int>((used_ + pixels() - 1) / pixels()); }
  // "region[k]" for each plane in use, for failure messages.
  std::vector<std::string> plane_names() const {
    std::vector<std::string> names;
    for (const Region& r : regions_)
      for (int k = 0; k < r.channels; ++k) names.push_back(r.name + "[" + std::to_string(k) + "]");
    return names;
  }

  // `packed`: the region holds Packed4 pixels, so it starts on 16 bytes (the arena's base is
  // 16-byte aligned on both sides; a pad of up to 3 floats before it).
  float* planes(const std::string& name, int channels, bool bytes = false, bool packed = false) {
    if (packed) used_ = (used_ + 3) / 4 * 4;
    const size_t offset = used_;
    used_ += static_cast<size_t>(channels) * pixels();
    REQUIRE(used_ <= host_.size());
    regions_.push_back(Region{name, offset, channels, bytes});
    return host_.data() + offset;
  }
  RgbView rgb(const std::string& name) {
    float* p = planes(name, 3);
    return {p, p + pixels(), p + 2 * pixels()};
  }
  IllumVarView illum_var(const std::string& name) {
    float* p = planes(name, 4);
    return {{p, p + pixels(), p + 2 * pixels()}, p + 3 * pixels()};
  }
  // Guide planes: depth, dx, dy, normal xyz, motion xy, mesh id (as raw 32-bit words).
  GuideView guides(const std::string& name) {
    float* p = planes(name, 9);
    const size_t n = pixels();
    GuideView g;
    g.width = w_;
    g.height = h_;
    g.depth = p;
    g.depth_dx = p + n;
    g.depth_dy = p + 2 * n;
    g.normal = {p + 3 * n, p + 4 * n, p + 5 * n};
    g.motion_x = p + 6 * n;
    g.motion_y = p + 7 * n;
    g.mesh_id = reinterpret_cast<const uint32_t*>(p + 8 * n);
    return g;
  }

 private:
  int w_, h_;
  std::vector<float> host_;
  std::vector<Region> regions_;
  size_t used_ = 0;
};

// Runs `run(runner)` on a CUDA exact StageRunner mirroring the arena: the kernel it runs (built
// with arena host pointers) goes over the arena on the CPU and over a device copy of the arena as
// it was before on the GPU, and every value of the two arenas must be identical (outputs, and
// inputs that must stay untouched): tests/test_device.h's StageRunner on CUDA exact.
template <class Run>
void check_on_arena(Arena& arena, const Run& run) {
  test::StageRunner runner(test::kCudaExact);
  runner.words(arena.host().data(), arena.planes_used(), arena.width(), arena.height(),
               arena.plane_names());
  run(runner);
  tally().stage_runs += 1;
  tally().stage_values += runner.values_compared();
}

// A pixel kernel over the arena's image.
template <class K>
void check_stage(Arena& arena, const K& kernel, const std::string& what,
                 cuda::LaunchShape shape = {}) {
  check_on_arena(arena, [&](test::StageRunner& r) {
    r.run(r.on_device(kernel), arena.width(), arena.height(), what, shape);
  });
}

// A block kernel (core/block_reduce.h) over `blocks` blocks.
template <class K>
void check_block_stage(Arena& arena, const K& kernel, int blocks, const std::string& what) {
  check_on_arena(arena,
                 [&](test::StageRunner& r) { r.run_blocks(r.on_device(kernel), blocks, what); });
}

}  // namespace svgf::gpu_test
