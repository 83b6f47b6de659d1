// svgf import: the per-buffer readers (PFM, Radiance .hdr, EXR), the GAMES202 layout with
// motion derived from matrices, bad input named by frame, buffer and file, and a round trip
// through a committed fixture.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "app/denoise_command.h"
#include "app/import_command.h"
#include "app/import_derive.h"
#include "app/import_frame.h"
#include "app/usage_error.h"
#include "io/exr_frame.h"
#include "io/games202_matrices.h"
#include "io/image_file.h"
#include "io/sequence.h"
#include "app_test_support.h"
#include "test_support.h"

namespace fs = std::filesystem;
using namespace svgf;

namespace {

void write_bytes(const fs::path& p, const std::string& bytes) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << bytes;
}

// A PFM file of `im` (1 or 3 channels), rows bottom to top, in either byte order.
std::string pfm_bytes(const Image& im, bool little) {
  std::string s = std::string(im.channels() == 3 ? "PF" : "Pf") + "\n" + std::to_string(im.width()) +
                  " " + std::to_string(im.height()) + "\n" + (little ? "-1.0" : "1.0") + "\n";
  for (int y = im.height() - 1; y >= 0; --y)
    for (int x = 0; x < im.width(); ++x)
      for (int c = 0; c < im.channels(); ++c) {
        uint32_t bits;
        const float v = im.at(x, y, c);
        std::memcpy(&bits, &v, 4);
        for (int b = 0; b < 4; ++b) s += static_cast<char>(bits >> (8 * (little ? b : 3 - b)));
      }
  return s;
}

// Radiance RGBE of a float triple (the usual frexp encoding).
std::array<unsigned char, 4> to_rgbe(float r, float g, float b) {
  const float v = std::max(r, std::max(g, b));
  if (v < 1e-32f) return {0, 0, 0, 0};
  int e;
  const float scale = std::frexp(v, &e) * 256.f / v;
  return {static_cast<unsigned char>(r * scale), static_cast<unsigned char>(g * scale),
          static_cast<unsigned char>(b * scale), static_cast<unsigned char>(e + 128)};
}

// An .hdr file of `im`, scanlines flat or new-style RLE (runs for repeats, literals otherwise).
std::string hdr_bytes(const Image& im, bool rle) {
  std::string s = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(im.height()) +
                  " +X " + std::to_string(im.width()) + "\n";
  const int w = im.width();
  for (int y = 0; y < im.height(); ++y) {
    std::vector<std::array<unsigned char, 4>> row;
    for (int x = 0; x < w; ++x) row.push_back(to_rgbe(im.at(x, y, 0), im.at(x, y, 1), im.at(x, y, 2)));
    if (!rle) {
      for (const auto& p : row) s.append(reinterpret_cast<const char*>(p.data()), 4);
      continue;
    }
    s += {2, 2, static_cast<char>(w >> 8), static_cast<char>(w & 0xff)};
    for (int c = 0; c < 4; ++c) {
      int x = 0;
      while (x < w) {
        int run = 1;
        while (x + run < w && run < 127 && row[x + run][c] == row[x][c]) ++run;
        if (run >= 3) {
          s += static_cast<char>(128 + run);
          s += static_cast<char>(row[x][c]);
          x += run;
          continue;
        }
        int lit = 1;  // up to the next run of 3
        while (x + lit < w && lit < 128 &&
               !(x + lit + 2 < w && row[x + lit][c] == row[x + lit + 1][c] &&
                 row[x + lit][c] == row[x + lit + 2][c]))
          ++lit;
        s += static_cast<char>(lit);
        for (int k = 0; k < lit; ++k) s += static_cast<char>(row[x + k][c]);
        x += lit;
      }
    }
  }
  return s;
}

// The value the reader gives for an RGBE-encoded float (Radiance: (m + 0.5) * 2^(e - 136)).
float rgbe_decoded(float v, float max_of_pixel) {
  const auto q = to_rgbe(v, 0.f, max_of_pixel);
  const int m = q[0];
  return q[3] == 0 ? 0.f : static_cast<float>(std::ldexp(m + 0.5, q[3] - 136));
}

Image ramp(int w, int h, int channels, float lo, float step) {
  Image im(w, h, channels);
  for (int c = 0; c < channels; ++c)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) im.at(x, y, c) = lo + step * float((c * h + y) * w + x);
  return im;
}

