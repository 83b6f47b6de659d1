#pragma once
// One test body for every backend and mode (as Open Image Denoise runs one test binary for any
// device). A test is written as `void body(const TestDevice&)` and registered once with
// SVGF_DEVICE_TEST: it then runs on the CPU, on CUDA in exact mode and on CUDA in fast mode.
// The CPU variant is a ctest entry of its own; the CUDA variants are hidden ([.cuda]) and run
// through the binary's single "<binary>:cuda" ctest entry, which reports Skipped (never passed)
// where there is no device or no CUDA backend.
//
// A body runs its stage kernels through a StageRunner: the same kernel struct, built from the
// runner's views, runs on the host (TBB) or on the device. On CUDA exact the runner also runs
// the kernel on the CPU and requires identical bits in every buffer it mapped, so every stage
// test is a CPU == CUDA bitwise test too. Fast mode keeps its own storage (Packed4, through
// packed() and packed_guides()) and is held to a tolerance (TestDevice::tolerance).
#include <cstdint>
#include <cstring>
#include <memory>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <catch2/catch.hpp>

#include "core/arith.h"
#include "core/denoiser.h"
#include "core/frame.h"
#include "core/image.h"
#include "core/views.h"
#include "kernels_cpu/cpu_block.h"
#include "kernels_cpu/parallel_for.h"
#include "kernels_cuda/launch_shape.h"
#if defined(SVGF_HAVE_CUDA)
#include "kernels_cuda/cuda_denoisers.h"
#include "kernels_cuda/device_array.h"
#endif
#if defined(__CUDACC__)
#include "kernels_cuda/cuda_launch.cuh"
#endif

namespace svgf::test {

// Fast mode against exact, per value: |fast - exact| <= kFastTolerance * max(|exact|, 1e-3)
// (docs/cuda.md; measured on the H100: a-trous 1.4e-5, variance 1.03e-5).
constexpr double kFastTolerance = 1e-4;

// Where a test body runs.
struct TestDevice {
  Backend backend = Backend::Cpu;
  Mode mode = Mode::Exact;

  bool cuda() const { return backend == Backend::Cuda; }
  bool fast() const { return mode == Mode::Fast; }
  std::string name() const { return cuda() ? (fast() ? "cuda-fast" : "cuda") : "cpu"; }
  // A relative tolerance written for exact arithmetic, widened to fast mode's where it runs.
  double tolerance(double exact) const {
    return fast() && exact < kFastTolerance ? kFastTolerance : exact;
  }
  // The engine settings that select this device (for denoisers made by make_denoiser).
  template <class Config>
  Config config(Config c) const {
    c.backend = backend;
    c.mode = mode;
    return c;
  }
};

inline const TestDevice kCpu{Backend::Cpu, Mode::Exact};
inline const TestDevice kCudaExact{Backend::Cuda, Mode::Exact};
inline const TestDevice kCudaFast{Backend::Cuda, Mode::Fast};

// True for the CPU, and for CUDA when the binary has the backend and a device is present;
// otherwise prints the line the "<binary>:cuda" ctest entry matches as a skip.
inline bool device_ready_or_skip(const TestDevice& d) {
  if (!d.cuda()) return true;
  std::string why;
#if defined(SVGF_HAVE_CUDA)
  if (cuda::device_available(&why)) return true;
#else
  why = "this test binary was built without the CUDA backend (target svgf_cuda absent)";
#endif
  WARN("SKIPPED: CUDA variant not run: " << why);
  return false;
}

// Runs body(arith) with the device's arithmetic policy (core/arith.h): ExactArith, or FastArith
// on CUDA fast, for stage functors templated on it alone.
template <class Body>
void with_arith(const TestDevice& d, const Body& body) {
  if (!d.fast()) {
    body(ExactArith{});
    return;
  }
#if defined(__CUDACC__)
  body(FastArith{});
#else
  FAIL("fast mode in a binary not compiled by nvcc");
#endif
}

// How many 4-byte values differ bit for bit between `want` and `got` (so -0 differs from +0
// and NaN payloads count); `first` gets the first five as "plane (x,y): CPU a CUDA b" lines.
// Values are planes of `words` each, rows of `width`.
inline size_t differing_words(const std::vector<uint32_t>& want, const std::vector<uint32_t>& got,
                              size_t words, int width, const std::vector<std::string>& plane_names,
                              std::string* first) {
  size_t bad = 0;
  std::ostringstream msg;
  for (size_t i = 0; i < want.size() && i < got.size(); ++i) {
    if (got[i] == want[i] || bad++ >= 5) continue;
    const size_t plane = i / words, at = i % words;
    float a, b;
    std::memcpy(&a, &want[i], 4);
    std::memcpy(&b, &got[i], 4);
    const std::string name =
        plane < plane_names.size() ? plane_names[plane] : "plane " + std::to_string(plane);
    msg << "  " << name << " (" << at % width << "," << at / width << "): CPU " << a << " CUDA " << b << "\n";
  }
  if (want.size() != got.size()) bad += 1;
  if (first) *first = msg.str();
  return bad;
}

// ---------------------------------------------------------------------------------------------

// The buffers of one stage run on one device. Map every host image the kernel reads or writes
// through plane()/rgb()/illum_var()/guides() (or packed()/packed_guides() in fast mode), build
// the kernel from the returned views and run() it. Each run uploads every mapped host buffer
// first and copies every one back afterwards, so the host images always hold the latest
// result and a test may change its inputs between runs. On the CPU the views are the host
// images themselves.
class StageRunner {
 public:
  explicit StageRunner(TestDevice d) : device_(d) {}
  StageRunner(const StageRunner&) = delete;
  StageRunner& operator=(const StageRunner&) = delete;

