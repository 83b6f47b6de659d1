#pragma once
// Helpers of the svgf denoise tests: generated sequences, scratch folders, folder snapshots.
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/sequence.h"
#include "synthetic_sequence.h"

namespace svgf::test {

namespace fs = std::filesystem;

// Removes an output folder and the failure report beside it.
inline void remove_output(const fs::path& out) {
  fs::remove_all(out);
  fs::remove(out.string() + ".failed-report.json");
}

// A path in the temp folder, unique to this process, removed if it exists.
inline fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("svgf_app_test_" + name + "_" + std::to_string(::getpid()));
  remove_output(p);
  return p;
}

// A synthetic sequence whose files, in manifest order, hold the given frame numbers.
inline fs::path write_numbered(const fs::path& dir, const std::vector<int>& numbers,
                               const SyntheticScene& scene = {}) {
  io::SequenceWriter writer(dir.string(), io::FrameStorage{});
  for (int n : numbers) writer.add(scene.frame(n));
  io::Manifest m;
  m.scene = "synthetic";
  m.generator = "app_test";
  writer.commit(m);
  return dir;
}

inline fs::path write_synthetic(const fs::path& dir, int frames, const SyntheticScene& scene = {}) {
  std::vector<int> numbers(static_cast<size_t>(frames));
  for (int k = 0; k < frames; ++k) numbers[static_cast<size_t>(k)] = k;
  return write_numbered(dir, numbers, scene);
}

inline std::string file_bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

inline std::vector<std::string> file_names(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

inline nlohmann::json read_json(const fs::path& p) {
  std::ifstream f(p);
  return nlohmann::json::parse(f);
}

// Every file under `dir` (relative path -> bytes): equal snapshots, byte-identical folders.
inline std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = file_bytes(e.path());
  return files;
}

// Names beside `out` that a run into it may leave: its staging and moved-aside folders.
inline std::vector<std::string> leftovers(const fs::path& out) {
  std::vector<std::string> found;
  const std::string base = out.filename().string();
  for (const std::string& name : file_names(out.parent_path()))
    if (name.rfind(base + ".tmp-", 0) == 0 || name.rfind(base + ".old-", 0) == 0)
      found.push_back(name);
  return found;
}

}  // namespace svgf::test