bool same_bits(const Image& a, const Image& b) {
  return a.width() == b.width() && a.height() == b.height() && a.channels() == b.channels() &&
         std::memcmp(a.data().data(), b.data().data(), a.data().size() * sizeof(float)) == 0;
}

// Runs svgf import and returns the IoError text ("exit N" when it threw none).
std::string import_error(const std::vector<std::string>& args) {
  try {
    return "exit " + std::to_string(app::import_command(args));
  } catch (const io::IoError& e) {
    return e.what();
  }
}

int denoise_cpu(const fs::path& seq, const fs::path& out) {
  return app::denoise_command({seq.string(), out.string(), "--backend", "cpu", "--no-preview"});
}

}  // namespace

TEST_CASE("import readers: PFM byte orders and row order, .hdr flat and RLE", "[app][import]") {
  const fs::path dir = test::scratch("import_readers");
  const Image rgb = ramp(9, 4, 3, -1.5f, 0.25f), gray = ramp(5, 3, 1, 0.125f, 1.f);
  write_bytes(dir / "le.pfm", pfm_bytes(rgb, true));
  write_bytes(dir / "be.PFM", pfm_bytes(gray, false));
  REQUIRE(same_bits(io::read_image((dir / "le.pfm").string()), rgb));
  REQUIRE(same_bits(io::read_image((dir / "be.PFM").string()), gray));

  Image hdr = ramp(12, 3, 3, 0.01f, 0.37f);
  for (int x = 0; x < 6; ++x)  // a run of equal pixels, so the RLE has runs and literals
    for (int c = 0; c < 3; ++c) hdr.at(x, 1, c) = 2.5f;
  write_bytes(dir / "flat.hdr", hdr_bytes(hdr, false));
  write_bytes(dir / "rle.hdr", hdr_bytes(hdr, true));
  const Image flat = io::read_image((dir / "flat.hdr").string());
  const Image rle = io::read_image((dir / "rle.hdr").string());
  REQUIRE(same_bits(flat, rle));
  REQUIRE(hdr_bytes(hdr, true).size() < hdr_bytes(hdr, false).size());
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 12; ++x) {
      const float mx = std::max(hdr.at(x, y, 0), std::max(hdr.at(x, y, 1), hdr.at(x, y, 2)));
      REQUIRE(flat.at(x, y, 0) == rgbe_decoded(hdr.at(x, y, 0), mx));  // the known answer
      REQUIRE(std::fabs(flat.at(x, y, 2) - hdr.at(x, y, 2)) <= hdr.at(x, y, 2) / 128.f);
    }
  // EXPOSURE is divided out.
  std::string exposed = hdr_bytes(hdr, false);
  exposed.insert(exposed.find("\n\n") + 1, "EXPOSURE=2\n");
  write_bytes(dir / "exposed.hdr", exposed);
  REQUIRE(io::read_image((dir / "exposed.hdr").string()).at(3, 2, 1) == flat.at(3, 2, 1) / 2.f);
  fs::remove_all(dir);
}

TEST_CASE("import: a plain color/albedo/normal .hdr frame without depth imports and denoises",
          "[app][import]") {
  const fs::path in = test::scratch("import_plain_in"), out = test::scratch("import_plain_out"),
                 res = test::scratch("import_plain_res");
  const int w = 24, h = 16;
  Image color = ramp(w, h, 3, 0.05f, 0.001f), albedo(w, h, 3, 0.5f), normal(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) normal.at(x, y, 2) = x < 20 ? 1.f : 0.f;  // 4 background columns
  write_bytes(in / "color.hdr", hdr_bytes(color, true));
  write_bytes(in / "albedo.hdr", hdr_bytes(albedo, false));
  write_bytes(in / "normal.hdr", hdr_bytes(normal, true));
  REQUIRE(app::import_command({in.string(), out.string(), "--color", "color.hdr", "--albedo",
                               "albedo.hdr", "--normal", "normal.hdr"}) == 0);
  const io::Sequence seq(out.string());
  REQUIRE(seq.size() == 1);
  const Frame f = seq.read(0);
  REQUIRE(f.width() == w);
  REQUIRE(same_bits(f.color, io::read_image((in / "color.hdr").string())));
  REQUIRE(f.depth.at(3, 5, 0) == 1.f);
  REQUIRE(f.depth.at(21, 5, 0) == 0.f);
  REQUIRE(f.mesh_id[5 * w + 3] == 1u);
  REQUIRE(f.mesh_id[5 * w + 21] == 0u);
  REQUIRE(f.depth_gradient.at(3, 5, 0) == 0.f);
  const auto report = test::read_json(out / "import.json");
  REQUIRE(report["warnings"].size() == 1);  // one frame: no motion warning
  REQUIRE(report["warnings"][0].get<std::string>().find("no depth") == 0);
  REQUIRE(report["sources"]["albedo"] == "file");
  REQUIRE(denoise_cpu(out, res) == 0);
  REQUIRE(fs::exists(res / "frame_0000.exr"));
  for (const auto& p : {in, out, res}) test::remove_output(p);
}

