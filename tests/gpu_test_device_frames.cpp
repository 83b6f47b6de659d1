// The device path (Denoiser::denoise_device, core/device_frame.h): frames whose buffers are
// already in GPU memory give the same bits as the same frames through denoise(), for every
// method, mode and layout; the work runs on the caller's stream without waiting; host and
// device frames alternate on one denoiser; the caller's inputs are never written; bad views are
// clear errors before anything is written.
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <cuda_runtime.h>

#include "gpu_test_support.h"
#include "io/sequence.h"
#include "kernels_cuda/cuda_check.h"
#include "kernels_cuda/device_array.h"
#include "pipeline/make_denoiser.h"
#include "synthetic_sequence.h"

using namespace svgf;
using namespace svgf::gpu_test;
using Catch::Matchers::Contains;

namespace {

enum class Layout {
  Planar,      // the project's own: one plane per channel
  Interleaved  // a pixel's channels together plus one spare float (NaN), rows padded
};

const char* to_string(Layout l) { return l == Layout::Planar ? "planar" : "interleaved"; }

// A frame's channels copied into device buffers in a layout, and the views of them.
class FrameOnDevice {
 public:
  FrameOnDevice(const Frame& f, Layout layout) : frame_(f.width(), f.height()), layout_(layout) {
    frame_.index = f.index;
    frame_.camera = f.camera;
    frame_.color = put(f.color);
    frame_.albedo = put(f.albedo);
    frame_.normal = put(f.normal);
    frame_.depth = put(f.depth);
    frame_.depth_gradient = put(f.depth_gradient);
    frame_.motion = put(f.motion);
    Image ids(f.width(), f.height(), 1);
    std::memcpy(ids.data().data(), f.mesh_id.data(), f.mesh_id.size() * sizeof(uint32_t));
    frame_.mesh_id = put(ids);
    if (!f.emission.empty()) frame_.emission = put(f.emission);
    if (!f.position.empty()) frame_.position = put(f.position);
    if (!f.direct.empty()) frame_.direct = put(f.direct);
    if (!f.indirect.empty()) frame_.indirect = put(f.indirect);
    // The device path never reads the mask on the host: a frame without samples leaves the
    // view empty (what the host path decides from the mask).
    if (has_samples(f)) frame_.gradient = put(f.gradient);
  }
  DeviceFrame& frame() { return frame_; }
  // Every buffer's bytes as they are now (to see that nothing was written).
  std::vector<std::vector<float>> contents() const {
    std::vector<std::vector<float>> all;
    for (const auto& b : buffers_) all.push_back(b->to_host());
    return all;
  }

  static bool has_samples(const Frame& f) {
    if (f.gradient.empty()) return false;
    for (size_t i = 0; i < f.gradient.pixel_count(); ++i)
      if (f.gradient.plane(2)[i] > 0.5f) return true;
    return false;
  }

 private:
  DeviceImageView put(const Image& im) {
    const int w = im.width(), h = im.height(), ch = im.channels();
    std::vector<float> host;
    if (layout_ == Layout::Planar) {
      host = im.data();
    } else {
      const size_t pixel = static_cast<size_t>(ch) + 1, row = pixel * w + 5;  // 20 bytes pad
      host.assign(row * h, std::numeric_limits<float>::quiet_NaN());
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int c = 0; c < ch; ++c) host[y * row + x * pixel + c] = im.at(x, y, c);
    }
    buffers_.push_back(std::make_unique<cuda::DeviceArray<float>>(host.data(), host.size()));
    const float* d = buffers_.back()->get();
    if (layout_ == Layout::Planar) return DeviceImageView::planar(d, w, h);
    return DeviceImageView::interleaved(d, w, ch + 1, ((ch + 1) * static_cast<size_t>(w) + 5) * 4);
  }

  DeviceFrame frame_;
  Layout layout_;
  std::vector<std::unique_ptr<cuda::DeviceArray<float>>> buffers_;
};