  const TestDevice& device() const { return device_; }

  float* plane(Image& im, int c = 0) { return map_image(im) + c * im.pixel_count(); }
  const float* plane(const Image& im, int c = 0) {
    return map_image(const_cast<Image&>(im)) + c * im.pixel_count();
  }
  RgbView rgb(Image& im, int first = 0) {
    return {plane(im, first), plane(im, first + 1), plane(im, first + 2)};
  }
  ConstRgbView rgb(const Image& im, int first = 0) {
    return {plane(im, first), plane(im, first + 1), plane(im, first + 2)};
  }
  // Channels 0-2 color, 3 variance.
  IllumVarView illum_var(Image& im) { return {rgb(im), plane(im, 3)}; }
  ConstIllumVarView illum_var(const Image& im) { return {rgb(im), plane(im, 3)}; }
  const uint32_t* ids(const std::vector<uint32_t>& v, int width) {
    auto* p = const_cast<uint32_t*>(v.data());
    return static_cast<const uint32_t*>(
        map({p}, v.size(), width, false, "mesh id"));
  }
  GuideView guides(const Frame& f) {
    GuideView g;
    g.width = f.width();
    g.height = f.height();
    g.depth = plane(f.depth);
    g.depth_dx = plane(f.depth_gradient, 0);
    g.depth_dy = plane(f.depth_gradient, 1);
    g.normal = rgb(f.normal);
    g.mesh_id = ids(f.mesh_id, f.width());
    g.motion_x = plane(f.motion, 0);
    g.motion_y = plane(f.motion, 1);
    return g;
  }
  // Raw host words (an arena of planes): `names` names each plane of `width` x `height`.
  float* words(float* host, int planes, int width, int height, std::vector<std::string> names) {
    const size_t n = static_cast<size_t>(width) * height;
    std::vector<void*> p;
    for (int k = 0; k < planes; ++k) p.push_back(host + k * n);
    float* out = static_cast<float*>(map(p, n, width, false, "arena"));
    maps_.back()->plane_names = std::move(names);
    return out;
  }

#if defined(__CUDACC__)
  // Fast mode's storage: a 4-channel image as one Packed4 (r, g, b, variance) per pixel.
  PackedIllumVar<Packed4> packed(Image& im) {
    return PackedIllumVar<Packed4>(static_cast<Packed4*>(map(
        {im.plane(0), im.plane(1), im.plane(2), im.plane(3)}, im.pixel_count(), im.width(),
        true, "packed")));
  }
  PackedIllumVar<const Packed4> packed(const Image& im) {
    return PackedIllumVar<const Packed4>(packed(const_cast<Image&>(im)).data);
  }
  // The guides as fast mode reads them: depth and normal packed, the gradient planes as is.
  PackedGuides packed_guides(const Frame& f) {
    PackedGuides g;
    g.width = f.width();
    g.height = f.height();
    auto* d = const_cast<Frame&>(f).depth.plane(0);
    Image& n = const_cast<Frame&>(f).normal;
    g.depth_normal_data = static_cast<const Packed4*>(
        map({d, n.plane(0), n.plane(1), n.plane(2)}, f.color.pixel_count(), f.width(), true,
            "packed guides"));
    g.depth_dx = plane(f.depth_gradient, 0);
    g.depth_dy = plane(f.depth_gradient, 1);
    return g;
  }
#endif

  // A kernel built from host pointers into mapped buffers (words()), moved to the device's
  // copies; on the CPU the kernel itself.
  template <class K>
  K on_device(const K& host_kernel) const {
#if defined(SVGF_HAVE_CUDA)
    if (device_.cuda()) return relocated(host_kernel, true);
#endif
    return host_kernel;
  }