TEST_CASE("import: a PFM sequence with {N:4}, depth gradient derived, frames discovered",
          "[app][import]") {
  const fs::path in = test::scratch("import_pfm_in"), out = test::scratch("import_pfm_out");
  const int w = 8, h = 6;
  for (int n : {3, 4, 5}) {
    char num[8];
    std::snprintf(num, sizeof num, "%04d", n);
    Image depth(w, h, 1);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) depth.at(x, y, 0) = 2.f + 0.5f * x + 0.25f * y * y;
    Image normal(w, h, 3, 0.f);
    for (size_t i = 0; i < normal.pixel_count(); ++i) normal.plane(1)[i] = 1.f;
    write_bytes(in / (std::string("c") + num + ".pfm"), pfm_bytes(ramp(w, h, 3, 0.1f * n, 0.01f), n % 2));
    write_bytes(in / (std::string("n") + num + ".pfm"), pfm_bytes(normal, true));
    write_bytes(in / (std::string("d") + num + ".pfm"), pfm_bytes(depth, false));
  }
  write_bytes(in / "c12.pfm", "not a frame: the width differs from {N:4}");
  REQUIRE(app::import_command({in.string(), out.string(), "--color", "c{N:4}.pfm", "--normal",
                               "n{N:4}.pfm", "--depth", "d{N:4}.pfm"}) == 0);
  const io::Sequence seq(out.string());
  REQUIRE(seq.size() == 3);
  const Frame f = seq.read(1);
  REQUIRE(f.index == 4);
  REQUIRE(same_bits(f.color, ramp(w, h, 3, 0.4f, 0.01f)));
  // Linear in x: central = one-sided = 0.5. Quadratic in y: central 0.5 * y, one-sided at edges.
  REQUIRE(f.depth_gradient.at(3, 2, 0) == 0.5f);
  REQUIRE(f.depth_gradient.at(0, 2, 0) == 0.5f);
  REQUIRE(f.depth_gradient.at(3, 2, 1) == 1.0f);   // (d(3) - d(1)) / 2 = 0.25 * (9 - 1) / 2
  REQUIRE(f.depth_gradient.at(3, 0, 1) == 0.25f);  // forward only: d(1) - d(0)
  const auto report = test::read_json(out / "import.json");
  REQUIRE(report["frames"] == nlohmann::json({3, 4, 5}));
  bool albedo_warned = false, motion_warned = false;
  for (const auto& wtext : report["warnings"]) {
    albedo_warned |= wtext.get<std::string>().find("no albedo") == 0;
    motion_warned |= wtext.get<std::string>().find("no motion") == 0;
  }
  REQUIRE(albedo_warned);
  REQUIRE(motion_warned);
  for (const auto& p : {in, out}) test::remove_output(p);
}