// An output buffer in a layout, filled with a sentinel, read back as an Image.
class OutputOnDevice {
 public:
  OutputOnDevice(int w, int h, Layout layout) : w_(w), h_(h), layout_(layout) {
    const size_t n = layout == Layout::Planar ? 3 * static_cast<size_t>(w) * h : row() * h;
    buffer_.resize(n);
    fill(kSentinel);
  }
  DeviceOutputView view() {
    if (layout_ == Layout::Planar) return DeviceOutputView::planar(buffer_.get(), w_, h_);
    return DeviceOutputView::interleaved(buffer_.get(), w_, 4, row() * 4);
  }
  void fill(float v) {
    std::vector<float> host(buffer_.size(), v);
    buffer_.upload(host.data(), host.size());
  }
  Image image() const {
    const std::vector<float> host = buffer_.to_host();
    Image im(w_, h_, 3);
    if (layout_ == Layout::Planar) {
      im.data() = host;
      return im;
    }
    for (int y = 0; y < h_; ++y)
      for (int x = 0; x < w_; ++x)
        for (int c = 0; c < 3; ++c) im.at(x, y, c) = host[y * row() + x * 4 + c];
    return im;
  }
  // The spare fourth floats and the row padding of the interleaved layout: still the sentinel.
  bool spares_untouched() const {
    if (layout_ == Layout::Planar) return true;
    const std::vector<float> host = buffer_.to_host();
    for (int y = 0; y < h_; ++y)
      for (size_t i = 0; i < row(); ++i) {
        const bool spare = i >= 4 * static_cast<size_t>(w_) || i % 4 == 3;
        if (spare && host[y * row() + i] != kSentinel) return false;
      }
    return true;
  }
  static constexpr float kSentinel = -12345.f;

 private:
  size_t row() const { return 4 * static_cast<size_t>(w_) + 3; }
  int w_, h_;
  Layout layout_;
  cuda::DeviceArray<float> buffer_;
};

// A sequence to run: frames on demand.
struct Frames {
  std::string name;
  int count;
  std::function<Frame(int)> frame;
};

std::vector<Frames> sequences() {
  std::vector<Frames> out;
  const std::vector<std::string> dirs = fixture_dirs();
  // Two fixtures (the first and the last by name) keep the run short; every method's math is
  // the host path's, proven on every fixture by gpu_test_pipeline.cpp. None in reduced mode
  // (the sanitizers' runs): the synthetic sequence has every kind of input.
  for (size_t k = 0; k < (options().reduced ? 0 : dirs.size());
       k += dirs.size() > 1 ? dirs.size() - 1 : 1) {
    auto seq = std::make_shared<io::Sequence>(dirs[k]);
    out.push_back({dirs[k], frames_to_use(seq->size(), 3), [seq](int i) { return seq->read(i); }});
  }
  // Synthetic, with bad samples in frame 1 and A-SVGF's gradient samples from frame 1 on.
  test::SyntheticScene scene;
  scene.width = 67;
  scene.height = 41;
  scene.square = 14;
  out.push_back({"synthetic 67x41", frames_to_use(4, 3), [scene](int k) {
                   Frame f = scene.frame(k);
                   if (k == 1) {
                     f.color.at(3, 3, 0) = std::numeric_limits<float>::quiet_NaN();
                     f.color.at(20, 10, 1) = std::numeric_limits<float>::infinity();
                     f.normal.at(30, 20, 2) = std::numeric_limits<float>::quiet_NaN();
                   }
                   f.gradient = Image(f.width(), f.height(), 3);
                   if (k > 0)
                     for (int y = 1; y < f.height(); y += kGradientStratum)
                       for (int x = 1; x < f.width(); x += kGradientStratum) {
                         f.gradient.at(x, y, 0) = scene.on_square(x, y, k) ? 0.9f : 0.5f;
                         f.gradient.at(x, y, 1) = 0.5f;
                         f.gradient.at(x, y, 2) = 1.f;
                       }
                   return f;
                 }});
  return out;
}

struct MethodSetting {
  std::string name;
  std::function<void(DenoiserConfig&)> configure;
};

std::vector<MethodSetting> method_settings() {
  return {{"svgf defaults", [](DenoiserConfig&) {}},
          {"svgf split + taa",
           [](DenoiserConfig& c) {
             c.svgf.split = SplitMode::Auto;
             c.svgf.taa = true;
           }},
          {"gaussian", [](DenoiserConfig& c) { c.method = Method::Gaussian; }},
          {"wavelet", [](DenoiserConfig& c) { c.method = Method::Wavelet; }},
          {"jbf", [](DenoiserConfig& c) { c.method = Method::Jbf; }},
          {"jbf-atrous", [](DenoiserConfig& c) { c.method = Method::JbfAtrous; }},
          {"bmfr", [](DenoiserConfig& c) { c.method = Method::Bmfr; }}};
}

