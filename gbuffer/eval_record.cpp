#include "gbuffer/eval_record.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "io/atomic_file.h"

namespace fs = std::filesystem;

namespace svgf::gbuffer {

namespace {

constexpr const char* kFormat = "svgf-eval-sequence";
// Version 2 added the reference noise per frame; a version 1 record reads with none recorded.
constexpr int kFormatVersion = 2;

std::string record_path(const std::string& dir) { return (fs::path(dir) / "eval.json").string(); }

std::string size_of(const EvalRecord& r) {
  return std::to_string(r.width) + "x" + std::to_string(r.height);
}

// One number per frame, null where there is none (NaN); absent (older records): all NaN.
std::vector<double> read_per_frame(const nlohmann::json& j, const char* key, int frames) {
  std::vector<double> v(static_cast<size_t>(frames), std::nan(""));
  if (!j.contains(key)) return v;
  const nlohmann::json& a = j.at(key);
  if (!a.is_array() || static_cast<int>(a.size()) != frames)
    throw std::runtime_error(std::string("'") + key + "' does not list one entry per frame");
  for (size_t k = 0; k < a.size(); ++k)
    if (!a[k].is_null()) v[k] = a[k].get<double>();
  return v;
}

nlohmann::ordered_json per_frame_json(const EvalRecord& r, double ReferenceNoise::*field) {
  nlohmann::ordered_json a = nlohmann::ordered_json::array();
  for (int k = 0; k < r.frames; ++k) {
    const size_t i = static_cast<size_t>(k);
    const double x = i < r.reference_noise.size() ? r.reference_noise[i].*field : std::nan("");
    a.push_back(std::isfinite(x) ? nlohmann::ordered_json(x) : nlohmann::ordered_json(nullptr));
  }
  return a;
}

}  // namespace

bool EvalRecord::complete() const {
  if (static_cast<int>(sha256.size()) != frames) return false;
  for (const std::string& s : sha256)
    if (s.empty()) return false;
  return true;
}

SequenceNoise sequence_reference_noise(const EvalRecord& r) {
  const SequenceNoise none{std::nan(""), std::nan("")};
  const size_t n = static_cast<size_t>(r.frames);
  if (r.frames < 1 || r.reference_noise.size() != n) return none;
  double sum = 0, clamped = 0;
  for (const ReferenceNoise& f : r.reference_noise) {
    const double v = f.mse, share = f.clamped_share;
    if (!std::isfinite(v) || !std::isfinite(share)) return none;
    sum += v;
    clamped += v * share;
  }
  return {sum / r.frames, sum > 0 ? clamped / sum : 0.0};
}

std::vector<std::string> parameter_differences(const EvalRecord& c, const EvalRecord& w) {
  std::vector<std::string> d;
  auto differ = [&d](const std::string& what, const std::string& cached, const std::string& wanted) {
    if (cached != wanted) d.push_back(what + " " + cached + " in the cache, " + wanted + " asked");
  };
  auto yes_no = [](bool b) { return std::string(b ? "on" : "off"); };
  differ("scene", c.scene, w.scene);
  differ("size", size_of(c), size_of(w));
  differ("frames", std::to_string(c.frames), std::to_string(w.frames));
  differ("spp", std::to_string(c.spp), std::to_string(w.spp));
  differ("reference spp", std::to_string(c.reference_spp), std::to_string(w.reference_spp));
  differ("seed", std::to_string(c.seed), std::to_string(w.seed));
  differ("generator", "'" + c.generator + "'", "'" + w.generator + "'");
  differ("split", yes_no(c.split), yes_no(w.split));
  differ("gradient samples", yes_no(c.gradients), yes_no(w.gradients));
  return d;
}

std::optional<EvalRecord> read_eval_record(const std::string& dir) {
  const std::string path = record_path(dir);
  if (!fs::exists(path)) return std::nullopt;
  try {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot open it");
    const nlohmann::json j = nlohmann::json::parse(in);
    const int version = j.at("format").get<std::string>() == kFormat
                            ? j.at("format_version").get<int>() : 0;
    if (version < 1 || version > kFormatVersion)
      throw std::runtime_error("not an eval.json of format version 1 to " +
                               std::to_string(kFormatVersion));
    EvalRecord r;
    r.scene = j.at("scene").get<std::string>();
    r.generator = j.at("generator").get<std::string>();
    r.width = j.at("width").get<int>();
    r.height = j.at("height").get<int>();
    r.frames = j.at("frames").get<int>();
    r.spp = j.at("spp").get<int>();
    r.reference_spp = j.at("reference_spp").get<int>();
    r.seed = j.at("seed").get<uint64_t>();
    r.split = j.at("split").get<bool>();
    r.gradients = j.at("gradients").get<bool>();
    r.sha256 = j.at("sha256").get<std::vector<std::string>>();
    if (r.frames < 1 || static_cast<int>(r.sha256.size()) != r.frames)
      throw std::runtime_error("'sha256' does not list one entry per frame");
    const std::vector<double> mse = read_per_frame(j, "reference_noise_mse", r.frames),
                              se = read_per_frame(j, "reference_noise_se", r.frames),
                              share = read_per_frame(j, "reference_noise_clamped_share", r.frames);
    for (size_t k = 0; k < mse.size(); ++k) r.reference_noise.push_back({mse[k], se[k], share[k]});
    r.records_reference_noise = version >= 2;
    return r;
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": unreadable: " + e.what());
  }
}

void write_eval_record(const std::string& dir, const EvalRecord& r) {
  nlohmann::ordered_json j;
  j["format"] = kFormat;
  j["format_version"] = kFormatVersion;
  j["scene"] = r.scene;
  j["generator"] = r.generator;
  j["width"] = r.width;
  j["height"] = r.height;
  j["frames"] = r.frames;
  j["spp"] = r.spp;
  j["reference_spp"] = r.reference_spp;
  j["seed"] = r.seed;
  j["split"] = r.split;
  j["gradients"] = r.gradients;
  j["sha256"] = r.sha256;  // "" for a frame not written yet
  // One array per field, null where none is recorded.
  j["reference_noise_mse"] = per_frame_json(r, &ReferenceNoise::mse);
  j["reference_noise_se"] = per_frame_json(r, &ReferenceNoise::standard_error);
  j["reference_noise_clamped_share"] = per_frame_json(r, &ReferenceNoise::clamped_share);
  io::write_file_atomically(record_path(dir), j.dump(2) + "\n");
}

}  // namespace svgf::gbuffer