namespace {

// A GAMES202-style scene: a wall (object 0) at z = -5 filling the view, a square (object 1) on
// it sliding +x 0.25 a frame; the camera at (0.5 k, 0, 0) looking down -z, tan(half fov) 0.5.
constexpr int kW = 32, kH = 24;
constexpr double kTanX = 0.5, kTanY = 0.5 * kH / kW;

io::Matrix4 translation(double tx) { return {1, 0, 0, tx, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }

io::SceneMatrices games202_matrices(int k) {
  io::SceneMatrices m;
  m.object_to_world = {translation(0), translation(0.25 * k)};
  m.world_to_camera = translation(-0.5 * k);
  // camera -> screen: x_s = (x / (-z tan_x) + 1) W / 2, y_s = (1 - y / (-z tan_y)) H / 2.
  const io::Matrix4 projection = {kW / (2 * kTanX), 0, -kW / 2.0, 0,
                                  0, -kH / (2 * kTanY), -kH / 2.0, 0,
                                  0, 0, 0, 1,
                                  0, 0, -1, 0};
  m.world_to_screen = app::multiply(projection, m.world_to_camera);
  return m;
}

bool on_square(double wx, double wy, int k) {
  const double left = -0.5 + 0.25 * k;
  return wx >= left && wx < left + 1.0 && wy >= -0.5 && wy < 0.5;
}

void write_games202_frame(const fs::path& in, int k) {
  Image beauty(kW, kH, 3), normal(kW, kH, 3), position(kW, kH, 3), depth(kW, kH, 1), id(kW, kH, 1);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const double ndc_x = 2.0 * (x + 0.5) / kW - 1.0, ndc_y = 1.0 - 2.0 * (y + 0.5) / kH;
      const double wx = 0.5 * k + 5.0 * ndc_x * kTanX, wy = 5.0 * ndc_y * kTanY;
      const bool sq = on_square(wx, wy, k);
      for (int c = 0; c < 3; ++c) beauty.at(x, y, c) = sq ? 0.8f : 0.3f + 0.01f * float(x);
      normal.at(x, y, 2) = 1.f;
      position.at(x, y, 0) = float(wx);
      position.at(x, y, 1) = float(wy);
      position.at(x, y, 2) = -5.f;
      depth.at(x, y, 0) = 5.f;
      id.at(x, y, 0) = sq ? 1.f : 0.f;
    }
  id.at(0, 0, 0) = -1.f;  // one background pixel
  const std::string n = std::to_string(k);
  fs::create_directories(in);
  io::write_image_exr((in / ("beauty_" + n + ".exr")).string(), beauty);
  io::write_image_exr((in / ("normal_" + n + ".exr")).string(), normal);
  io::write_image_exr((in / ("position_" + n + ".exr")).string(), position);
  io::write_image_exr((in / ("depth_" + n + ".exr")).string(), depth);
  io::write_image_exr((in / ("ID_" + n + ".exr")).string(), id);
  io::write_games202_matrices((in / ("matrix_" + n + ".mat")).string(), games202_matrices(k));
}

}  // namespace

TEST_CASE("import --preset games202: motion from object and camera matrices, known answer",
          "[app][import]") {
  const fs::path in = test::scratch("import_g202_in"), out = test::scratch("import_g202_out"),
                 out2 = test::scratch("import_g202_out2"), res = test::scratch("import_g202_res");
  for (int k = 0; k < 3; ++k) write_games202_frame(in, k);
  REQUIRE(app::import_command({in.string(), out.string(), "--preset", "games202"}) == 0);
  const io::Sequence seq(out.string());
  REQUIRE(seq.size() == 3);
  const Frame f = seq.read(2);
  // A wall point: the camera moved +0.5 at depth 5, so it was 0.5 / (5 tan_x) * W / 2 = 3.2
  // pixels to the right; a square point also moved +0.25 with its object: 1.6 pixels.
  int wall = 0, square = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const size_t i = static_cast<size_t>(y) * kW + x;
      if (x == 0 && y == 0) {
        REQUIRE(f.mesh_id[i] == 0u);
        REQUIRE(f.depth.plane(0)[i] == 0.f);
        REQUIRE(f.motion.plane(0)[i] == 0.f);
        continue;
      }
      const bool sq = f.mesh_id[i] == 2u;
      REQUIRE(f.mesh_id[i] == (sq ? 2u : 1u));
      REQUIRE(f.motion.plane(0)[i] == Approx(sq ? 1.6 : 3.2).margin(1e-4));
      REQUIRE(f.motion.plane(1)[i] == Approx(0.0).margin(1e-4));
      (sq ? square : wall) += 1;
    }
  REQUIRE(square > 10);
  REQUIRE(wall > 10);
  REQUIRE(seq.read(0).motion.at(5, 5, 0) == 0.f);  // the first frame has no previous one
  REQUIRE(f.camera.world_to_view[3] == -1.f);       // the camera's translation, as given
  const auto report = test::read_json(out / "import.json");
  REQUIRE(report["sources"]["motion"] == "derived from the object and camera matrices");
  REQUIRE(report["warnings"][0].get<std::string>().find("no albedo") == 0);

  // Without the position buffer, positions are reconstructed from depth: the same motion.
  REQUIRE(app::import_command({in.string(), out2.string(), "--color", "beauty_{N}.exr", "--normal",
                               "normal_{N}.exr", "--depth", "depth_{N}.exr", "--id", "ID_{N}.exr",
                               "--matrices", "matrix_{N}.mat", "--frames", "1..2"}) == 0);
  const Frame g = io::Sequence(out2.string()).read(1);
  REQUIRE(g.index == 2);
  for (size_t i = 1; i < g.motion.pixel_count(); ++i) {
    REQUIRE(g.motion.plane(0)[i] == Approx(f.motion.plane(0)[i]).margin(1e-4));
    REQUIRE(g.motion.plane(1)[i] == Approx(f.motion.plane(1)[i]).margin(1e-4));
  }
  REQUIRE(denoise_cpu(out, res) == 0);
  REQUIRE(test::read_json(res / "report.json")["frames"].size() == 3);
  for (const auto& p : {in, out, out2, res}) test::remove_output(p);
}