  // Runs kernel(x, y) over width x height; a kernel returning bool returns how many pixels
  // returned true. `what` names the run in failures.
  template <class K>
  int64_t run(const K& kernel, int width, int height, const std::string& what = "stage",
              cuda::LaunchShape shape = {}) {
    if (!device_.cuda()) return run_on_host(kernel, width, height);
#if defined(__CUDACC__)
    upload();
    int64_t host_count = 0;
    if constexpr (kHostRunnable<K>) {
      if (!device_.fast()) host_count = run_on_host(to_host(kernel), width, height);
    }
    const int64_t device_count = cuda::run(kernel, width, height, shape, what.c_str());
    download(what);
    if (!device_.fast()) {
      INFO(what << ": pixels counted on the CPU and on CUDA");
      REQUIRE(host_count == device_count);
    }
    ++runs_;
    return device_count;
#else
    (void)shape;
    FAIL(what << ": CUDA stage run in a binary not compiled by nvcc");
    return 0;
#endif
  }

  // Runs a block kernel (core/block_reduce.h) over `blocks` blocks, as run() runs a pixel kernel.
  template <class K>
  void run_blocks(const K& kernel, int blocks, const std::string& what = "block stage") {
    if (!device_.cuda()) {
      cpu::for_each_block(blocks, kernel);
      return;
    }
#if defined(__CUDACC__)
    upload();
    if constexpr (kHostRunnable<K>) {
      if (!device_.fast()) cpu::for_each_block(blocks, to_host(kernel));
    }
    cuda::run_blocks(kernel, blocks, what.c_str());
    download(what);
    ++runs_;
#else
    FAIL(what << ": CUDA block stage run in a binary not compiled by nvcc");
#endif
  }

  int runs() const { return runs_; }            // CUDA runs compared (or, fast, fetched)
  int64_t values_compared() const { return compared_; }

 private:
  // Kernels built on FastArith exist on the device only.
  template <class K, class = void>
  struct UsesFastArith : std::false_type {};
#if defined(__CUDACC__)
  template <class K>
  struct UsesFastArith<K, std::void_t<typename K::Arith>>
      : std::is_same<typename K::Arith, FastArith> {};
#endif
  template <class K>
  static constexpr bool kHostRunnable = !UsesFastArith<K>::value;

  template <class K>
  static int64_t run_on_host(const K& kernel, int width, int height) {
    if constexpr (std::is_same_v<decltype(kernel(0, 0)), bool>) {
      return cpu::count_pixels(width, height, kernel);
    } else {
      cpu::for_each_pixel(width, height, kernel);
      return 0;
    }
  }

  // One mapped host buffer: `planes` host planes of `words` 4-byte values each, stored on the
  // device one plane after another, or interleaved (Packed4) when `interleaved`.
  struct Mapping {
    std::vector<void*> planes;
    size_t words = 0;
    int width = 1;
    bool interleaved = false;
    std::string name;
    std::vector<std::string> plane_names;
#if defined(SVGF_HAVE_CUDA)
    cuda::DeviceArray<uint32_t> device;
#endif
    size_t bytes() const { return planes.size() * words * 4; }
  };

  void* map(const std::vector<void*>& planes, size_t words, int width, bool interleaved,
            const char* name) {
    if (!device_.cuda()) return planes[0];
#if defined(SVGF_HAVE_CUDA)
    for (const auto& m : maps_)
      if (m->planes == planes && m->interleaved == interleaved) return m->device.get();
    for (const auto& m : maps_)  // one host plane, one device copy
      for (void* p : m->planes)
        for (void* q : planes)
          if (p == q) FAIL("a host plane of '" << name << "' is mapped twice in two layouts");
    auto m = std::make_unique<Mapping>();
    m->planes = planes;
    m->words = words;
    m->width = width;
    m->interleaved = interleaved;
    m->name = name;
    m->device.resize(planes.size() * words, name);
    maps_.push_back(std::move(m));
    return maps_.back()->device.get();
#else
    (void)words, (void)width, (void)interleaved;
    FAIL("CUDA buffer '" << name << "' mapped in a build without the CUDA backend");
    return nullptr;
#endif
  }
  float* map_image(Image& im) {
    std::vector<void*> p;
    for (int c = 0; c < im.channels(); ++c) p.push_back(im.plane(c));
    return static_cast<float*>(map(p, im.pixel_count(), im.width(), false, "image"));
  }

#if defined(SVGF_HAVE_CUDA)
  // The host layout of a mapping as the device stores it, and back.
  static std::vector<uint32_t> gather(const Mapping& m) {
    std::vector<uint32_t> v(m.planes.size() * m.words);
    const size_t k = m.planes.size();
    for (size_t p = 0; p < k; ++p) {
      const auto* src = static_cast<const uint32_t*>(m.planes[p]);
      if (!m.interleaved) std::memcpy(v.data() + p * m.words, src, m.words * 4);
      else
        for (size_t i = 0; i < m.words; ++i) v[i * k + p] = src[i];
    }
    return v;
  }
  static void scatter(const Mapping& m, const std::vector<uint32_t>& v) {
    const size_t k = m.planes.size();
    for (size_t p = 0; p < k; ++p) {
      auto* dst = static_cast<uint32_t*>(m.planes[p]);
      if (!m.interleaved) std::memcpy(dst, v.data() + p * m.words, m.words * 4);
      else
        for (size_t i = 0; i < m.words; ++i) dst[i] = v[i * k + p];
    }
  }

