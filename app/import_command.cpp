// svgf import: per-buffer files from another renderer into a sequence (docs/import.md).
#include "app/import_command.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <regex>

#include <nlohmann/json.hpp>

#include "cli/command_line.h"
#include "app/folder_checks.h"
#include "app/import_frame.h"
#include "app/interrupt.h"
#include "cli/progress_bar.h"
#include "io/atomic_file.h"
#include "io/printable.h"
#include "io/sequence.h"
#include "io/staged_folder.h"

namespace fs = std::filesystem;

namespace svgf::app {
namespace {

constexpr const char* kReportName = "import.json";

// The GAMES202 homework 5 framework's file names (its LoadFrameInfo): no albedo, no motion.
const std::map<std::string, std::string> kGames202 = {
    {"color", "beauty_{N}.exr"}, {"normal", "normal_{N}.exr"}, {"position", "position_{N}.exr"},
    {"depth", "depth_{N}.exr"},  {"id", "ID_{N}.exr"},         {"matrices", "matrix_{N}.mat"}};

bool is_buffer_key(const std::string& key) {
  const auto& keys = import_buffer_keys();
  return std::find(keys.begin(), keys.end(), key) != keys.end();
}

// "A..B" (inclusive) or "A".
std::vector<int> parse_frames(const std::string& s) {
  const std::regex range(R"((\d{1,7})(?:\.\.(\d{1,7}))?)");
  std::smatch m;
  if (!std::regex_match(s, m, range))
    throw UsageError("--frames takes A..B or N (frame numbers >= 0), got '" + s + "'");
  const int a = std::stoi(m[1]), b = m[2].matched ? std::stoi(m[2]) : a;
  if (b < a) throw UsageError("--frames " + s + ": the range is empty");
  std::vector<int> frames;
  for (int n = a; n <= b; ++n) frames.push_back(n);
  return frames;
}

struct ImportArgs {
  std::string in_dir, out_dir, preset, map, frames;
  int spp = 1, reference_spp = 0;
  CLI::Option* reference_spp_option = nullptr;
  std::map<std::string, std::string> buffers;  // a pattern for each buffer key
  std::map<std::string, CLI::Option*> buffer_options;
};

// Patterns from the preset, then the mapping file, then the flags (each overriding the last).
std::map<std::string, std::string> patterns_from(const ImportArgs& o, std::string& frames_spec) {
  std::map<std::string, std::string> patterns;
  if (!o.preset.empty()) patterns = kGames202;  // the only preset (a validator says so)
  if (!o.map.empty()) {
    const std::string& path = o.map;
    std::ifstream in(path);
    if (!in) throw UsageError("--map: cannot read '" + path + "'");
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
      throw UsageError("--map: " + path + ": invalid JSON: " + e.what());
    }
    if (!j.is_object()) throw UsageError("--map: " + path + ": not a JSON object");
    for (const auto& [key, value] : j.items()) {
      if (!value.is_string())
        throw UsageError("--map: " + path + ": key '" + key + "' is not a string");
      if (key == "frames")
        frames_spec = value.get<std::string>();
      else if (is_buffer_key(key))
        patterns[key] = value.get<std::string>();
      else
        throw UsageError("--map: " + path + ": unknown key '" + key + "'");
    }
  }
  for (const std::string& key : import_buffer_keys())
    if (o.buffer_options.at(key)->count()) patterns[key] = o.buffers.at(key);
  if (!o.frames.empty()) frames_spec = o.frames;
  for (const char* needed : {"color", "normal"})
    if (!patterns.count(needed))
      throw UsageError(std::string("no pattern for the ") + needed + " buffer (--" + needed +
                       ", --map or --preset)");
  for (const auto& [key, pattern] : patterns) {
    if (pattern.empty()) throw UsageError("--" + key + ": empty pattern");
    try {
      expand_pattern(pattern, 0);
    } catch (const std::invalid_argument& e) {
      throw UsageError("--" + key + ": " + e.what());
    }
  }
  return patterns;
}

// The frame numbers whose color file exists: the color pattern's {N} matched against the names
// in its folder.
std::vector<int> discover_frames(const std::string& in_dir, const std::string& color) {
  const fs::path pattern(color);
  const std::string name = pattern.filename().string();
  if (has_placeholder(pattern.parent_path().string()))
    throw UsageError("--color: {N} in a folder name; give --frames A..B");
  const size_t at = name.find("{N"), close = name.find('}', at);
  const std::string prefix = name.substr(0, at), suffix = name.substr(close + 1);
  const fs::path folder = fs::path(in_dir) / pattern.parent_path();
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw io::IoError(folder.string() + ": folder does not exist");
  std::vector<int> frames;
  for (const auto& e : fs::directory_iterator(folder, ec)) {
    const std::string f = e.path().filename().string();
    if (f.size() <= prefix.size() + suffix.size() || f.compare(0, prefix.size(), prefix) != 0 ||
        f.compare(f.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    const std::string digits = f.substr(prefix.size(), f.size() - prefix.size() - suffix.size());
    if (digits.size() > 7 || !std::all_of(digits.begin(), digits.end(), ::isdigit)) continue;
    const int n = std::stoi(digits);
    if (expand_pattern(name, n) == f) frames.push_back(n);  // the width matches too
  }
  if (ec) throw io::IoError(folder.string() + ": cannot list (" + ec.message() + ")");
  if (frames.empty())
    throw io::IoError(folder.string() + ": no file matches the color pattern '" + name + "'");
  std::sort(frames.begin(), frames.end());
  return frames;
}

struct Run {
  ImportSpec spec;
  std::vector<int> frames;
  std::string out_dir;
  int spp = 1, reference_spp = 0;
};

// Imports every frame, writing each to `writer` when there is one (the second pass) or only
// checking it (the first). Motion from matrices needs the previous frame's matrices: frame n's
// come from n - 1 when it is imported.
void import_all(const Run& run, ImportNotes& notes, io::SequenceWriter* writer, const char* label) {
  cli::ProgressBar bar(label, static_cast<int>(run.frames.size()));
  io::SceneMatrices previous, current;
  int width = 0, height = 0, last = -2, done = 0;
  for (int n : run.frames) {
    throw_if_interrupted();
    const bool has_previous = n == last + 1 && run.spec.patterns.count("matrices");
    const Frame f = import_frame(run.spec, n, width, height, has_previous ? &previous : nullptr,
                                 &current, notes);
    width = f.width();
    height = f.height();
    if (writer) writer->add(f);
    previous = current;
    last = n;
    bar.update(++done, "frame " + std::to_string(n));
  }
}

nlohmann::ordered_json report_of(const Run& run, const ImportNotes& notes) {
  nlohmann::ordered_json j;
  j["input"] = run.spec.in_dir;
  j["patterns"] = run.spec.patterns;
  j["frames"] = run.frames;
  j["sources"] = notes.sources;
  j["warnings"] = notes.warnings;
  return j;
}

int run_import(const ImportArgs& o) {
  Run run;
  run.spec.in_dir = o.in_dir;
  std::string frames_spec;
  run.spec.patterns = patterns_from(o, frames_spec);
  check_folders_apart(run.spec.in_dir, o.out_dir);
  run.out_dir = output_folder(o.out_dir, "manifest.json");
  run.spp = o.spp;
  run.reference_spp = o.reference_spp_option->count() ? o.reference_spp
                                                       : run.spec.patterns.count("reference") ? 1 : 0;
  if (run.reference_spp > 0 && !run.spec.patterns.count("reference"))
    throw UsageError("--reference-spp without a --reference pattern");
  const std::string& color = run.spec.patterns.at("color");
  if (!has_placeholder(color)) {
    if (!frames_spec.empty()) throw UsageError("--frames needs {N} in the color pattern");
    run.frames = {0};
  } else if (!frames_spec.empty()) {
    run.frames = parse_frames(frames_spec);
  }

  const InterruptGuard interrupts;
  try {
    if (run.frames.empty()) run.frames = discover_frames(run.spec.in_dir, color);
    run.spec.frame_count = static_cast<int>(run.frames.size());
    ImportNotes notes;
    import_all(run, notes, nullptr, "check ");  // every file, before anything is written
    io::FrameStorage storage;  // FLOAT throughout: the input's values are kept as they are
    storage.albedo = storage.normal = io::PixelStorage::Float;
    io::SequenceWriter writer(run.out_dir, storage);
    ImportNotes written;
    import_all(run, written, &writer, "import");
    io::write_file_atomically((fs::path(writer.staging_dir()) / kReportName).string(),
                              report_of(run, notes).dump(2) + "\n");
    io::Manifest m;
    m.scene = fs::path(io::normalized_folder(run.spec.in_dir)).filename().string();
    m.spp = run.spp;
    m.reference_spp = run.reference_spp;
    m.generator = "svgf import 1";
    writer.commit(m);
    for (const std::string& w : notes.warnings)
      std::fprintf(stderr, "svgf: warning: %s\n", io::printable(w).c_str());
    std::fprintf(stderr, "svgf: imported %zu frame%s into %s (what was derived: %s)\n",
                 run.frames.size(), run.frames.size() == 1 ? "" : "s", io::printable(run.out_dir).c_str(),
                 io::printable((fs::path(run.out_dir) / kReportName).string()).c_str());
    return 0;
  } catch (const Interrupted& e) {
    std::fprintf(stderr, "svgf: %s; %s left as it was\n", e.what(), io::printable(run.out_dir).c_str());
    return 128 + e.signal_number();
  }
}

}  // namespace

CLI::App* add_import_command(CLI::App& svgf, int& status) {
  auto o = std::make_shared<ImportArgs>();
  CLI::App* sub = svgf.add_subcommand(
      "import", "per-buffer files (EXR, .hdr, PFM; GAMES202) into a sequence");
  sub->footer(
      "Turns per-buffer image files (.exr, .hdr, .pfm) into a sequence in OUT_DIR\n"
      "(docs/import.md). Patterns are file names relative to IN_DIR with {N} for the frame\n"
      "number ({N:4}: zero-padded to 4 digits); a pattern without {N} is one frame (0).\n"
      "Every file is checked before anything is written; OUT_DIR (absent, empty or a\n"
      "sequence) is replaced as a whole, with OUT_DIR/import.json saying what was derived.\n"
      "Absent albedo is 1, depth gradient is derived from depth, motion from matrices or 0,\n"
      "mesh ids from --id or depth > 0; each is named in import.json and warned about.");
  sub->add_option("IN_DIR", o->in_dir, "the folder the patterns are relative to")->required();
  sub->add_option("OUT_DIR", o->out_dir, "the sequence folder, replaced as a whole")->required();
  const std::map<std::string, std::string> what = {
      {"color", "noisy color (required)"},
      {"normal", "world normals (required)"},
      {"motion", "pixels to the previous frame, +y down"},
      {"id", "object ids from 0, negative = background"},
      {"matrices", "GAMES202 matrix_N.mat: motion (and depth) from matrices"}};
  for (const std::string& key : import_buffer_keys()) {
    const auto it = what.find(key);
    o->buffer_options[key] =
        sub->add_option("--" + key, o->buffers[key],
                        "pattern of the " + key + " buffer" +
                            (it == what.end() ? std::string() : ": " + it->second))
            ->type_name("P")
            ->group("buffers (color and normal required)");
  }
  sub->add_option("--preset", o->preset,
                  "games202: beauty_{N}.exr normal_{N}.exr position_{N}.exr depth_{N}.exr "
                  "ID_{N}.exr matrix_{N}.mat")
      ->type_name("NAME")
      ->check(CLI::IsMember({"games202"}));
  sub->add_option("--map", o->map,
                  "JSON object: the buffer keys above (and \"frames\") -> patterns")
      ->type_name("FILE");
  sub->add_option("--frames", o->frames,
                  "frame numbers (default: every N whose color file exists)")
      ->type_name("A..B");
  sub->add_option("--spp", o->spp, "what the manifest says (default 1)")
      ->type_name("N")
      ->check(CLI::Range(1, 1 << 20));
  o->reference_spp_option =
      sub->add_option("--reference-spp", o->reference_spp,
                      "what the manifest says (default 1; 0 without a reference)")
          ->type_name("N")
          ->check(CLI::Range(0, 1 << 20));
  sub->callback([o, &status] { status = run_import(*o); });
  return sub;
}

int import_command(const std::vector<std::string>& args) {
  return cli::run_subcommand("svgf", add_import_command, args);
}

}  // namespace svgf::app