std::unique_ptr<Denoiser> make(const MethodSetting& s, Mode mode) {
  DenoiserConfig c;
  c.backend = Backend::Cuda;
  c.mode = mode;
  s.configure(c);
  return make_denoiser(c);
}

// The frame with a direct/indirect split (a third of the color as indirect), for the split
// setting; positions for the methods that need them are in every source already.
Frame with_split(Frame f) {
  f.direct = f.color;
  f.indirect = Image(f.width(), f.height(), 3);
  for (size_t i = 0; i < f.color.data().size(); ++i) {
    const float c = f.color.data()[i];
    f.indirect.data()[i] = std::isfinite(c) ? c / 3.f : c;
    f.direct.data()[i] = std::isfinite(c) ? c - f.indirect.data()[i] : c;
  }
  return f;
}

void require_same_report(const FrameReport& host, const FrameReport& device,
                         const std::string& where) {
  INFO(where);
  REQUIRE(device.repairs.total() == host.repairs.total());
  REQUIRE(device.repairs.color == host.repairs.color);
  REQUIRE(device.repairs.normal == host.repairs.normal);
  REQUIRE(device.fallback_pixels == host.fallback_pixels);
  REQUIRE(device.times[kCopyInStage] > 0.0);
  REQUIRE(device.times[kCopyOutStage] > 0.0);
  REQUIRE(device.times[kUploadStage] == 0.0);
  REQUIRE(host.times[kCopyInStage] == 0.0);
}

// Bitwise (NaN compares unequal to itself, and the interleaved spares are NaN).
bool same_bytes(const std::vector<std::vector<float>>& a,
                const std::vector<std::vector<float>>& b) {
  if (a.size() != b.size()) return false;
  for (size_t k = 0; k < a.size(); ++k)
    if (a[k].size() != b[k].size() ||
        std::memcmp(a[k].data(), b[k].data(), a[k].size() * sizeof(float)) != 0)
      return false;
  return true;
}

// Spins on the GPU for about `ms` milliseconds (on an idle device: a clock loop).
__global__ void spin_kernel(long long cycles) {
  const long long start = clock64();
  while (clock64() - start < cycles) {
  }
}

void spin(cudaStream_t stream, double ms) {
  int khz = 0;
  cuda::check(cudaDeviceGetAttribute(&khz, cudaDevAttrClockRate, 0), "cudaDeviceGetAttribute");
  spin_kernel<<<1, 1, 0, stream>>>(static_cast<long long>(ms * khz));
  cuda::check(cudaGetLastError(), "spin kernel launch");
}

class StreamHandle {
 public:
  explicit StreamHandle(unsigned flags = cudaStreamNonBlocking) {
    cuda::check(cudaStreamCreateWithFlags(&s_, flags), "cudaStreamCreate");
  }
  ~StreamHandle() { cudaStreamDestroy(s_); }
  cudaStream_t get() const { return s_; }

 private:
  cudaStream_t s_ = nullptr;
};

}  // namespace

TEST_CASE("device frames: the same bits as host frames, every method, mode and layout",
          "[device-frames]") {
  StreamHandle stream;
  for (const MethodSetting& setting : method_settings())
    for (Mode mode : {Mode::Exact, Mode::Fast})
      for (Layout layout : {Layout::Planar, Layout::Interleaved})
        for (const Frames& seq : sequences()) {
          auto host = make(setting, mode);
          auto device = make(setting, mode);
          for (int k = 0; k < seq.count; ++k) {
            Frame f = seq.frame(k);
            if (setting.name == "svgf split + taa") f = with_split(std::move(f));
            const std::string where = seq.name + ", frame " + std::to_string(k) + ", " +
                                      device->description() + ", " + to_string(layout);
            Image expected;
            host->denoise(f, expected);
            FrameOnDevice in(f, layout);
            OutputOnDevice out(f.width(), f.height(), layout);
            const auto before = in.contents();
            device->denoise_device(in.frame(), out.view(), stream.get());
            cuda::check(cudaStreamSynchronize(stream.get()), "cudaStreamSynchronize");
            test::require_identical(expected, out.image(),
                                    where + ": output (host vs device path)");
            for (const std::string& name : host->debug_buffers())
              test::require_identical(host->read_buffer(name), device->read_buffer(name),
                                      where + ": " + name);
            require_same_report(host->last_report(), device->last_report(), where);
            INFO(where);
            REQUIRE(same_bytes(in.contents(), before));
            REQUIRE(out.spares_untouched());
            tally().device_frames += 1;
          }
        }
}

