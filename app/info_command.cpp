#include "app/info_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "cli/command_line.h"
#include "app/input_warnings.h"
#include "io/atomic_file.h"
#include "io/printable.h"
#include "io/sequence.h"

namespace svgf::app {
namespace {

using json = nlohmann::json;

// A channel's values over the frames read: finite ones give min, max and mean; the others are
// counted, per frame too.
struct ChannelStats {
  double min = std::numeric_limits<double>::infinity();
  double max = -std::numeric_limits<double>::infinity();
  double sum = 0;
  int64_t finite = 0;
  int64_t non_finite = 0;

  // Returns this image's non-finite values.
  int64_t add(const Image& im) {
    int64_t bad = 0;
    for (float v : im.data()) {
      if (!std::isfinite(v)) {
        ++bad;
        continue;
      }
      min = std::min(min, double(v));
      max = std::max(max, double(v));
      sum += v;
      ++finite;
    }
    non_finite += bad;
    return bad;
  }
  json to_json() const {
    json j = {{"non_finite", non_finite}, {"values", finite + non_finite}};
    if (finite > 0) {
      j["min"] = min;
      j["max"] = max;
      j["mean"] = sum / double(finite);
    }
    return j;
  }
};

// The frame's planes by channel name (docs/frame-format.md), absent optional ones left out.
std::vector<std::pair<const char*, const Image*>> channels_of(const Frame& f) {
  std::vector<std::pair<const char*, const Image*>> v = {
      {"color", &f.color},   {"albedo", &f.albedo}, {"normal", &f.normal},
      {"position", &f.position}, {"depth", &f.depth}, {"depth_gradient", &f.depth_gradient},
      {"motion", &f.motion}, {"emission", &f.emission}, {"reference", &f.reference},
      {"direct", &f.direct}, {"indirect", &f.indirect}, {"gradient", &f.gradient}};
  std::vector<std::pair<const char*, const Image*>> present;
  for (const auto& c : v)
    if (!c.second->empty()) present.push_back(c);
  return present;
}

std::string fixed(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

namespace {

struct InfoArgs {
  std::string dir, json;
};

int run_info(const InfoArgs& a) {
  const std::string& dir = a.dir;
  const io::Sequence seq(dir);  // the manifest: an IoError naming it when missing or bad
  const io::Manifest& m = seq.manifest();

  json report = {{"sequence", dir},
                 {"scene", m.scene},
                 {"width", m.width},
                 {"height", m.height},
                 {"frames", seq.size()},
                 {"spp", m.spp},
                 {"reference_spp", m.reference_spp},
                 {"generator", m.generator},
                 {"camera_cuts", m.camera_cuts}};
  std::map<std::string, ChannelStats> stats;
  json frames = json::array(), problems = json::array();
  int64_t surface = 0, pixels = 0;
  json warnings = json::array();
  Camera previous_camera;
  bool has_previous = false;
  for (int k = 0; k < seq.size(); ++k) {
    json fr = {{"frame", k}, {"file", m.frames[static_cast<size_t>(k)].name}};
    const auto problem = [&](const std::string& what) {
      problems.push_back(seq.path(k) + ": " + what);
      fr["problems"].push_back(what);
    };
    try {
      seq.verify_checksum(k);
      fr["sha256_ok"] = true;
    } catch (const io::IoError& e) {
      fr["sha256_ok"] = false;
      problem(std::string("SHA-256 differs from the manifest (") + e.what() + ")");
    }
    try {
      const Frame f = seq.read(k);
      json non_finite = json::object();
      for (const auto& [name, image] : channels_of(f))
        if (const int64_t bad = stats[name].add(*image); bad > 0) non_finite[name] = bad;
      if (!non_finite.empty()) {
        fr["non_finite"] = non_finite;
        problems.push_back(seq.path(k) + ": non-finite values " + non_finite.dump() +
                           " (svgf denoise repairs them: docs/bad-input.md)");
      }
      const bool cut = std::find(m.camera_cuts.begin(), m.camera_cuts.end(), k) != m.camera_cuts.end();
      for (const InputWarning& w : input_warnings(f, has_previous && !cut ? &previous_camera : nullptr)) {
        fr["warnings"].push_back(w.kind);
        warnings.push_back(seq.path(k) + ": " + w.text);
      }
      previous_camera = f.camera;
      has_previous = true;
      for (float d : f.depth.data()) surface += d > 0.f;
      pixels += static_cast<int64_t>(f.depth.pixel_count());
    } catch (const io::IoError& e) {
      problem(std::string("unreadable: ") + e.what());
    }
    frames.push_back(fr);
  }
  json channels = json::object();
  for (const auto& [name, s] : stats) channels[name] = s.to_json();
  report["channels"] = channels;
  report["surface_fraction"] = pixels > 0 ? double(surface) / double(pixels) : 0.0;
  report["per_frame"] = frames;
  report["problems"] = problems;
  report["warnings"] = warnings;
  int failed = 0;
  for (const json& fr : frames)
    failed += !fr.value("sha256_ok", false) || fr.contains("problems") ? 1 : 0;
  report["ok"] = failed == 0;

  std::printf("%s: %s, %dx%d, %d frames, %d spp (reference %d spp), %s\n",
              io::printable(dir).c_str(), m.scene.c_str(), m.width, m.height, seq.size(), m.spp,
              m.reference_spp, m.generator.c_str());
  if (!m.camera_cuts.empty()) std::printf("  camera cuts at %s\n", json(m.camera_cuts).dump().c_str());
  std::printf("  surface pixels    %.1f%%\n", 100.0 * report["surface_fraction"].get<double>());
  std::printf("  %-16s %14s %14s %14s %12s\n", "channel", "min", "max", "mean", "non-finite");
  for (const auto& [name, s] : stats) {
    const bool any = s.finite > 0;
    std::printf("  %-16s %14s %14s %14s %12lld\n", name.c_str(), any ? fixed(s.min).c_str() : "-",
                any ? fixed(s.max).c_str() : "-", any ? fixed(s.sum / double(s.finite)).c_str() : "-",
                static_cast<long long>(s.non_finite));
  }
  for (const json& p : problems)
    std::fprintf(stderr, "svgf: %s\n", io::printable(p.get<std::string>()).c_str());
  for (const json& w : warnings)
    std::fprintf(stderr, "svgf: warning: %s\n", io::printable(w.get<std::string>()).c_str());
  std::printf("  %s\n", failed == 0 ? "every frame reads and matches the manifest"
                                    : (std::to_string(failed) + " of " +
                                       std::to_string(seq.size()) + " frames failed").c_str());
  if (!a.json.empty()) io::write_file_atomically(a.json, report.dump(2) + "\n");
  return failed == 0 ? 0 : 1;
}

}  // namespace

CLI::App* add_info_command(CLI::App& svgf, int& status) {
  auto a = std::make_shared<InfoArgs>();
  CLI::App* sub = svgf.add_subcommand(
      "info", "what a sequence holds, checked against its manifest");
  sub->footer(
      "What the sequence folder SEQ holds: size, frames, channels with their value ranges and\n"
      "non-finite counts, surface coverage; each frame file checked against the manifest's\n"
      "SHA-256. Exit 0 when every frame reads and matches, 1 otherwise.");
  sub->add_option("SEQ", a->dir, "a sequence folder (manifest.json + frames)")->required();
  sub->add_option("--json", a->json, "also write the findings as JSON")->type_name("FILE");
  sub->callback([a, &status] { status = run_info(*a); });
  return sub;
}

int info_command(const std::vector<std::string>& args) {
  return cli::run_subcommand("svgf", add_info_command, args);
}

}  // namespace svgf::app
