#include "bench/results.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace svgf::bench {
namespace {

// Fields (JSON pointers) the writers read from every entry of a list.
const char* const kTimingFields[] = {"/group",
                                     "/key",
                                     "/label",
                                     "/input/width",
                                     "/input/height",
                                     "/input/pixels",
                                     "/config",
                                     "/frame_ms/filter/median",
                                     "/frame_ms/filter/p95"};
const char* const kQualityFields[] = {"/key", "/scene", "/mean", "/frames"};

template <size_t N>
void check_entries(const json& doc, const char* list, const char* const (&fields)[N],
                   const fs::path& file) {
  if (!doc.contains(list)) return;
  if (!doc[list].is_array())
    throw std::runtime_error(file.string() + ": \"" + list + "\" is not a list");
  for (const json& e : doc[list]) {
    if (e.contains("error")) continue;  // a failed run: kept in the file, never read
    for (const char* f : fields)
      if (!e.contains(json::json_pointer(f)))
        throw std::runtime_error(file.string() + ": an entry of \"" + list + "\" (" +
                                 e.value("key", std::string("no key")) + ") has no " + f);
  }
}

// OpenCV baselines were named like the project's methods ("gaussian s1") before the "cv-"
// prefix; such entries are read under their present names.
void rename_legacy_baselines(json& doc) {
  for (const char* l : {"timings", "quality"}) {
    if (!doc.contains(l)) continue;
    for (json& e : doc[l]) {
      json& c = e["config"];
      if (!c.is_object() || c.value("mode", "") != "opencv" ||
          c.value("method", "").rfind("cv-", 0) == 0)
        continue;
      for (json* j : {&e, &c})
        for (const char* field : {"key", "label", "method"})
          if (j->contains(field)) (*j)[field] = "cv-" + (*j)[field].get<std::string>();
    }
  }
}

// A suite's list `name`, or an empty one.
const json& list(const json& suite, const char* name) {
  static const json kNone = json::array();
  const auto it = suite.find(name);
  return it == suite.end() ? kNone : *it;
}

}  // namespace

const json* Results::suite(const std::string& name) const {
  auto it = suites.find(name);
  return it == suites.end() ? nullptr : &it->second;
}

std::vector<const json*> Results::timings(const std::string& suite_name,
                                          const std::string& section) const {
  std::vector<const json*> v;
  if (const json* s = suite(suite_name))
    for (const json& e : list(*s, "timings"))
      if (e.value("group", "") == section && !e.contains("error")) v.push_back(&e);
  return v;
}

namespace {

// On the evaluation set a clean scene's entry has the PSNR with the reference's own noise taken
// out (bench/eval_quality.h): the charts and curves take it as the entry's PSNR, the measured
// one kept as psnr_measured.
json with_corrected_psnr(json e) {
  auto swap_in = [](json& m) {
    if (!m.contains("psnr_corrected")) return;
    m["psnr_measured"] = m["psnr"];
    m["psnr"] = m["psnr_corrected"];
  };
  if (!e.contains("mean") || !e["mean"].contains("psnr_corrected")) return e;
  swap_in(e["mean"]);
  for (json& f : e["frames"]) swap_in(f);
  return e;
}

}  // namespace

std::map<std::string, json> Results::quality(const std::string& key) const {
  std::map<std::string, json> by_scene;
  if (!eval_quality.is_null()) {
    for (const json& e : eval_quality["quality"])
      if (e["key"] == key && !e.contains("error"))
        by_scene[e["scene"].get<std::string>()] = with_corrected_psnr(e);
    return by_scene;
  }
  for (const char* s : {"gpu", "cpu"})
    if (const json* doc = suite(s))
      for (const json& e : list(*doc, "quality"))
        if (e["key"] == key && !e.contains("error") &&
            !by_scene.count(e["scene"].get<std::string>()))
          by_scene[e["scene"].get<std::string>()] = e;
  return by_scene;
}

Results load_results(const std::string& dir) {
  Results r;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const fs::path& file = entry.path();
    if (file.extension() != ".json") continue;
    std::ifstream in(file);
    json doc = json::parse(in, nullptr, false);
    if (doc.is_discarded()) throw std::runtime_error(file.string() + ": not valid JSON");
    if (!doc.contains("suite")) continue;
    if (!doc["suite"].is_string())
      throw std::runtime_error(file.string() + ": \"suite\" is not a name");
    check_entries(doc, "timings", kTimingFields, file);
    check_entries(doc, "quality", kQualityFields, file);
    rename_legacy_baselines(doc);
    const std::string name = doc["suite"].get<std::string>();  // before doc is moved from
    r.suites[name] = std::move(doc);
  }
  if (r.suites.empty()) throw std::runtime_error("no suite results (cpu.json, gpu.json) in " + dir);
  return r;
}

void load_eval_quality(Results& r, const std::string& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot read " + file);
  json doc = json::parse(in, nullptr, false);
  if (doc.is_discarded()) throw std::runtime_error(file + ": not valid JSON");
  if (doc.value("kind", "") != "eval-quality" || !doc.contains("set"))
    throw std::runtime_error(file + ": not a quality file of `svgf-bench quality`");
  check_entries(doc, "quality", kQualityFields, fs::path(file));
  r.eval_quality = std::move(doc);
}

std::string size_of(const json& e) {
  return std::to_string(e["input"]["width"].get<int>()) + "x" +
         std::to_string(e["input"]["height"].get<int>());
}
double mpix(const json& e) { return e["input"]["pixels"].get<double>() / 1e6; }
double median_ms(const json& e) { return e["frame_ms"]["filter"]["median"].get<double>(); }
double p95_ms(const json& e) { return e["frame_ms"]["filter"]["p95"].get<double>(); }
double num(const json& v) { return v.is_number() ? v.get<double>() : std::nan(""); }

}  // namespace svgf::bench
