// libFuzzer target: the frame reader (io::read_frame_from_memory) on arbitrary bytes.
// What must hold for every input, beyond ASan/UBSan finding nothing:
// - the reader returns a frame or throws io::IoError naming the input; no other exception
//   escapes (one would abort the run, which libFuzzer reports as a crash);
// - a frame that reads is consistent (check_frame_consistent) and survives write_frame (FLOAT
//   storage) and a second read bit for bit.
#include <ImfHeader.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "io/exr_frame.h"
#include "io/printable.h"

namespace {

using namespace svgf;
namespace fs = std::filesystem;

constexpr const char* kName = "fuzz-input.exr";
// The reader allocates what the header claims (Sequence::read bounds it by the manifest), and a
// few header bytes can claim 30000x30000: beyond this OpenEXR's own check refuses the header,
// so libFuzzer's memory limit means a leak or a runaway allocation, not a large frame.
constexpr int kMaxSide = 64;

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "fuzz_exr_frame: %s\n", io::printable(what).c_str());  // names may hold NULs
  std::abort();
}

bool same_bits(const Image& a, const Image& b) {
  return a.width() == b.width() && a.height() == b.height() && a.channels() == b.channels() &&
         (a.empty() ||  // an empty image's data() may be null, which memcmp must not get
          std::memcmp(a.data().data(), b.data().data(), a.data().size() * sizeof(float)) == 0);
}

bool same_frame(const Frame& a, const Frame& b) {
  return a.index == b.index && same_bits(a.color, b.color) && same_bits(a.albedo, b.albedo) &&
         same_bits(a.normal, b.normal) && same_bits(a.position, b.position) &&
         same_bits(a.depth, b.depth) && same_bits(a.depth_gradient, b.depth_gradient) &&
         same_bits(a.motion, b.motion) && a.mesh_id == b.mesh_id &&
         same_bits(a.emission, b.emission) && same_bits(a.reference, b.reference) &&
         same_bits(a.direct, b.direct) && same_bits(a.indirect, b.indirect) &&
         same_bits(a.gradient, b.gradient) &&
         std::memcmp(&a.camera, &b.camera, sizeof(Camera)) == 0;  // bits: NaNs compare too
}

// OpenEXR 3.1 allocates an unknown attribute's declared size (up to 2 GiB) before reading it,
// and under ASan each such allocation and free fills size/8 bytes of shadow memory: perf put 96%
// of the run time there (40 inputs a second; 5000 with this filter). Inputs whose header declares
// an attribute longer than the rest of the input are left out: OpenEXR refuses nearly all of
// them with an exception, which reaches the same catch in the reader as any damaged file's.
// Walks the first header as OpenEXR reads it (name\0 type\0 int32 size, value; an empty name
// ends it; a channel list is read entry by entry whatever its size says) but knows no other
// type; a misreading costs speed, nothing else.
bool declares_attribute_past_end(const uint8_t* data, size_t size) {
  size_t pos = 8;  // magic number and version
  // The string at pos (OpenEXR reads at most 256 bytes of it); false past the input's end.
  auto read_string = [&](std::string& out) {
    out.clear();
    for (; pos < size && out.size() < 256; ++pos) {
      if (data[pos] == 0) return ++pos, true;
      out.push_back(static_cast<char>(data[pos]));
    }
    return false;
  };
  std::string name, type;
  while (read_string(name) && !name.empty() && read_string(type) && pos + 4 <= size) {
    const uint32_t declared = uint32_t(data[pos]) | uint32_t(data[pos + 1]) << 8 |
                              uint32_t(data[pos + 2]) << 16 | uint32_t(data[pos + 3]) << 24;
    pos += 4;
    if (type == "chlist") {
      std::string channel;
      while (read_string(channel) && !channel.empty()) pos += 16;  // type, pLinear, sampling
      continue;
    }
    if (declared > size - pos) return true;  // a negative int32 too (OpenEXR refuses those)
    pos += declared;
  }
  return false;
}

// A folder of this process for the round trip's file, removed at exit.
struct ScratchDir {
  fs::path path = fs::temp_directory_path() / ("svgf_fuzz_exr_frame-" + std::to_string(::getpid()));
  ScratchDir() { fs::create_directories(path); }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

void check_round_trip(const Frame& f) {
  static const ScratchDir scratch;
  io::FrameStorage all_float;  // FLOAT keeps every value read, HALF-stored ones included
  all_float.albedo = all_float.normal = io::PixelStorage::Float;
  const std::string path = (scratch.path / "frame.exr").string();
  io::write_frame(path, f, all_float);
  if (!same_frame(io::read_frame(path), f)) fail("the frame read back differs from the frame written");
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  Imf::Header::setMaxImageSize(kMaxSide, kMaxSide);
  Imf::Header::setMaxTileSize(kMaxSide, kMaxSide);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (declares_attribute_past_end(data, size)) return -1;  // -1: not kept in the corpus
  Frame f;
  try {
    f = io::read_frame_from_memory(reinterpret_cast<const char*>(data), size, kName);
  } catch (const io::IoError& e) {
    if (std::string(e.what()).rfind(std::string(kName) + ": ", 0) != 0)
      fail(std::string("an IoError does not name the input: ") + e.what());
    return 0;
  }
  try {
    check_frame_consistent(f);
  } catch (const std::invalid_argument& e) {
    fail(std::string("inconsistent frame: ") + e.what());
  }
  check_round_trip(f);
  return 0;
}
