#include "io/sequence.h"

#include <algorithm>
#include <climits>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "io/atomic_file.h"
#include "io/sha256.h"

namespace svgf::io {
namespace fs = std::filesystem;
namespace {

constexpr const char* kManifestName = "manifest.json";
constexpr const char* kFormat = "svgf-sequence";

std::string manifest_path(const std::string& dir) { return (fs::path(dir) / kManifestName).string(); }

std::string size_str(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

// No NUL either: the OS ends a path there, so "a.exr\0x" would open a.exr under another name.
bool is_plain_file_name(const std::string& s) {
  return !s.empty() && s != "." && s != ".." && s.find('/') == std::string::npos &&
         s.find('\\') == std::string::npos && s.find('\0') == std::string::npos;
}

bool is_sha256_hex(const std::string& s) {
  return s.size() == 64 && std::all_of(s.begin(), s.end(), [](char c) {
           return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
         });
}

// The first semantic problem of a manifest ("key 'width' must be positive"), or "" if none.
// Shared by reader and writer so that whatever is written can be read back.
std::string manifest_problem(const Manifest& m) {
  if (m.format_version != 1)
    return "key 'format_version' is " + std::to_string(m.format_version) + ", expected 1";
  if (m.width <= 0) return "key 'width' must be positive";
  if (m.height <= 0) return "key 'height' must be positive";
  if (m.spp < 1) return "key 'spp' must be at least 1";
  if (m.reference_spp < 0) return "key 'reference_spp' must not be negative";
  std::set<std::string> names;
  for (size_t i = 0; i < m.frames.size(); ++i) {
    const std::string key = "frames[" + std::to_string(i) + "]";
    if (!is_plain_file_name(m.frames[i].name))
      return "key '" + key + ".file' is not a plain file name: '" + m.frames[i].name + "'";
    if (!names.insert(m.frames[i].name).second)
      return "key '" + key + ".file' repeats '" + m.frames[i].name + "'";
    if (!is_sha256_hex(m.frames[i].sha256))
      return "key '" + key + ".sha256' is not 64 lowercase hex digits";
  }
  for (size_t i = 0; i < m.camera_cuts.size(); ++i)
    if (m.camera_cuts[i] < 0 || m.camera_cuts[i] >= static_cast<int>(m.frames.size()))
      return "key 'camera_cuts[" + std::to_string(i) + "]' is " +
             std::to_string(m.camera_cuts[i]) + ", outside the " +
             std::to_string(m.frames.size()) + " frames";
  return "";
}

// Typed access to JSON keys; failures name the manifest and the key.
class JsonReader {
 public:
  explicit JsonReader(const std::string& path) : path_(path) {}

  const nlohmann::json& need(const nlohmann::json& obj, const std::string& key,
                             const std::string& where) const {
    auto it = obj.find(key);
    if (it == obj.end()) fail(where + key, "is missing");
    return *it;
  }
  std::string get_string(const nlohmann::json& obj, const std::string& key,
                         const std::string& where = "") const {
    const auto& v = need(obj, key, where);
    if (!v.is_string()) fail(where + key, "is not a string");
    return v.get<std::string>();
  }
  int as_int(const nlohmann::json& v, const std::string& key) const {
    if (!v.is_number_integer()) fail(key, "is not an integer");
    if (v.is_number_unsigned() ? v.get<uint64_t>() > uint64_t(INT_MAX)
                               : (v.get<int64_t>() < INT_MIN || v.get<int64_t>() > INT_MAX))
      fail(key, "is out of range");
    return v.get<int>();
  }
  int get_int(const nlohmann::json& obj, const std::string& key) const {
    return as_int(need(obj, key, ""), key);
  }
  uint64_t get_uint64(const nlohmann::json& obj, const std::string& key) const {
    const auto& v = need(obj, key, "");
    if (!v.is_number_unsigned()) fail(key, "is not a non-negative integer");
    return v.get<uint64_t>();
  }
  const nlohmann::json& get_array(const nlohmann::json& obj, const std::string& key) const {
    const auto& v = need(obj, key, "");
    if (!v.is_array()) fail(key, "is not an array");
    return v;
  }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw IoError(path_ + ": key '" + key + "' " + what);
  }

 private:
  const std::string& path_;
};

}  // namespace

std::string frame_file_name(int index) {
  if (index < 0) throw std::invalid_argument("frame_file_name: negative index");
  char buf[32];
  std::snprintf(buf, sizeof(buf), "frame_%04d.exr", index);
  return buf;
}

Manifest read_manifest(const std::string& dir) {
  const std::string path = manifest_path(dir);
  std::error_code ec;
  if (!fs::exists(path, ec)) throw IoError(path + ": file does not exist");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open file for reading");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw IoError(path + ": invalid JSON: " + e.what());
  }
  if (!j.is_object()) throw IoError(path + ": not a JSON object");

