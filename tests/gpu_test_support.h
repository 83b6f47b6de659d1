#pragma once
// Support for svgf_gpu_tests: run options, fixture discovery, a tally of what was compared, and
// the "arena" that lets one kernel struct run on both sides. An arena is one host allocation
// holding every plane a stage touches, mirrored by one device allocation of the same layout;
// a kernel built with host pointers is translated to device pointers by offset, so the CPU and
// the GPU run the same struct on the same bytes (compiled by nvcc: cuda::run is the generic
// launcher), and the whole arena is compared afterwards
// (outputs, and inputs that must stay untouched).
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
#include "test_support.h"

namespace svgf::gpu_test {

struct Options {
  bool reduced = false;  // fewer sizes and frames (compute-sanitizer runs)
  int max_frames = 0;    // per fixture sequence; 0: all
  std::string fixtures_dir;
};
Options& options();

// What the run compared, printed by main at the end (docs/cuda.md quotes it).
struct Tally {
  int64_t stage_runs = 0;       // single-stage CPU vs GPU comparisons
  int64_t stage_values = 0;     // values compared bitwise in them
  int64_t frames = 0;           // pipeline frames compared bitwise (CPU vs CUDA exact)
  int64_t frame_values = 0;
  int64_t determinism_frames = 0;
  int64_t fast_frames = 0;      // fast-mode frames checked against the tolerance
  double fast_worst_relmse = 0;
  std::string fast_worst_relmse_at;
  double fast_worst_psnr_delta = 0;
  std::string fast_worst_psnr_at;
  std::vector<std::string> sequences;
};
Tally& tally();

// Fixture folders (those holding manifest.json), sorted by name.
std::vector<std::string> fixture_dirs();

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

  float* planes(const std::string& name, int channels, bool bytes = false) {
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

// The host arena and its device copy.
struct Mapper {
  const float* host;
  float* device;
};

// A kernel built with arena host pointers, with every pointer into the arena moved to the same
// offset in the device copy. Kernels are trivially copyable structs of views and parameters, so
// this works on their bytes for any kernel type (no per-kernel list to keep): each 8-byte
// aligned word holding an address inside the host arena is a pointer into it. A float or int
// field would have to spell a heap address bit for bit to be mistaken for one.
template <class K>
K to_device(const K& kernel, const Mapper& m, size_t arena_bytes) {
  static_assert(std::is_trivially_copyable_v<K>, "kernels are plain structs");
  K out = kernel;
  unsigned char* bytes = reinterpret_cast<unsigned char*>(&out);
  const auto lo = reinterpret_cast<uintptr_t>(m.host);
  for (size_t at = 0; at + sizeof(uintptr_t) <= sizeof(K); at += alignof(void*)) {
    uintptr_t word;
    std::memcpy(&word, bytes + at, sizeof word);
    if (word >= lo && word < lo + arena_bytes) {
      word = reinterpret_cast<uintptr_t>(m.device) + (word - lo);
      std::memcpy(bytes + at, &word, sizeof word);
    }
  }
  return out;
}

// Bitwise comparison of two arena images, region by region, with the first differing pixels.
inline void require_same_arena(const Arena& arena, const std::vector<float>& cpu,
                               const std::vector<float>& gpu, const std::string& what) {
  REQUIRE(cpu.size() == gpu.size());
  if (std::memcmp(cpu.data(), gpu.data(), cpu.size() * sizeof(float)) == 0) return;
  const int w = arena.width(), h = arena.height();
  const size_t n = arena.pixels();
  for (const Arena::Region& r : arena.regions()) {
    const size_t count = static_cast<size_t>(r.channels) * n;
    if (std::memcmp(cpu.data() + r.offset, gpu.data() + r.offset, count * sizeof(float)) == 0)
      continue;
    if (r.bytes) {  // interleaved RGB8 at the region's start
      const auto* a = reinterpret_cast<const uint8_t*>(cpu.data() + r.offset);
      const auto* b = reinterpret_cast<const uint8_t*>(gpu.data() + r.offset);
      size_t bad = 0;
      std::ostringstream msg;
      for (size_t i = 0; i < 3 * n; ++i)
        if (a[i] != b[i] && bad++ < 5)
          msg << "  (" << (i / 3) % w << "," << (i / 3) / w << ") channel " << i % 3 << ": "
              << int(a[i]) << " vs " << int(b[i]) << "\n";
      INFO(what << ": " << r.name << ": " << bad << " differing bytes (CPU vs CUDA)\n"
                << msg.str());
      REQUIRE(bad == 0);
      continue;
    }
    Image a(w, h, r.channels), b(w, h, r.channels);
    std::memcpy(a.data().data(), cpu.data() + r.offset, count * sizeof(float));
    std::memcpy(b.data().data(), gpu.data() + r.offset, count * sizeof(float));
    test::require_identical(a, b, what + ": " + r.name + " (CPU vs CUDA)");
  }
  FAIL(what << ": arenas differ outside every named region");
}

// Runs `kernel` (built with arena host pointers) on the CPU over the arena and on the GPU over
// a device copy of the arena as it was before, then compares the two arenas bitwise.
template <class K>
void check_stage(Arena& arena, const K& kernel, const std::string& what,
                 cuda::LaunchShape shape = {}) {
  const int w = arena.width(), h = arena.height();
  cuda::DeviceArray<float> device(arena.host().data(), arena.host().size());
  const K on_device = to_device(kernel, Mapper{arena.host().data(), device.get()},
                                arena.host().size() * sizeof(float));
  int64_t cpu_count = 0, gpu_count = 0;
  if constexpr (std::is_same_v<decltype(kernel(0, 0)), bool>) {
    cpu_count = cpu::count_pixels(w, h, kernel);
  } else {
    cpu::for_each_pixel(w, h, kernel);
  }
  gpu_count = cuda::run(on_device, w, h, shape, what.c_str());
  const std::vector<float> gpu = device.to_host();
  require_same_arena(arena, arena.host(), gpu, what);
  INFO(what);
  REQUIRE(cpu_count == gpu_count);
  tally().stage_runs += 1;
  tally().stage_values += static_cast<int64_t>(arena.host().size());
}

}  // namespace svgf::gpu_test