TEST_CASE("device frames: inputs with NaN and Inf are repaired in the denoiser's copy, never "
          "in the caller's buffers", "[device-frames]") {
  test::SyntheticScene scene;
  scene.width = 40;
  scene.height = 24;
  Frame f = scene.frame(0);
  f.color.at(1, 1, 0) = std::numeric_limits<float>::quiet_NaN();
  f.color.at(2, 1, 1) = -std::numeric_limits<float>::infinity();
  f.albedo.at(3, 1, 2) = 7.f;
  f.depth.at(4, 2, 0) = std::numeric_limits<float>::quiet_NaN();
  f.motion.at(5, 3, 1) = 1e30f;
  auto host = make(method_settings()[0], Mode::Exact);
  auto device = make(method_settings()[0], Mode::Exact);
  Image expected;
  host->denoise(f, expected);
  FrameOnDevice in(f, Layout::Planar);
  OutputOnDevice out(f.width(), f.height(), Layout::Planar);
  const auto before = in.contents();
  device->denoise_device(in.frame(), out.view(), nullptr);
  test::require_identical(expected, out.image(), "output");
  REQUIRE(same_bytes(in.contents(), before));
  const InputRepairs& r = device->last_report().repairs;
  REQUIRE(r.color == 2);
  REQUIRE(r.albedo == 1);
  REQUIRE(r.surface == 1);
  REQUIRE(r.motion == 1);
  REQUIRE(r.total() == host->last_report().repairs.total());
}

// [timing]: the sanitizers run every launch to completion before returning, so this test is
// left out of their runs (kernels_cuda/run_gpu_checks.sh).
TEST_CASE("device frames: the call returns before the work is done; the report waits",
          "[device-frames][timing]") {
  test::SyntheticScene scene;
  scene.width = 320;
  scene.height = 180;
  StreamHandle stream;
  for (Mode mode : {Mode::Exact, Mode::Fast}) {
    auto device = make(method_settings()[0], mode);
    auto host = make(method_settings()[0], mode);
    Image expected;
    // The first frame allocates the denoiser's buffers (which may wait); later ones never do.
    const Frame f0 = scene.frame(0), f1 = scene.frame(1);
    host->denoise(f0, expected);
    host->denoise(f1, expected);
    FrameOnDevice in0(f0, Layout::Planar), in1(f1, Layout::Planar);
    OutputOnDevice out(f1.width(), f1.height(), Layout::Planar);
    device->denoise_device(in0.frame(), out.view(), stream.get());
    cuda::check(cudaStreamSynchronize(stream.get()), "cudaStreamSynchronize");
    // Half a second of GPU work ahead of the frame on the caller's stream: a call that waited
    // for its frame would take that long.
    spin(stream.get(), 500.0);
    const auto start = std::chrono::steady_clock::now();
    device->denoise_device(in1.frame(), out.view(), stream.get());
    const double call_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count();
    const cudaError_t busy = cudaStreamQuery(stream.get());
    INFO(to_string(mode) << ": denoise_device returned after " << call_ms << " ms");
    REQUIRE(busy == cudaErrorNotReady);
    REQUIRE(call_ms < 250.0);
    // The report waits for the frame (not for anything enqueued after it).
    const FrameReport& r = device->last_report();
    REQUIRE(cudaStreamQuery(stream.get()) == cudaSuccess);
    REQUIRE(r.times[kCopyInStage] > 0.0);
    test::require_identical(expected, out.image(), "output after the wait");
  }
}