  const JsonReader r(path);
  const std::string format = r.get_string(j, "format");
  if (format != kFormat)
    r.fail("format", "is '" + format + "', expected '" + std::string(kFormat) + "'");
  Manifest m;
  m.format_version = r.get_int(j, "format_version");
  if (m.format_version != 1)
    r.fail("format_version", "is " + std::to_string(m.format_version) + ", expected 1");
  m.scene = r.get_string(j, "scene");
  m.width = r.get_int(j, "width");
  m.height = r.get_int(j, "height");
  m.spp = r.get_int(j, "spp");
  m.reference_spp = r.get_int(j, "reference_spp");
  m.seed = r.get_uint64(j, "seed");
  m.generator = r.get_string(j, "generator");
  const auto& frames = r.get_array(j, "frames");
  for (size_t i = 0; i < frames.size(); ++i) {
    const std::string where = "frames[" + std::to_string(i) + "].";
    if (!frames[i].is_object()) r.fail("frames[" + std::to_string(i) + "]", "is not an object");
    m.frames.push_back({r.get_string(frames[i], "file", where),
                        r.get_string(frames[i], "sha256", where)});
  }
  const auto& cuts = r.get_array(j, "camera_cuts");
  for (size_t i = 0; i < cuts.size(); ++i)
    m.camera_cuts.push_back(r.as_int(cuts[i], "camera_cuts[" + std::to_string(i) + "]"));
  if (const std::string problem = manifest_problem(m); !problem.empty())
    throw IoError(path + ": " + problem);
  return m;
}

void write_manifest(const std::string& dir, const Manifest& m) {
  const std::string path = manifest_path(dir);
  if (const std::string problem = manifest_problem(m); !problem.empty())
    throw std::invalid_argument(path + ": " + problem);
  // ordered_json keeps the keys in this (documented) order rather than sorting them.
  nlohmann::ordered_json j;
  j["format"] = kFormat;
  j["format_version"] = m.format_version;
  j["scene"] = m.scene;
  j["width"] = m.width;
  j["height"] = m.height;
  j["spp"] = m.spp;
  j["reference_spp"] = m.reference_spp;
  j["seed"] = m.seed;
  j["generator"] = m.generator;
  j["frames"] = nlohmann::ordered_json::array();
  for (const auto& f : m.frames) j["frames"].push_back({{"file", f.name}, {"sha256", f.sha256}});
  j["camera_cuts"] = m.camera_cuts;
  write_file_atomically(path, j.dump(2) + "\n");
}

Sequence::Sequence(const std::string& dir) : dir_(dir), manifest_(read_manifest(dir)) {}

std::string Sequence::path(int k) const {
  if (k < 0 || k >= size())
    throw std::out_of_range(dir_ + ": frame " + std::to_string(k) + " outside the sequence's " +
                            std::to_string(size()) + " frames");
  return (fs::path(dir_) / manifest_.frames[static_cast<size_t>(k)].name).string();
}

Frame Sequence::read(int k) const {
  const std::string p = path(k);
  bool has_index = false;
  // The size is checked from the header, before anything is allocated.
  Frame f = detail::read_frame(p, &has_index, {manifest_.width, manifest_.height, "manifest"});
  if (!has_index) f.index = k;
  return f;
}

FrameHeader Sequence::read_header(int k) const {
  FrameHeader h = read_frame_header(path(k), {manifest_.width, manifest_.height, "manifest"});
  if (!h.has_index) h.index = k;
  return h;
}

bool Sequence::is_camera_cut(int k) const {
  return std::find(manifest_.camera_cuts.begin(), manifest_.camera_cuts.end(), k) !=
         manifest_.camera_cuts.end();
}

void Sequence::verify_checksum(int k) const {
  const std::string p = path(k);
  const std::string& expected = manifest_.frames[static_cast<size_t>(k)].sha256;
  const std::string actual = sha256_file(p);
  if (actual != expected)
    throw IoError(p + ": SHA-256 is " + actual + ", manifest says " + expected);
}

// The manifest marks a folder as a sequence: only a sequence (or an empty folder) is replaced,
// so a wrong `dir` such as the fixtures root is never wiped.
SequenceWriter::SequenceWriter(const std::string& dir, const FrameStorage& storage)
    : folder_(dir, kManifestName), storage_(storage) {}

void SequenceWriter::add(const Frame& frame) {
  if (committed_) throw std::logic_error(folder_.dir() + ": SequenceWriter::add after commit");
  const int n = static_cast<int>(files_.size());
  if (n > 0 && (frame.width() != width_ || frame.height() != height_))
    throw std::invalid_argument(folder_.dir() + ": frame " + std::to_string(n) + " is " +
                                size_str(frame.width(), frame.height()) +
                                ", earlier frames are " + size_str(width_, height_));
  const std::string name = frame_file_name(n);
  const std::string path = (fs::path(folder_.path()) / name).string();
  write_frame(path, frame, storage_);
  files_.push_back({name, sha256_file(path)});
  width_ = frame.width();
  height_ = frame.height();
}

void SequenceWriter::commit(Manifest manifest) {
  if (committed_) throw std::logic_error(folder_.dir() + ": SequenceWriter::commit called twice");
  if (!files_.empty()) {
    if (manifest.width == 0 && manifest.height == 0) {
      manifest.width = width_;
      manifest.height = height_;
    } else if (manifest.width != width_ || manifest.height != height_) {
      throw std::invalid_argument(folder_.dir() + ": manifest says " +
                                  size_str(manifest.width, manifest.height) + ", frames are " +
                                  size_str(width_, height_));
    }
  }
  manifest.frames = files_;
  write_manifest(folder_.path(), manifest);
  folder_.commit();
  committed_ = true;
}

}  // namespace svgf::io