  void upload() {
    for (const auto& m : maps_) {
      const std::vector<uint32_t> v = gather(*m);
      m->device.upload(v.data(), v.size());
    }
  }

  // The device's results into the host images. CUDA exact: the host images hold the CPU's
  // results of the same run, and every value must be identical.
  void download(const std::string& what) {
    for (const auto& m : maps_) {
      const std::vector<uint32_t> got = m->device.to_host();
      if (!device_.fast()) {
        const std::vector<uint32_t> want = gather(*m);
        compared_ += static_cast<int64_t>(want.size());
        std::string first;
        const size_t bad =
            differing_words(want, got, m->words, m->width, m->plane_names, &first);
        INFO(what << ": " << m->name << ": " << bad << " values differ (CPU vs CUDA exact)\n"
                  << first);
        REQUIRE(bad == 0);
      }
      scatter(*m, got);
    }
  }

  // The kernel with every address inside a mapped (plane-layout) buffer moved to the other
  // side: a device address to the host plane it mirrors, or a host address to its device copy.
  // Kernels are trivially copyable structs of views and parameters, so this works on their
  // bytes for any kernel type (no list of kernel types anywhere): each pointer-aligned word
  // holding an address inside a mapped buffer is a pointer into it. A float or int field would
  // have to spell that address bit for bit to be mistaken for one.
  template <class K>
  K relocated(const K& kernel, bool to_device) const {
    static_assert(std::is_trivially_copyable_v<K>, "kernels are plain structs");
    K out = kernel;
    auto* bytes = reinterpret_cast<unsigned char*>(&out);
    for (size_t at = 0; at + sizeof(uintptr_t) <= sizeof(K); at += alignof(void*)) {
      uintptr_t word;
      std::memcpy(&word, bytes + at, sizeof word);
      const uintptr_t moved = relocated_address(word, to_device);
      std::memcpy(bytes + at, &moved, sizeof moved);
    }
    return out;
  }
  uintptr_t relocated_address(uintptr_t word, bool to_device) const {
    for (const auto& m : maps_) {
      const size_t plane_bytes = m->words * 4;
      const auto device = reinterpret_cast<uintptr_t>(m->device.get());
      for (size_t p = 0; p < m->planes.size(); ++p) {
        const auto host = reinterpret_cast<uintptr_t>(m->planes[p]);
        const uintptr_t from = to_device ? host : device + p * plane_bytes;
        const uintptr_t to = to_device ? device + p * plane_bytes : host;
        if (word < from || word >= from + plane_bytes) continue;
        REQUIRE_FALSE(m->interleaved);  // packed buffers are built through packed()
        return to + (word - from);
      }
    }
    return word;
  }
  template <class K>
  K to_host(const K& kernel) const { return relocated(kernel, false); }
#endif

  TestDevice device_;
  std::vector<std::unique_ptr<Mapping>> maps_;
  int runs_ = 0;
  int64_t compared_ = 0;
};

}  // namespace svgf::test

// Registers `void function(const svgf::test::TestDevice&)` for the CPU, CUDA exact and CUDA
// fast. The CUDA variants are hidden ([.cuda]) and run through "<binary>:cuda".
#define SVGF_DEVICE_TEST(name, tags, function)                                   \
  SVGF_BACKEND_TEST(name, tags, function)                                        \
  TEST_CASE(name " - cuda-fast", "[.cuda][fast]" tags) {                         \
    if (::svgf::test::device_ready_or_skip(::svgf::test::kCudaFast))             \
      function(::svgf::test::kCudaFast);                                         \
  }

// For stages whose fast mode runs the exact kernel (demodulate, reprojection: fast mode makes
// exact mode's history decisions): the CPU and CUDA exact only.
#define SVGF_BACKEND_TEST(name, tags, function)                                  \
  TEST_CASE(name " - cpu", "[cpu]" tags) { function(::svgf::test::kCpu); }       \
  TEST_CASE(name " - cuda", "[.cuda]" tags) {                                    \
    if (::svgf::test::device_ready_or_skip(::svgf::test::kCudaExact))            \
      function(::svgf::test::kCudaExact);                                        \
  }
