// The device path's host side, which needs no GPU (core/device_frame.h): the layouts' strides,
// the layout rules and their messages, and a CPU denoiser's refusal. The device path itself is
// tested on the GPU (tests/gpu_test_device_frames.cpp).
#include <cstdint>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/device_frame.h"
#include "pipeline/make_denoiser.h"

using namespace svgf;
using Catch::Matchers::Contains;

namespace {

// A frame of 8x4 whose views point into `memory` (never read here), planar.
DeviceFrame planar_frame(std::vector<float>& memory) {
  memory.assign(3 * 32 * 16, 0.f);
  const float* p = memory.data();
  DeviceFrame f(8, 4);
  f.index = 7;
  f.color = f.albedo = f.normal = f.position = DeviceImageView::planar(p, 8, 4);
  f.depth = f.mesh_id = DeviceImageView::planar(p, 8, 4);
  f.depth_gradient = f.motion = DeviceImageView::planar(p, 8, 4);
  return f;
}

}  // namespace

TEST_CASE("device frame views: planar and interleaved strides", "[device-frame]") {
  float dummy[4];
  const DeviceImageView planar = DeviceImageView::planar(dummy, 10, 6);
  REQUIRE(planar.pixel_stride == 4);
  REQUIRE(planar.row_stride == 40);
  REQUIRE(planar.channel_stride == 240);
  const DeviceImageView rgba = DeviceImageView::interleaved(dummy, 10, 4);
  REQUIRE(rgba.pixel_stride == 16);
  REQUIRE(rgba.row_stride == 160);
  REQUIRE(rgba.channel_stride == 4);
  const DeviceImageView pitched = DeviceImageView::interleaved(dummy, 10, 3, 512);
  REQUIRE(pitched.row_stride == 512);
  const DeviceOutputView out = DeviceOutputView::interleaved(dummy, 10, 4, 256);
  REQUIRE(out.pixel_stride == 16);
  REQUIRE(out.as_input().row_stride == 256);
  for (const DeviceImageView& v : {planar, rgba, pitched})
    REQUIRE(device_view_problem(v, 10, 6, 3).empty());
}

TEST_CASE("device frame views: what the layout rules refuse, and how they say it",
          "[device-frame]") {
  float memory[64];
  DeviceImageView v = DeviceImageView::interleaved(memory, 10, 4);
  SECTION("rows overlapping") {
    v.row_stride = 156;
    REQUIRE_THAT(device_view_problem(v, 10, 6, 3),
                 Contains("row stride (156 bytes) is less than a row of 10 pixels of 16 bytes"));
  }
  SECTION("channels past the pixel, not whole planes") {
    v.channel_stride = 8;  // 3 channels need 4 + 2 * 8 = 20 bytes of a 16-byte pixel
    REQUIRE_THAT(device_view_problem(v, 10, 6, 3), Contains("channel stride (8 bytes)"));
    REQUIRE(device_view_problem(v, 10, 6, 2).empty());  // 12 bytes fit
  }
  SECTION("misaligned address or stride") {
    v.data = reinterpret_cast<const char*>(memory) + 1;
    REQUIRE_THAT(device_view_problem(v, 10, 6, 3), Contains("multiples of 4 bytes"));
    v.data = memory;
    v.row_stride = 162;
    REQUIRE_THAT(device_view_problem(v, 10, 6, 3), Contains("multiples of 4 bytes"));
  }
  SECTION("a pixel narrower than a value") {
    v.pixel_stride = 0;
    REQUIRE_THAT(device_view_problem(v, 10, 6, 1), Contains("pixel stride is below 4 bytes"));
  }
  SECTION("planes overlapping") {
    DeviceImageView p = DeviceImageView::planar(memory, 10, 6);
    p.channel_stride -= 4;
    REQUIRE_THAT(device_view_problem(p, 10, 6, 3), Contains("nor a whole plane of 240 bytes"));
  }
}

TEST_CASE("device frames: missing channels and a missing output are named with the frame",
          "[device-frame]") {
  std::vector<float> memory;
  DeviceFrame f = planar_frame(memory);
  const DeviceOutputView out = DeviceOutputView::planar(memory.data(), 8, 4);
  check_device_frame(f, out);  // complete: no error
  const auto refused = [&](DeviceFrame bad, const DeviceOutputView& o, const std::string& what) {
    REQUIRE_THROWS_WITH(check_device_frame(bad, o), Contains(what));
  };
  DeviceFrame g = f;
  g.mesh_id = {};
  refused(g, out, "frame 7 (device): channel 'mesh_id' has no device address");
  g = f;
  g.motion.row_stride = 4;
  refused(g, out, "frame 7 (device): channel 'motion': its row stride (4 bytes)");
  g = f;
  g.emission = DeviceImageView::interleaved(memory.data(), 8, 2);  // 3 channels in 8 bytes
  refused(g, out, "channel 'emission': its channel stride");
  refused(f, DeviceOutputView{}, "frame 7 (device): the output has no device address");
  DeviceOutputView narrow = out;
  narrow.pixel_stride = 2;
  refused(f, narrow, "the output: its address and strides must be multiples of 4 bytes");
  refused(DeviceFrame(0, 4), out, "size 0x4 is empty");
}

TEST_CASE("device frames: a CPU denoiser refuses them, saying why", "[device-frame]") {
  std::vector<float> memory;
  const DeviceFrame f = planar_frame(memory);
  for (Method m : {Method::Svgf, Method::Gaussian, Method::Wavelet, Method::Jbf,
                   Method::JbfAtrous, Method::Bmfr}) {
    DenoiserConfig c;
    c.method = m;
    c.backend = Backend::Cpu;
    auto d = make_denoiser(c);
    try {
      d->denoise_device(f, DeviceOutputView::planar(memory.data(), 8, 4), nullptr);
      FAIL("no error");
    } catch (const std::logic_error& e) {
      REQUIRE_THAT(e.what(), Contains("runs on the CPU") && Contains("Backend::Cuda"));
      REQUIRE_THAT(e.what(), Contains(d->description()));
    }
  }
}
