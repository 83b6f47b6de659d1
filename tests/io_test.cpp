// I/O layer: frame EXR files, RGB EXR, PNG, atomic writes, SHA-256, sequences and manifests.
#include <unistd.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <Imath/half.h>

#include <algorithm>
#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <set>
#include <utility>

#include "io/atomic_file.h"
#include "io/exr_frame.h"
#include "io/png.h"
#include "io/printable.h"
#include "io/sequence.h"
#include "io/sha256.h"

#include "file_test_support.h"

namespace fs = std::filesystem;
using namespace svgf;
using Catch::Matchers::Contains;

namespace {

// A fresh folder per test, removed afterwards.
struct TempDir {
  fs::path path;
  TempDir() {
    static std::atomic<int> counter{0};
    const auto ticks = std::chrono::steady_clock::now().time_since_epoch().count();
    path = fs::temp_directory_path() /
           ("svgf_io_test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + "-" +
            std::to_string(ticks));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string operator/(const std::string& name) const { return (path / name).string(); }
};

using svgf::test::list_dir;
using svgf::test::read_text;
using svgf::test::write_text;

void fill(Image& im, std::mt19937& rng, float lo, float hi) {
  std::uniform_real_distribution<float> d(lo, hi);
  for (float& v : im.data()) v = d(rng);
}

Frame random_frame(int w, int h, uint32_t seed, bool optional = true) {
  std::mt19937 rng(seed);
  Frame f;
  f.allocate(w, h);
  f.index = static_cast<int>(seed % 1000) + 1;
  fill(f.color, rng, 0.f, 40.f);
  fill(f.albedo, rng, 0.f, 1.f);
  fill(f.normal, rng, -1.f, 1.f);
  fill(f.position, rng, -100.f, 100.f);
  fill(f.depth, rng, 0.1f, 50.f);
  fill(f.depth_gradient, rng, -2.f, 2.f);
  fill(f.motion, rng, -8.f, 8.f);
  // Full 32-bit range: ids above 2^24 would not survive a trip through float.
  for (uint32_t& id : f.mesh_id) id = static_cast<uint32_t>(rng());
  if (optional) {
    f.emission = Image(w, h, 3);
    f.reference = Image(w, h, 3);
    f.direct = Image(w, h, 3);
    f.indirect = Image(w, h, 3);
    fill(f.emission, rng, 0.f, 30.f);
    fill(f.reference, rng, 0.f, 10.f);
    fill(f.direct, rng, 0.f, 20.f);
    fill(f.indirect, rng, 0.f, 20.f);
  } else {
    f.position = Image();
  }
  std::uniform_real_distribution<float> m(-3.f, 3.f);
  for (float& v : f.camera.world_to_view) v = m(rng);
  for (float& v : f.camera.view_to_clip) v = m(rng);
  return f;
}

bool bitwise_equal(const Image& a, const Image& b) {
  return a.width() == b.width() && a.height() == b.height() && a.channels() == b.channels() &&
         std::memcmp(a.data().data(), b.data().data(), a.data().size() * sizeof(float)) == 0;
}

// What a HALF channel must read back as: round to nearest half, then exact widening.
bool half_equal(const Image& read, const Image& written) {
  if (read.data().size() != written.data().size() || read.channels() != written.channels())
    return false;
  for (size_t i = 0; i < read.data().size(); ++i) {
    const float x = written.data()[i];
    if (read.data()[i] != static_cast<float>(Imath::half(x))) return false;
    if (std::fabs(read.data()[i] - x) > std::fabs(x) * 0x1p-11f + 0x1p-24f) return false;
  }
  return true;
}

// Writes an EXR with exactly the given channels (and no svgf attributes) through OpenEXR.
void write_raw_exr(const std::string& path, int w, int h,
                   const std::vector<std::pair<std::string, Imf::PixelType>>& channels,
                   int x0 = 0, int y0 = 0) {
  const Imath::Box2i window({x0, y0}, {x0 + w - 1, y0 + h - 1});
  Imf::Header header(window, window);
  std::vector<std::vector<uint32_t>> buffers;  // 4 bytes per sample fits every type
  Imf::FrameBuffer fb;
  uint32_t k = 1;
  for (const auto& [name, type] : channels) {
    header.channels().insert(name, Imf::Channel(type));
    std::vector<uint32_t> buf(static_cast<size_t>(w) * h);
    for (uint32_t& v : buf) {
      ++k;
      if (type == Imf::FLOAT) {
        const float f = 0.25f * static_cast<float>(k % 97);
        std::memcpy(&v, &f, 4);
      } else if (type == Imf::HALF) {
        const Imath::half hv(0.5f * static_cast<float>(k % 31));
        const uint16_t bits = hv.bits();
        v = 0;
        std::memcpy(&v, &bits, 2);
      } else {
        v = k * 2654435761u;
      }
    }
    // HALF samples sit in the first 2 bytes of each 4-byte slot: stride 4 for every type.
    char* base = reinterpret_cast<char*>(buf.data()) - (static_cast<size_t>(y0) * w + x0) * 4;
    fb.insert(name, Imf::Slice(type, base, 4, 4 * static_cast<size_t>(w)));
    buffers.push_back(std::move(buf));
  }
  Imf::OutputFile file(path.c_str(), header);
  file.setFrameBuffer(fb);
  file.writePixels(h);
}

using ChannelTypes = std::vector<std::pair<std::string, Imf::PixelType>>;

// Every required frame channel with a valid type.
ChannelTypes required_channels() {
  ChannelTypes c;
  for (const char* n : io::channel::kColor) c.push_back({n, Imf::FLOAT});
  for (const char* n : io::channel::kAlbedo) c.push_back({n, Imf::HALF});
  for (const char* n : io::channel::kNormal) c.push_back({n, Imf::HALF});
  c.push_back({io::channel::kDepth, Imf::FLOAT});
  for (const char* n : io::channel::kDepthGradient) c.push_back({n, Imf::FLOAT});
  for (const char* n : io::channel::kMotion) c.push_back({n, Imf::FLOAT});
  c.push_back({io::channel::kMeshId, Imf::UINT});
  return c;
}

ChannelTypes with_type(ChannelTypes c, const std::string& name, Imf::PixelType t) {
  for (auto& [n, type] : c)
    if (n == name) type = t;
  return c;
}

ChannelTypes without(ChannelTypes c, const std::string& name) {
  c.erase(std::remove_if(c.begin(), c.end(), [&](const auto& p) { return p.first == name; }),
          c.end());
  return c;
}

template <class F>
std::string io_error_of(F&& f) {
  try {
    f();
  } catch (const io::IoError& e) {
    const std::string msg = e.what();
    CHECK(msg.find('\n') == std::string::npos);  // one line
    return msg;
  }
  FAIL("no IoError thrown");
  return "";
}

io::Manifest test_manifest() {
  io::Manifest m;
  m.scene = "synthetic";
  m.spp = 1;
  m.reference_spp = 4096;
  m.seed = 0xfedcba9876543210ull;  // above 2^63: must survive JSON as unsigned
  m.generator = "svgf io_test";
  return m;
}

}  // namespace

TEST_CASE("sha256 matches the FIPS 180-4 known answers", "[io][sha256]") {
  CHECK(io::sha256_hex("", 0) ==
        "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(io::sha256_hex("abc", 3) ==
        "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  const std::string two_blocks = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
  CHECK(io::sha256_hex(two_blocks.data(), two_blocks.size()) ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  const std::string million(1000000, 'a');
  CHECK(io::sha256_hex(million.data(), million.size()) ==
        "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST_CASE("sha256_file streams a file and names a missing one", "[io][sha256]") {
  TempDir tmp;
  const std::string path = tmp / "million_a.bin";
  write_text(path, std::string(1000000, 'a'));  // spans several read chunks
  CHECK(io::sha256_file(path) ==
        "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");

  std::mt19937 rng(7);
  std::string bytes(200003, '\0');
  for (char& c : bytes) c = static_cast<char>(rng());
  write_text(tmp / "random.bin", bytes);
  CHECK(io::sha256_file(tmp / "random.bin") == io::sha256_hex(bytes.data(), bytes.size()));

  write_text(tmp / "empty.bin", "");
  CHECK(io::sha256_file(tmp / "empty.bin") ==
        "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");

  const std::string missing = tmp / "missing.bin";
  CHECK_THAT(io_error_of([&] { io::sha256_file(missing); }), Contains(missing));
}

TEST_CASE("frame round trip with FLOAT storage is bitwise exact", "[io][exr]") {
  TempDir tmp;
  Frame f = random_frame(13, 7, 42);
  // Special values survive FLOAT storage too.
  f.color.at(0, 0, 0) = -0.0f;
  f.color.at(1, 0, 1) = std::numeric_limits<float>::denorm_min();
  f.motion.at(2, 3, 0) = std::numeric_limits<float>::infinity();
  io::FrameStorage all_float;
  all_float.albedo = all_float.normal = io::PixelStorage::Float;
  const std::string path = tmp / "frame.exr";
  io::write_frame(path, f, all_float);
  CHECK(list_dir(tmp.path) == std::set<std::string>{"frame.exr"});

  const Frame r = io::read_frame(path);
  CHECK(r.index == f.index);
  CHECK(r.width() == 13);
  CHECK(r.height() == 7);
  CHECK(bitwise_equal(r.color, f.color));
  CHECK(bitwise_equal(r.albedo, f.albedo));
  CHECK(bitwise_equal(r.normal, f.normal));
  CHECK(bitwise_equal(r.position, f.position));
  CHECK(bitwise_equal(r.depth, f.depth));
  CHECK(bitwise_equal(r.depth_gradient, f.depth_gradient));
  CHECK(bitwise_equal(r.motion, f.motion));
  CHECK(bitwise_equal(r.emission, f.emission));
  CHECK(bitwise_equal(r.reference, f.reference));
  CHECK(bitwise_equal(r.direct, f.direct));
  CHECK(bitwise_equal(r.indirect, f.indirect));
  CHECK(r.mesh_id == f.mesh_id);
  CHECK(r.camera.world_to_view == f.camera.world_to_view);
  CHECK(r.camera.view_to_clip == f.camera.view_to_clip);
  CHECK_NOTHROW(check_frame_consistent(r));
}

TEST_CASE("frame round trip with HALF storage is within half precision", "[io][exr]") {
  TempDir tmp;
  const Frame f = random_frame(17, 9, 5);
  SECTION("default storage: albedo and normal HALF, the rest FLOAT") {
    io::write_frame(tmp / "f.exr", f);
    const Frame r = io::read_frame(tmp / "f.exr");
    CHECK(half_equal(r.albedo, f.albedo));
    CHECK(half_equal(r.normal, f.normal));
    CHECK_FALSE(bitwise_equal(r.albedo, f.albedo));  // really stored as HALF
    CHECK(bitwise_equal(r.color, f.color));
    CHECK(bitwise_equal(r.depth, f.depth));
    CHECK(bitwise_equal(r.reference, f.reference));
    CHECK(r.mesh_id == f.mesh_id);
  }
  SECTION("everything HALF") {
    const io::PixelStorage H = io::PixelStorage::Half;
    const io::FrameStorage all_half{H, H, H, H, H, H, H};
    io::write_frame(tmp / "f.exr", f, all_half);
    const Frame r = io::read_frame(tmp / "f.exr");
    CHECK(half_equal(r.color, f.color));
    CHECK(half_equal(r.albedo, f.albedo));
    CHECK(half_equal(r.normal, f.normal));
    CHECK(half_equal(r.position, f.position));
    CHECK(half_equal(r.depth, f.depth));
    CHECK(half_equal(r.depth_gradient, f.depth_gradient));
    CHECK(half_equal(r.motion, f.motion));
    CHECK(half_equal(r.reference, f.reference));
    CHECK(half_equal(r.direct, f.direct));
    CHECK(half_equal(r.indirect, f.indirect));
    CHECK(r.mesh_id == f.mesh_id);  // UINT regardless of storage
    CHECK(r.camera.world_to_view == f.camera.world_to_view);
    // HALF halves the float channels' size.
    io::write_frame(tmp / "g.exr", f);
    CHECK(fs::file_size(tmp / "f.exr") < fs::file_size(tmp / "g.exr"));
  }
}

TEST_CASE("optional channels are written only when present", "[io][exr]") {
  TempDir tmp;
  Frame f = random_frame(8, 5, 9, /*optional=*/false);
  io::write_frame(tmp / "f.exr", f);
  Frame r = io::read_frame(tmp / "f.exr");
  CHECK(r.position.empty());
  CHECK(r.emission.empty());
  CHECK(r.reference.empty());
  CHECK(r.direct.empty());
  CHECK(r.indirect.empty());
  CHECK_FALSE(r.has_reference());
  CHECK(bitwise_equal(r.color, f.color));

  std::mt19937 rng(3);
  f.reference = Image(8, 5, 3);
  fill(f.reference, rng, 0.f, 1.f);
  f.position = Image(8, 5, 3);
  fill(f.position, rng, -1.f, 1.f);
  io::write_frame(tmp / "f.exr", f);
  r = io::read_frame(tmp / "f.exr");
  CHECK(r.has_reference());
  CHECK(bitwise_equal(r.reference, f.reference));
  CHECK(bitwise_equal(r.position, f.position));
  CHECK(r.direct.empty());
  CHECK(r.indirect.empty());
}

TEST_CASE("frame files are deterministic", "[io][exr]") {
  TempDir tmp;
  const Frame f = random_frame(31, 11, 77);
  io::write_frame(tmp / "a.exr", f);
  io::write_frame(tmp / "b.exr", f);
  CHECK(io::sha256_file(tmp / "a.exr") == io::sha256_file(tmp / "b.exr"));
}

TEST_CASE("a file without svgf attributes reads with defaults", "[io][exr]") {
  TempDir tmp;
  const std::string path = tmp / "plain.exr";
  write_raw_exr(path, 6, 4, required_channels());
  const Frame r = io::read_frame(path);
  CHECK(r.index == 0);
  CHECK(r.camera.world_to_view == Camera{}.world_to_view);
  CHECK(r.camera.view_to_clip == Camera{}.view_to_clip);
  CHECK(r.width() == 6);
  CHECK(r.height() == 4);
  CHECK(r.position.empty());
  CHECK(r.color.at(1, 0, 0) != 0.f);  // the data was really read
  CHECK(r.mesh_id[3] != 0u);
}

TEST_CASE("read_frame errors name the file and the channel", "[io][exr][errors]") {
  TempDir tmp;
  SECTION("missing file") {
    const std::string path = tmp / "nope.exr";
    CHECK_THAT(io_error_of([&] { io::read_frame(path); }),
               Contains(path) && Contains("does not exist"));
  }
  SECTION("a text file named .exr") {
    const std::string path = tmp / "text.exr";
    write_text(path, "this is not an image\n");
    CHECK_THAT(io_error_of([&] { io::read_frame(path); }),
               Contains(path) && Contains("not an OpenEXR file"));
  }
  SECTION("a truncated file") {
    const std::string path = tmp / "cut.exr";
    io::write_frame(path, random_frame(40, 30, 1));
    fs::resize_file(path, fs::file_size(path) / 2);
    CHECK_THAT(io_error_of([&] { io::read_frame(path); }), Contains(path));
  }
  SECTION("missing channel") {
    const std::string path = tmp / "frame_0003.exr";
    write_raw_exr(path, 5, 4, without(required_channels(), "albedo.G"));
    CHECK(io_error_of([&] { io::read_frame(path); }) ==
          path + ": channel 'albedo.G' is missing");
  }
  SECTION("missing mesh_id") {
    const std::string path = tmp / "f.exr";
    write_raw_exr(path, 5, 4, without(required_channels(), "mesh_id"));
    CHECK_THAT(io_error_of([&] { io::read_frame(path); }),
               Contains(path) && Contains("'mesh_id'") && Contains("missing"));
  }
  SECTION("mesh_id stored as FLOAT") {
    const std::string path = tmp / "f.exr";
    write_raw_exr(path, 5, 4, with_type(required_channels(), "mesh_id", Imf::FLOAT));
    CHECK_THAT(io_error_of([&] { io::read_frame(path); }),
               Contains(path) && Contains("'mesh_id'") && Contains("FLOAT") &&
                   Contains("expected UINT"));
  }
  SECTION("color stored as UINT") {
    const std::string path = tmp / "f.exr";
    write_raw_exr(path, 5, 4, with_type(required_channels(), "color.G", Imf::UINT));
    CHECK_THAT(io_error_of([&] { io::read_frame(path); }),
               Contains(path) && Contains("'color.G'") && Contains("UINT"));
  }
  SECTION("partly present optional group") {
    ChannelTypes c = required_channels();
    c.push_back({"reference.R", Imf::FLOAT});
    c.push_back({"reference.G", Imf::FLOAT});
    const std::string path = tmp / "f.exr";
    write_raw_exr(path, 5, 4, c);
    CHECK_THAT(io_error_of([&] { io::read_frame(path); }),
               Contains(path) && Contains("'reference.B'") && Contains("missing"));
  }
  SECTION("data window not at 0,0") {
    const std::string path = tmp / "f.exr";
    write_raw_exr(path, 5, 4, required_channels(), 2, 1);
    CHECK_THAT(io_error_of([&] { io::read_frame(path); }),
               Contains(path) && Contains("data window"));
  }
}

// Issue 15: a sequence is validated before any output is written. read_frame_header makes every
// check read_frame makes before the pixels, with the same message, and reads no pixels: a file
// whose pixel data is cut short passes it and fails read_frame.
TEST_CASE("read_frame_header refuses what read_frame refuses, without the pixels",
          "[io][exr][errors]") {
  TempDir tmp;
  const std::string path = tmp / "f.exr";
  auto same_error = [&](const io::detail::ExpectedSize& expected = {}) {
    const std::string message = io_error_of([&] { io::detail::read_frame(path, nullptr, expected); });
    CHECK_THAT(message, Contains(path));
    CHECK(io_error_of([&] { io::read_frame_header(path, expected); }) == message);
  };
  SECTION("missing channel") {
    write_raw_exr(path, 5, 4, without(required_channels(), "albedo.G"));
    same_error();
  }
  SECTION("mesh_id stored as FLOAT") {
    write_raw_exr(path, 5, 4, with_type(required_channels(), "mesh_id", Imf::FLOAT));
    same_error();
  }
  SECTION("partly present optional group") {
    ChannelTypes c = required_channels();
    c.push_back({"direct.R", Imf::FLOAT});
    write_raw_exr(path, 5, 4, c);
    same_error();
  }
  SECTION("data window not at 0,0") {
    write_raw_exr(path, 5, 4, required_channels(), 2, 1);
    same_error();
  }
  SECTION("size other than expected") {
    write_raw_exr(path, 5, 4, required_channels());
    same_error({5, 5, "manifest"});
  }
  SECTION("a good header with its pixel data cut short") {
    Frame f = random_frame(40, 30, 5);
    io::write_frame(path, f);
    fs::resize_file(path, fs::file_size(path) - 64);
    const io::FrameHeader h = io::read_frame_header(path, {40, 30, "manifest"});
    CHECK(h.width == 40);
    CHECK(h.height == 30);
    CHECK(h.has_index);
    CHECK(h.index == f.index);
    CHECK_THAT(io_error_of([&] { io::read_frame(path); }), Contains(path));
  }
  SECTION("no svgf.frame") {
    write_raw_exr(path, 5, 4, required_channels());
    const io::FrameHeader h = io::read_frame_header(path);
    CHECK_FALSE(h.has_index);
    CHECK(h.width == 5);
  }
}

TEST_CASE("read_frame_from_memory reads what read_frame reads", "[io][exr]") {
  TempDir tmp;
  const std::string path = tmp / "f.exr";
  io::write_frame(path, random_frame(9, 6, 5));
  const std::string bytes = read_text(path);
  const Frame from_file = io::read_frame(path);
  const Frame r = io::read_frame_from_memory(bytes.data(), bytes.size(), "in memory");
  CHECK(r.index == from_file.index);
  CHECK(bitwise_equal(r.color, from_file.color));
  CHECK(bitwise_equal(r.albedo, from_file.albedo));
  CHECK(bitwise_equal(r.normal, from_file.normal));
  CHECK(bitwise_equal(r.position, from_file.position));
  CHECK(bitwise_equal(r.depth, from_file.depth));
  CHECK(bitwise_equal(r.depth_gradient, from_file.depth_gradient));
  CHECK(bitwise_equal(r.motion, from_file.motion));
  CHECK(bitwise_equal(r.emission, from_file.emission));
  CHECK(bitwise_equal(r.reference, from_file.reference));
  CHECK(bitwise_equal(r.direct, from_file.direct));
  CHECK(bitwise_equal(r.indirect, from_file.indirect));
  CHECK(r.mesh_id == from_file.mesh_id);
  CHECK(r.camera.world_to_view == from_file.camera.world_to_view);
  CHECK(r.camera.view_to_clip == from_file.camera.view_to_clip);
}

TEST_CASE("read_frame_from_memory errors name the given name", "[io][exr][errors]") {
  TempDir tmp;
  const std::string path = tmp / "f.exr";
  io::write_frame(path, random_frame(40, 30, 1));
  const std::string bytes = read_text(path);
  SECTION("no bytes") {
    CHECK(io_error_of([] { io::read_frame_from_memory(nullptr, 0, "mem"); }) ==
          "mem: not an OpenEXR file (bad magic number)");
  }
  SECTION("text") {
    const std::string text = "this is not an image\n";
    CHECK(io_error_of([&] { io::read_frame_from_memory(text.data(), text.size(), "mem"); }) ==
          "mem: not an OpenEXR file (bad magic number)");
  }
  SECTION("truncated anywhere") {
    // Cut in the header, in the offset table and in the pixels: the stream refuses to read
    // past the end, which OpenEXR reports.
    for (const size_t size : {size_t{4}, size_t{100}, bytes.size() / 2, bytes.size() - 1}) {
      CAPTURE(size);
      CHECK_THAT(io_error_of([&] { io::read_frame_from_memory(bytes.data(), size, "mem"); }),
                 Catch::Matchers::StartsWith("mem: "));
    }
  }
}

TEST_CASE("write_frame rejects an inconsistent frame", "[io][exr][errors]") {
  TempDir tmp;
  Frame f = random_frame(8, 4, 2);
  f.albedo = Image(7, 4, 3);
  const std::string path = tmp / "bad.exr";
  CHECK_THROWS_AS(io::write_frame(path, f), std::invalid_argument);
  CHECK_THROWS_WITH(io::write_frame(path, f), Contains(path) && Contains("albedo"));
  CHECK(list_dir(tmp.path).empty());
}

// Issue 12: A-SVGF gradient samples travel as an optional FLOAT group, whatever the storage.
TEST_CASE("the gradient group: FLOAT round trip, optional, all or nothing", "[io][exr]") {
  TempDir tmp;
  Frame f = random_frame(10, 7, 21);
  f.gradient = Image(10, 7, 3);
  std::mt19937 rng(4);
  fill(f.gradient, rng, 0.f, 3.f);
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 10; ++x) {
      const bool sample = (x % 3 == 1) && (y % 3 == 2);
      f.gradient.at(x, y, 2) = sample ? 1.f : 0.f;
      if (!sample) f.gradient.at(x, y, 0) = f.gradient.at(x, y, 1) = 0.f;
    }
  f.gradient.at(1, 2, 1) = 0.1f + 1e-7f;  // not a half: must come back bit for bit
  const io::PixelStorage H = io::PixelStorage::Half;
  io::write_frame(tmp / "g.exr", f, io::FrameStorage{H, H, H, H, H, H, H});
  const Frame r = io::read_frame(tmp / "g.exr");
  CHECK(bitwise_equal(r.gradient, f.gradient));
  CHECK(half_equal(r.color, f.color));
  CHECK_NOTHROW(check_frame_consistent(r));

  f.gradient = Image();
  io::write_frame(tmp / "none.exr", f);
  CHECK(io::read_frame(tmp / "none.exr").gradient.empty());

  ChannelTypes c = required_channels();
  c.push_back({"gradient.previous", Imf::FLOAT});
  c.push_back({"gradient.current", Imf::FLOAT});
  write_raw_exr(tmp / "part.exr", 5, 4, c);
  CHECK(io_error_of([&] { io::read_frame(tmp / "part.exr"); }) ==
        tmp / "part.exr" + ": channel 'gradient.mask' is missing");
  CHECK(io_error_of([&] { io::read_frame_header(tmp / "part.exr"); }) ==
        tmp / "part.exr" + ": channel 'gradient.mask' is missing");

  f.gradient = Image(10, 7, 2);
  CHECK_THROWS_WITH(check_frame_consistent(f), Contains("'gradient'") && Contains("10x7x3"));
}

TEST_CASE("write_frame into a missing folder throws IoError and leaves nothing", "[io][exr]") {
  TempDir tmp;
  const std::string path = tmp / "no/such/folder/f.exr";
  CHECK_THAT(io_error_of([&] { io::write_frame(path, random_frame(4, 4, 4)); }),
             Contains(path));
  CHECK(list_dir(tmp.path).empty());
}

TEST_CASE("RGB EXR round trip", "[io][exr]") {
  TempDir tmp;
  Image im(11, 6, 3);
  std::mt19937 rng(11);
  fill(im, rng, 0.f, 100.f);
  const std::string path = tmp / "out.exr";
  io::write_rgb_exr(path, im);
  CHECK(list_dir(tmp.path) == std::set<std::string>{"out.exr"});
  CHECK(bitwise_equal(io::read_rgb_exr(path), im));

  SECTION("HALF input from another tool") {
    const std::string hpath = tmp / "half.exr";
    write_raw_exr(hpath, 9, 3, {{"R", Imf::HALF}, {"G", Imf::HALF}, {"B", Imf::HALF}});
    const Image r = io::read_rgb_exr(hpath);
    CHECK(r.width() == 9);
    CHECK(r.height() == 3);
    CHECK(r.channels() == 3);
    CHECK(r.at(1, 0, 0) != 0.f);
  }
  SECTION("missing B") {
    const std::string bad = tmp / "rg.exr";
    write_raw_exr(bad, 4, 4, {{"R", Imf::FLOAT}, {"G", Imf::FLOAT}});
    CHECK(io_error_of([&] { io::read_rgb_exr(bad); }) == bad + ": channel 'B' is missing");
  }
  SECTION("UINT R") {
    const std::string bad = tmp / "uint.exr";
    write_raw_exr(bad, 4, 4, {{"R", Imf::UINT}, {"G", Imf::FLOAT}, {"B", Imf::FLOAT}});
    CHECK_THAT(io_error_of([&] { io::read_rgb_exr(bad); }),
               Contains(bad) && Contains("'R'") && Contains("UINT"));
  }
  SECTION("a frame file is not an RGB file") {
    const std::string fpath = tmp / "frame.exr";
    io::write_frame(fpath, random_frame(4, 4, 8));
    CHECK_THAT(io_error_of([&] { io::read_rgb_exr(fpath); }),
               Contains(fpath) && Contains("'R'"));
  }
}

TEST_CASE("write_atomically leaves either the whole file or nothing", "[io][atomic]") {
  TempDir tmp;
  const std::string path = tmp / "out.txt";
  io::write_atomically(path, [&](const std::string& t) {
    CHECK(t != path);
    CHECK(fs::path(t).parent_path() == fs::path(path).parent_path());
    write_text(t, "first");
  });
  CHECK(read_text(path) == "first");
  CHECK(list_dir(tmp.path) == std::set<std::string>{"out.txt"});

  SECTION("a throwing writer leaves neither target nor temp") {
    const std::string other = tmp / "other.txt";
    CHECK_THROWS_WITH(io::write_atomically(other,
                                           [&](const std::string& t) {
                                             write_text(t, "partial");
                                             throw std::runtime_error("boom");
                                           }),
                      "boom");
    CHECK(list_dir(tmp.path) == std::set<std::string>{"out.txt"});
  }
  SECTION("a throwing writer keeps the old content") {
    CHECK_THROWS(io::write_atomically(path, [&](const std::string& t) {
      write_text(t, "second, partial");
      throw std::runtime_error("boom");
    }));
    CHECK(read_text(path) == "first");
    CHECK(list_dir(tmp.path) == std::set<std::string>{"out.txt"});
  }
  SECTION("a successful rewrite replaces the content") {
    io::write_atomically(path, [&](const std::string& t) { write_text(t, "second"); });
    CHECK(read_text(path) == "second");
    CHECK(list_dir(tmp.path) == std::set<std::string>{"out.txt"});
  }
}

TEST_CASE("write_png_rgb8 writes an 8-bit RGB PNG atomically", "[io][png]") {
  TempDir tmp;
  const int w = 37, h = 21;
  std::vector<uint8_t> rgb(static_cast<size_t>(w) * h * 3);
  std::mt19937 rng(13);
  for (uint8_t& v : rgb) v = static_cast<uint8_t>(rng());
  const std::string path = tmp / "out.png";
  io::write_png_rgb8(path, rgb.data(), w, h);
  CHECK(list_dir(tmp.path) == std::set<std::string>{"out.png"});
  const std::string bytes = read_text(path);
  REQUIRE(bytes.size() > 33);
  CHECK(bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0);
  CHECK(bytes.compare(12, 4, "IHDR") == 0);
  auto be32 = [&](size_t o) {
    return (uint32_t(uint8_t(bytes[o])) << 24) | (uint32_t(uint8_t(bytes[o + 1])) << 16) |
           (uint32_t(uint8_t(bytes[o + 2])) << 8) | uint32_t(uint8_t(bytes[o + 3]));
  };
  CHECK(be32(16) == uint32_t(w));
  CHECK(be32(20) == uint32_t(h));
  CHECK(uint8_t(bytes[24]) == 8);  // bit depth
  CHECK(uint8_t(bytes[25]) == 2);  // colour type RGB
  CHECK(bytes.compare(bytes.size() - 8, 4, "IEND") == 0);

  const std::string bad = tmp / "no/folder/out.png";
  CHECK_THAT(io_error_of([&] { io::write_png_rgb8(bad, rgb.data(), w, h); }), Contains(bad));
  CHECK_THROWS_AS(io::write_png_rgb8(tmp / "zero.png", rgb.data(), 0, h), io::IoError);
  CHECK(list_dir(tmp.path) == std::set<std::string>{"out.png"});
}

TEST_CASE("encode_png_rgb8 and decode_png_rgb8 round trip; bad bytes are named", "[io][png]") {
  const int w = 19, h = 7;
  std::vector<uint8_t> rgb(static_cast<size_t>(w) * h * 3);
  std::mt19937 rng(5);
  for (uint8_t& v : rgb) v = static_cast<uint8_t>(rng());
  const std::string bytes = io::encode_png_rgb8(rgb.data(), w, h);
  CHECK(bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0);
  const io::Rgb8Image back = io::decode_png_rgb8(bytes, "round trip");
  CHECK(back.width == w);
  CHECK(back.height == h);
  CHECK(back.rgb == rgb);
  // The file writer and the encoder give the same image.
  TempDir tmp;
  io::write_png_rgb8(tmp / "same.png", rgb.data(), w, h);
  CHECK(io::decode_png_rgb8(read_text(tmp / "same.png"), "file").rgb == rgb);

  CHECK_THAT(io_error_of([&] { io::decode_png_rgb8("not a png", "page image 3"); }),
             Contains("page image 3"));
  CHECK_THROWS_AS(io::decode_png_rgb8(bytes.substr(0, bytes.size() / 2), "cut"), io::IoError);
  CHECK_THROWS_AS(io::encode_png_rgb8(rgb.data(), 0, h), io::IoError);
}

TEST_CASE("frame_file_name", "[io][sequence]") {
  CHECK(io::frame_file_name(0) == "frame_0000.exr");
  CHECK(io::frame_file_name(3) == "frame_0003.exr");
  CHECK(io::frame_file_name(12345) == "frame_12345.exr");
}

TEST_CASE("SequenceWriter round trip", "[io][sequence]") {
  TempDir tmp;
  const std::string dir = tmp / "seq";
  std::vector<Frame> frames;
  for (uint32_t k = 0; k < 3; ++k) frames.push_back(random_frame(12, 8, 100 + k, k != 1));
  {
    io::SequenceWriter w(dir, io::FrameStorage{});
    for (const Frame& f : frames) w.add(f);
    CHECK_FALSE(fs::exists(dir));  // nothing visible before commit
    io::Manifest m = test_manifest();
    m.camera_cuts = {0, 2};
    w.commit(m);  // width and height filled in from the frames
  }
  CHECK(list_dir(tmp.path) == std::set<std::string>{"seq"});
  CHECK(list_dir(dir) == std::set<std::string>{"frame_0000.exr", "frame_0001.exr",
                                               "frame_0002.exr", "manifest.json"});

  const io::Sequence seq(dir);
  const io::Manifest& m = seq.manifest();
  CHECK(seq.size() == 3);
  CHECK(m.format_version == 1);
  CHECK(m.scene == "synthetic");
  CHECK(m.width == 12);
  CHECK(m.height == 8);
  CHECK(m.spp == 1);
  CHECK(m.reference_spp == 4096);
  CHECK(m.seed == 0xfedcba9876543210ull);
  CHECK(m.generator == "svgf io_test");
  CHECK(m.camera_cuts == std::vector<int>{0, 2});
  CHECK(seq.is_camera_cut(0));
  CHECK_FALSE(seq.is_camera_cut(1));
  CHECK(seq.is_camera_cut(2));
  const std::string text = read_text(dir + "/manifest.json");
  CHECK_THAT(text, Contains("\"format\": \"svgf-sequence\""));
  for (int k = 0; k < 3; ++k) {
    CHECK(m.frames[k].name == io::frame_file_name(k));
    CHECK(m.frames[k].sha256 == io::sha256_file(seq.path(k)));
    CHECK_NOTHROW(seq.verify_checksum(k));
    const Frame r = seq.read(k);
    CHECK(r.index == frames[k].index);  // from svgf.frame
    CHECK(seq.read_header(k).index == frames[k].index);
    CHECK(bitwise_equal(r.color, frames[k].color));
    CHECK(half_equal(r.normal, frames[k].normal));
    CHECK(r.mesh_id == frames[k].mesh_id);
    CHECK(r.has_reference() == (k != 1));
  }
  CHECK_THROWS_AS(seq.path(3), std::out_of_range);

  SECTION("committing again replaces the old sequence") {
    {
      io::SequenceWriter w(dir + "/", io::FrameStorage{});  // trailing slash: same folder
      w.add(frames[1]);
      w.commit(test_manifest());
    }
    CHECK(list_dir(tmp.path) == std::set<std::string>{"seq"});
    CHECK(list_dir(dir) == std::set<std::string>{"frame_0000.exr", "manifest.json"});
    const io::Sequence again(dir);
    CHECK(again.size() == 1);
    CHECK(bitwise_equal(again.read(0).motion, frames[1].motion));
  }
  SECTION("a tampered frame fails verify_checksum") {
    io::write_frame(seq.path(1), frames[0]);
    CHECK_THAT(io_error_of([&] { seq.verify_checksum(1); }),
               Contains(seq.path(1)) && Contains("SHA-256"));
  }
}

TEST_CASE("an uncommitted SequenceWriter leaves nothing", "[io][sequence]") {
  TempDir tmp;
  const std::string dir = tmp / "seq";
  {
    io::SequenceWriter w(dir, io::FrameStorage{});
    w.add(random_frame(6, 6, 1));
    w.add(random_frame(6, 6, 2));
    CHECK(list_dir(tmp.path).size() == 1);  // the temporary sibling
  }
  CHECK(list_dir(tmp.path).empty());

  SECTION("and leaves an existing sequence untouched") {
    {
      io::SequenceWriter w(dir, io::FrameStorage{});
      w.add(random_frame(6, 6, 3));
      w.commit(test_manifest());
    }
    const std::string before = io::sha256_file(dir + "/frame_0000.exr");
    {
      io::SequenceWriter w(dir, io::FrameStorage{});
      w.add(random_frame(6, 6, 4));
    }
    CHECK(list_dir(tmp.path) == std::set<std::string>{"seq"});
    CHECK(io::sha256_file(dir + "/frame_0000.exr") == before);
    CHECK(io::Sequence(dir).size() == 1);
  }
}

TEST_CASE("SequenceWriter refuses frames of different sizes and non-sequence folders",
          "[io][sequence]") {
  TempDir tmp;
  {
    io::SequenceWriter w(tmp / "seq", io::FrameStorage{});
    w.add(random_frame(6, 6, 1));
    CHECK_THROWS_AS(w.add(random_frame(7, 6, 2)), std::invalid_argument);
    io::Manifest m = test_manifest();
    m.width = 5;
    m.height = 6;
    CHECK_THROWS_AS(w.commit(m), std::invalid_argument);
  }
  CHECK(list_dir(tmp.path).empty());

  fs::create_directories(tmp.path / "precious");
  write_text(tmp / "precious/keep.txt", "keep");
  CHECK_THAT(io_error_of([&] { io::SequenceWriter w(tmp / "precious", io::FrameStorage{}); }),
             Contains("precious"));
  CHECK(read_text(tmp / "precious/keep.txt") == "keep");
}

TEST_CASE("Sequence::read checks the frame size against the manifest", "[io][sequence]") {
  TempDir tmp;
  const std::string dir = tmp / "seq";
  {
    io::SequenceWriter w(dir, io::FrameStorage{});
    w.add(random_frame(8, 6, 1));
    w.commit(test_manifest());
  }
  io::Manifest m = io::read_manifest(dir);
  m.width = 9;
  io::write_manifest(dir, m);
  const io::Sequence seq(dir);
  const std::string file = seq.path(0);
  CHECK(io_error_of([&] { seq.read(0); }) == file + ": frame is 8x6, manifest says 9x6");
}

// Issue 15: a small file whose header claims a huge size made the reader allocate for it before
// comparing with the manifest. The size now comes first, from the header alone: a frame file of
// the wrong size reports its size even when it also lacks every channel but R, G, B.
TEST_CASE("Sequence::read checks the size from the header before reading channels",
          "[io][sequence]") {
  TempDir tmp;
  const std::string dir = tmp / "seq";
  {
    io::SequenceWriter w(dir, io::FrameStorage{});
    w.add(random_frame(8, 6, 1));
    w.commit(test_manifest());
  }
  const io::Sequence seq(dir);
  const std::string file = seq.path(0);
  Image rgb(40, 30, 3, 0.5f);
  fs::remove(file);
  io::write_rgb_exr(file, rgb);
  CHECK(io_error_of([&] { seq.read(0); }) == file + ": frame is 40x30, manifest says 8x6");
  // Read on its own (no manifest), the same file is refused for its missing channels.
  CHECK_THAT(io_error_of([&] { io::read_frame(file); }), !Contains("manifest"));
}

TEST_CASE("Sequence::read numbers frames without svgf.frame by position", "[io][sequence]") {
  TempDir tmp;
  const std::string dir = tmp / "seq";
  fs::create_directories(dir);
  io::Manifest m = test_manifest();
  m.width = 5;
  m.height = 3;
  for (int k = 0; k < 3; ++k) {
    const std::string name = io::frame_file_name(k);
    write_raw_exr(dir + "/" + name, 5, 3, required_channels());
    m.frames.push_back({name, io::sha256_file(dir + "/" + name)});
  }
  io::write_manifest(dir, m);
  const io::Sequence seq(dir);
  for (int k = 0; k < 3; ++k) {
    CHECK(seq.read(k).index == k);
    CHECK(seq.read_header(k).index == k);
  }
}

TEST_CASE("read_manifest errors name the manifest and the key", "[io][sequence][errors]") {
  TempDir tmp;
  const std::string dir = tmp.path.string();
  const std::string path = tmp / "manifest.json";
  SECTION("missing file") {
    CHECK_THAT(io_error_of([&] { io::read_manifest(dir); }),
               Contains(path) && Contains("does not exist"));
    CHECK_THROWS_AS(io::Sequence(dir), io::IoError);
  }
  SECTION("bad JSON") {
    write_text(path, "{\"format\": ");
    CHECK_THAT(io_error_of([&] { io::read_manifest(dir); }),
               Contains(path) && Contains("invalid JSON"));
  }
  io::Manifest good = test_manifest();
  good.width = 4;
  good.height = 4;
  good.frames.push_back({"frame_0000.exr", std::string(64, 'a')});
  io::write_manifest(dir, good);
  const std::string text = read_text(path);
  auto edited = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    const size_t at = t.find(from);
    REQUIRE(at != std::string::npos);
    t.replace(at, from.size(), to);
    write_text(path, t);
  };
  SECTION("the written manifest reads back") {
    const io::Manifest m = io::read_manifest(dir);
    CHECK(m.frames.size() == 1);
    CHECK(m.seed == good.seed);
  }
  SECTION("missing key") {
    edited("\"spp\": 1,", "");
    CHECK(io_error_of([&] { io::read_manifest(dir); }) == path + ": key 'spp' is missing");
  }
  SECTION("ill-typed key") {
    edited("\"width\": 4", "\"width\": \"4\"");
    CHECK_THAT(io_error_of([&] { io::read_manifest(dir); }),
               Contains(path) && Contains("'width'") && Contains("not an integer"));
  }
  SECTION("ill-typed frame entry") {
    edited("\"sha256\": \"", "\"sha256\": 5, \"x\": \"");
    CHECK_THAT(io_error_of([&] { io::read_manifest(dir); }),
               Contains(path) && Contains("'frames[0].sha256'"));
  }
  SECTION("wrong format") {
    edited("svgf-sequence", "something-else");
    CHECK_THAT(io_error_of([&] { io::read_manifest(dir); }),
               Contains(path) && Contains("'format'"));
  }
  SECTION("frame name leaving the folder") {
    edited("frame_0000.exr", "../frame_0000.exr");
    CHECK_THAT(io_error_of([&] { io::read_manifest(dir); }),
               Contains(path) && Contains("'frames[0].file'"));
  }
  SECTION("frame name with a NUL, where the OS would end the path") {
    // "frame_0000.exr\0x" would open frame_0000.exr: two distinct names, one file.
    edited("frame_0000.exr", "frame_0000.exr\\u0000x");
    CHECK_THAT(io_error_of([&] { io::read_manifest(dir); }),
               Contains(path) && Contains("'frames[0].file' is not a plain file name"));
    io::Manifest nul_name = good;
    nul_name.frames[0].name = std::string("frame_0000.exr\0x", 16);
    CHECK_THROWS_AS(io::write_manifest(dir, nul_name), std::invalid_argument);
  }
  SECTION("camera cut outside the frames") {
    edited("\"camera_cuts\": []", "\"camera_cuts\": [1]");
    CHECK_THAT(io_error_of([&] { io::read_manifest(dir); }),
               Contains(path) && Contains("'camera_cuts[0]'"));
  }
}

// Issue 15: text from a file goes into error messages; control characters and broken UTF-8 must
// not reach the terminal raw, while readable names (accents included) stay as they are.
TEST_CASE("printable: control characters and invalid UTF-8 are escaped, UTF-8 is kept",
          "[io]") {
  using svgf::io::printable;
  REQUIRE(printable("color.R missing") == "color.R missing");
  REQUIRE(printable("\x1b[31mPWN") == "\\x1b[31mPWN");
  REQUIRE(printable(std::string("a\0b", 3)) == "a\\x00b");
  REQUIRE(printable("tab\there\nnew\x7f") == "tab\\x09here\\x0anew\\x7f");
  REQUIRE(printable("sc\xc3\xa8ne") == "sc\xc3\xa8ne");              // U+00E8, kept
  REQUIRE(printable("\xe2\x82\xac 5") == "\xe2\x82\xac 5");          // U+20AC, kept
  REQUIRE(printable("csi \xc2\x9b" "2J") == "csi \\xc2\\x9b2J");     // C1 control U+009B
  REQUIRE(printable("raw \x9b" "2J") == "raw \\x9b2J");              // stray byte
  REQUIRE(printable("cut \xe2\x82") == "cut \\xe2\\x82");            // truncated sequence
}