TEST_CASE("import: bad input is named by frame, buffer and file, and nothing is written",
          "[app][import]") {
  const fs::path in = test::scratch("import_bad_in"), out = test::scratch("import_bad_out");
  const Image rgb = ramp(6, 4, 3, 0.1f, 0.1f), normal(6, 4, 3, 1.f);
  for (int n : {0, 1}) {
    write_bytes(in / ("c" + std::to_string(n) + ".pfm"), pfm_bytes(rgb, true));
    write_bytes(in / ("n" + std::to_string(n) + ".pfm"), pfm_bytes(normal, true));
  }
  const std::vector<std::string> base = {in.string(), out.string(), "--color", "c{N}.pfm",
                                         "--normal", "n{N}.pfm"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = base;
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  // A missing file in the second frame: named, and the first frame was not written either.
  write_bytes(in / "a0.pfm", pfm_bytes(rgb, true));
  std::string e = import_error(with({"--albedo", "a{N}.pfm"}));
  REQUIRE(e == "frame 1, buffer 'albedo': " + (in / "a1.pfm").string() + ": file does not exist");
  REQUIRE_FALSE(fs::exists(out));
  REQUIRE(test::leftovers(out).empty());
  // A size mismatch between buffers.
  write_bytes(in / "a1.pfm", pfm_bytes(ramp(5, 4, 3, 0.f, 1.f), true));
  e = import_error(with({"--albedo", "a{N}.pfm"}));
  REQUIRE(e == "frame 1, buffer 'albedo': " + (in / "a1.pfm").string() + ": is 5x4, the color is 6x4");
  // A bad PFM header.
  write_bytes(in / "a1.pfm", "PF\n6 four\n-1\n");
  e = import_error(with({"--albedo", "a{N}.pfm"}));
  REQUIRE(e == "frame 1, buffer 'albedo': " + (in / "a1.pfm").string() + ": bad height 'four' in the header");
  // A truncated .hdr (its last scanline cut short).
  std::string hdr = hdr_bytes(rgb, false);
  hdr.resize(hdr.size() - 5);
  write_bytes(in / "r0.hdr", hdr);
  e = import_error(with({"--reference", "r0.hdr", "--frames", "0"}));
  REQUIRE(e == "frame 0, buffer 'reference': " + (in / "r0.hdr").string() +
                   ": truncated (file ends in scanline 3 of 4)");
  // Too few channels, a non-finite guide, a surface with depth 0.
  write_bytes(in / "d0.pfm", pfm_bytes(Image(6, 4, 1, 2.f), false));
  e = import_error(with({"--albedo", "d0.pfm", "--frames", "0"}));
  REQUIRE(e.find("frame 0, buffer 'albedo'") == 0);
  REQUIRE(e.find("has 1 channel, needs 3") != std::string::npos);
  Image depth(6, 4, 1, 2.f), id(6, 4, 1, 0.f);
  depth.at(4, 1, 0) = NAN;
  write_bytes(in / "dn.pfm", pfm_bytes(depth, true));
  e = import_error(with({"--depth", "dn.pfm", "--frames", "0"}));
  REQUIRE(e.find("at pixel (4, 1), channel 0 (this buffer must be finite)") != std::string::npos);
  depth.at(4, 1, 0) = 0.f;
  write_bytes(in / "dz.pfm", pfm_bytes(depth, true));
  write_bytes(in / "id.pfm", pfm_bytes(id, true));
  e = import_error(with({"--depth", "dz.pfm", "--id", "id.pfm", "--frames", "0"}));
  REQUIRE(e.find("frame 0, buffer 'depth'") == 0);
  REQUIRE(e.find("depth 0.000000 at pixel (4, 1), whose id says it is a surface") != std::string::npos);
  // Usage errors: no normal pattern, a bad placeholder, an unknown preset.
  REQUIRE_THROWS_AS(app::import_command({in.string(), out.string(), "--color", "c{N}.pfm"}),
                    app::UsageError);
  REQUIRE_THROWS_AS(app::import_command(with({"--albedo", "a{N:x}.pfm"})), app::UsageError);
  REQUIRE_THROWS_AS(app::import_command(with({"--preset", "games101"})), app::UsageError);
  REQUIRE_FALSE(fs::exists(out));
  test::remove_output(in);
}

TEST_CASE("import round trip: a fixture's buffers as EXR files come back bit for bit",
          "[app][import]") {
  const fs::path fixture = fs::path(SVGF_SOURCE_DIR) / "fixtures" / "cornell-moving";
  const fs::path in = test::scratch("import_rt_in"), out = test::scratch("import_rt_out"),
                 out2 = test::scratch("import_rt_out2");
  const io::Sequence source(fixture.string());
  std::vector<Frame> frames;
  for (int k = 0; k < 2; ++k) {
    Frame f = source.read(k);
    const std::string n = std::to_string(k);
    auto put = [&](const char* name, const Image& im) {
      io::write_image_exr((in / (std::string(name) + "_" + n + ".exr")).string(), im);
    };
    fs::create_directories(in);
    put("color", f.color);
    put("albedo", f.albedo);
    put("normal", f.normal);
    put("position", f.position);
    put("depth", f.depth);
    put("gradient", f.depth_gradient);
    put("motion", f.motion);
    put("reference", f.reference);
    put("emission", f.emission);
    Image id(f.width(), f.height(), 1);
    for (size_t i = 0; i < f.mesh_id.size(); ++i) id.plane(0)[i] = float(f.mesh_id[i]) - 1.f;
    put("id", id);
    frames.push_back(std::move(f));
  }
  const std::string map = (in / "map.json").string();
  write_bytes(map, R"({"color": "color_{N}.exr", "albedo": "albedo_{N}.exr",
    "normal": "normal_{N}.exr", "position": "position_{N}.exr", "depth": "depth_{N}.exr",
    "motion": "motion_{N}.exr", "id": "id_{N}.exr", "reference": "reference_{N}.exr",
    "emission": "emission_{N}.exr", "frames": "0..1"})");
  REQUIRE(app::import_command({in.string(), out.string(), "--map", map, "--depth-gradient",
                               "gradient_{N}.exr"}) == 0);
  const io::Sequence imported(out.string());
  REQUIRE(imported.size() == 2);
  for (int k = 0; k < 2; ++k) {
    const Frame a = frames[static_cast<size_t>(k)], b = imported.read(k);
    REQUIRE(b.index == a.index);
    REQUIRE(same_bits(a.color, b.color));
    REQUIRE(same_bits(a.albedo, b.albedo));
    REQUIRE(same_bits(a.normal, b.normal));
    REQUIRE(same_bits(a.position, b.position));
    REQUIRE(same_bits(a.depth, b.depth));
    REQUIRE(same_bits(a.depth_gradient, b.depth_gradient));
    REQUIRE(same_bits(a.motion, b.motion));
    REQUIRE(same_bits(a.reference, b.reference));
    REQUIRE(same_bits(a.emission, b.emission));
    REQUIRE(a.mesh_id == b.mesh_id);
  }
  REQUIRE(test::read_json(out / "import.json")["warnings"].empty());

  // Without the gradient file it is derived from depth: close to the renderer's analytic one
  // inside surfaces (docs/import.md states the difference).
  REQUIRE(app::import_command({in.string(), out2.string(), "--map", map, "--frames", "0"}) == 0);
  const Frame derived = io::Sequence(out2.string()).read(0);
  const Frame& truth = frames[0];
  int inside = 0, close = 0;
  const int w = truth.width(), h = truth.height();
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      const uint32_t id = truth.mesh_id[i];
      if (id == 0 || truth.mesh_id[i - 1] != id || truth.mesh_id[i + 1] != id ||
          truth.mesh_id[i - w] != id || truth.mesh_id[i + w] != id)
        continue;
      ++inside;
      bool ok = true;
      for (int c = 0; c < 2; ++c) {
        const float t = truth.depth_gradient.plane(c)[i], d = derived.depth_gradient.plane(c)[i];
        ok = ok && std::fabs(t - d) <= 0.01f * std::fabs(t) + 1e-4f;
      }
      close += ok;
    }
  INFO("inside " << inside << ", within 1% " << close);
  REQUIRE(inside > w * h / 2);
  REQUIRE(close >= inside * 99 / 100);
  for (const auto& p : {in, out, out2}) test::remove_output(p);
}
