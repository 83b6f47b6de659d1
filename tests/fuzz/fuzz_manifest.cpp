// libFuzzer target: the manifest parser (io::read_manifest) on arbitrary manifest.json bytes.
// read_manifest reads a folder's manifest.json, so each input is written there first (a tmpfs
// file write is cheap next to the parse). What must hold for every input, beyond ASan/UBSan
// finding nothing:
// - the parser returns a manifest or throws io::IoError naming the manifest file; no other
//   exception escapes (one would abort the run, which libFuzzer reports as a crash);
// - a manifest that reads keeps docs/frame-format.md's promises, checked here independently of
//   the parser: positive size, spp >= 1, reference_spp >= 0, frame files that are distinct
//   plain file names inside the folder with a 64-digit lowercase SHA-256, camera cuts that are
//   frame numbers;
// - write_manifest accepts it and reading that back gives the same manifest.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "io/printable.h"
#include "io/sequence.h"

namespace {

using namespace svgf;
namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "fuzz_manifest: %s\n", io::printable(what).c_str());  // names may hold NULs
  std::abort();
}

// Two folders of this process (the input's, the round trip's), removed at exit.
struct ScratchDirs {
  fs::path root = fs::temp_directory_path() / ("svgf_fuzz_manifest-" + std::to_string(::getpid()));
  std::string input = (root / "input").string();
  std::string written = (root / "written").string();
  ScratchDirs() {
    fs::create_directories(input);
    fs::create_directories(written);
  }
  ~ScratchDirs() {
    std::error_code ignored;
    fs::remove_all(root, ignored);
  }
};

// A name that opens a file directly inside the sequence folder: one path component, not "." or
// "..", and no NUL (the OS would end the path there, so two names could open one file).
bool names_a_file_in_the_folder(const std::string& name) {
  return !name.empty() && name != "." && name != ".." &&
         name.find_first_of(std::string("/\\\0", 3)) == std::string::npos;
}

bool is_lowercase_sha256(const std::string& s) {
  return s.size() == 64 && s.find_first_not_of("0123456789abcdef") == std::string::npos;
}

void check_promises(const io::Manifest& m) {
  if (m.format_version != 1) fail("format_version " + std::to_string(m.format_version));
  if (m.width <= 0 || m.height <= 0) fail("a size that is not positive");
  if (m.spp < 1 || m.reference_spp < 0) fail("spp " + std::to_string(m.spp) + ", reference_spp " +
                                             std::to_string(m.reference_spp));
  std::set<std::string> names;
  for (const io::ManifestFile& f : m.frames) {
    if (!names_a_file_in_the_folder(f.name)) fail("frame file '" + f.name + "' is not a plain name");
    if (!names.insert(f.name).second) fail("frame file '" + f.name + "' repeats");
    if (!is_lowercase_sha256(f.sha256)) fail("sha256 '" + f.sha256 + "'");
  }
  for (const int cut : m.camera_cuts)
    if (cut < 0 || cut >= static_cast<int>(m.frames.size()))
      fail("camera cut " + std::to_string(cut) + " outside the frames");
}

bool same_manifest(const io::Manifest& a, const io::Manifest& b) {
  if (a.frames.size() != b.frames.size()) return false;
  for (size_t i = 0; i < a.frames.size(); ++i)
    if (a.frames[i].name != b.frames[i].name || a.frames[i].sha256 != b.frames[i].sha256)
      return false;
  return a.format_version == b.format_version && a.scene == b.scene && a.width == b.width &&
         a.height == b.height && a.spp == b.spp && a.reference_spp == b.reference_spp &&
         a.seed == b.seed && a.generator == b.generator && a.camera_cuts == b.camera_cuts;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const ScratchDirs dirs;
  const std::string path = (fs::path(dirs.input) / "manifest.json").string();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out.flush()) fail("cannot write " + path);
  }
  io::Manifest m;
  try {
    m = io::read_manifest(dirs.input);
  } catch (const io::IoError& e) {
    if (std::string(e.what()).rfind(path + ": ", 0) != 0)
      fail(std::string("an IoError does not name the manifest: ") + e.what());
    return 0;
  }
  check_promises(m);
  io::write_manifest(dirs.written, m);
  if (!same_manifest(io::read_manifest(dirs.written), m))
    fail("the manifest read back differs from the manifest written");
  return 0;
}