TEST_CASE("device frames: host and device frames alternate on one denoiser, across streams",
          "[device-frames]") {
  test::SyntheticScene scene;
  scene.width = 96;
  scene.height = 64;
  scene.square = 20;
  StreamHandle a, b(cudaStreamDefault);
  for (const MethodSetting& setting : {method_settings()[0], method_settings()[6]}) {
    auto reference = make(setting, Mode::Exact);
    auto mixed = make(setting, Mode::Exact);
    // host, stream a, stream b, host, legacy default stream, stream a
    const int path[] = {0, 1, 2, 0, 3, 1};
    for (int k = 0; k < 6; ++k) {
      const Frame f = scene.frame(k);
      const std::string where =
          setting.name + ", frame " + std::to_string(k) + ", path " + std::to_string(path[k]);
      Image expected, got;
      reference->denoise(f, expected);
      if (path[k] == 0) {
        mixed->denoise(f, got);
      } else {
        FrameOnDevice in(f, Layout::Interleaved);
        OutputOnDevice out(f.width(), f.height(), Layout::Interleaved);
        const cudaStream_t s = path[k] == 1 ? a.get() : path[k] == 2 ? b.get() : nullptr;
        mixed->denoise_device(in.frame(), out.view(), s);
        // The next frame (on another stream or the host path) orders itself after this one
        // without help; the caller's read of the output needs the frame done.
        cuda::check(cudaStreamSynchronize(s), "cudaStreamSynchronize");
        got = out.image();
      }
      test::require_identical(expected, got, where);
      tally().device_frames += 1;
    }
  }
}

TEST_CASE("device frames: bad views are clear errors, before anything is written",
          "[device-frames]") {
  test::SyntheticScene scene;
  scene.width = 32;
  scene.height = 16;
  const Frame f = scene.frame(0);
  auto device = make(method_settings()[0], Mode::Exact);
  auto reference = make(method_settings()[0], Mode::Exact);
  FrameOnDevice good(f, Layout::Planar);
  OutputOnDevice out(f.width(), f.height(), Layout::Planar);
  std::vector<float> host_memory(3 * f.color.pixel_count(), 1.f);

  const auto refused = [&](const std::function<void(DeviceFrame&, DeviceOutputView&)>& spoil,
                           const std::string& message) {
    DeviceFrame bad = good.frame();
    DeviceOutputView view = out.view();
    spoil(bad, view);
    INFO(message);
    REQUIRE_THROWS_WITH(device->denoise_device(bad, view, nullptr), Contains(message));
    cuda::check(cudaDeviceSynchronize(), "cudaDeviceSynchronize");
    const Image written = out.image();
    for (float v : written.data()) REQUIRE(v == OutputOnDevice::kSentinel);
  };
  refused([](DeviceFrame& b, DeviceOutputView&) { b.color = {}; },
          "frame 0 (device): channel 'color' has no device address");
  refused([&](DeviceFrame& b, DeviceOutputView&) {
    b.albedo = DeviceImageView::planar(host_memory.data(), 32, 16);
  }, "channel 'albedo' is not device memory");
  refused([](DeviceFrame& b, DeviceOutputView&) { b.normal.row_stride -= 4; },
          "channel 'normal': its row stride");
  refused([](DeviceFrame& b, DeviceOutputView&) { b.motion.channel_stride = 8; },
          "channel 'motion': its channel stride");
  refused([](DeviceFrame& b, DeviceOutputView&) {
    b.depth.data = static_cast<const char*>(b.depth.data) + 2;
  }, "channel 'depth': its address and strides must be multiples of 4 bytes");
  refused([](DeviceFrame&, DeviceOutputView& v) { v.data = nullptr; },
          "the output has no device address");
  refused([&](DeviceFrame&, DeviceOutputView& v) { v.data = host_memory.data(); },
          "the output is not device memory");
  refused([](DeviceFrame& b, DeviceOutputView&) { b = DeviceFrame(0, 16); }, "is empty");
  // The denoiser is unharmed: its next frame is the same as one that never saw the bad ones.
  Image expected;
  reference->denoise(f, expected);
  device->denoise_device(good.frame(), out.view(), nullptr);
  test::require_identical(expected, out.image(), "the first good frame after the refusals");
}
