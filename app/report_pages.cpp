#include "app/report_pages.h"

#include <cmath>
#include <cstdio>
#include <map>

#include "app/report_images.h"

namespace svgf::app {
namespace {

double number_or_nan(const nlohmann::json& frame, const char* key) {
  return frame.contains(key) && frame[key].is_number() ? frame[key].get<double>() : NAN;
}

std::string fixed(double v, const char* unit, int digits = 3) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f%s", digits, v, unit);
  return buf;
}

std::string frames_text(size_t n) { return std::to_string(n) + (n == 1 ? " frame" : " frames"); }

// A plot of report keys, one series per key.
HtmlPlot plot_of(const nlohmann::json& frames, const std::string& title, bool log_scale,
                 const std::vector<std::pair<std::string, const char*>>& series) {
  HtmlPlot plot{title, {}, log_scale};
  for (const auto& [name, key] : series) {
    HtmlSeries s{name, {}};
    for (const auto& f : frames) s.values.push_back(number_or_nan(f, key));
    plot.series.push_back(std::move(s));
  }
  return plot;
}

}  // namespace

HtmlReport denoise_page(const nlohmann::json& report, std::vector<std::vector<HtmlImage>> images,
                        const std::string& images_note) {
  const nlohmann::json& frames = report.at("frames");
  HtmlReport page;
  page.title = "svgf denoise: " + report.value("scene", std::string("?"));
  page.subtitle = frames_text(frames.size()) + " of " + std::to_string(report.value("width", 0)) +
                  "x" + std::to_string(report.value("height", 0)) + " from " +
                  report.value("input", std::string()) + ", " +
                  report.value("denoiser", std::string());
  for (const auto& f : frames)
    page.frames.push_back(f.value("input", std::to_string(f.value("frame", 0))));

  page.plots.push_back(plot_of(frames, "PSNR (dB, higher is better)", false,
                               {{"noisy", "psnr_noisy_db"}, {"denoised", "psnr_denoised_db"}}));
  page.plots.push_back(plot_of(frames, "relMSE (lower is better)", true,
                               {{"noisy", "relmse_noisy"}, {"denoised", "relmse_denoised"}}));
  // Time per frame and per stage, stages by name (the method's own: core/denoiser.h).
  std::map<std::string, std::vector<double>> stages;
  for (size_t k = 0; k < frames.size(); ++k) {
    const nlohmann::json stage_ms = frames[k].value("stage_ms", nlohmann::json::object());
    for (const auto& [stage, ms] : stage_ms.items()) {
      auto& values = stages[stage];
      values.resize(frames.size(), NAN);
      values[k] = ms.get<double>();
    }
  }
  HtmlPlot times = plot_of(frames, "time (ms)", false, {{"frame", "time_ms"}});
  for (auto& [stage, values] : stages) {
    values.resize(frames.size(), NAN);
    times.series.push_back({stage, values});
  }
  page.plots.push_back(std::move(times));

  page.images = std::move(images);
  page.images_note = images_note;
  page.colour_bar = error_map_colour_bar();

  HtmlTable run{"Configuration", {}};
  run.rows = {{"input", report.value("input", std::string())},
              {"scene", report.value("scene", std::string())},
              {"size", std::to_string(report.value("width", 0)) + " x " +
                           std::to_string(report.value("height", 0))},
              {"denoiser", report.value("denoiser", std::string())},
              {"frames", std::to_string(frames.size())}};
  HtmlTable timing{"Mean time per frame (I/O excluded)", {}};
  if (report.contains("mean_time_ms"))
    timing.rows.push_back({"frame", fixed(report["mean_time_ms"].get<double>(), " ms")});
  for (const auto& [stage, values] : stages) {
    double sum = 0;
    int count = 0;
    for (double v : values)
      if (std::isfinite(v)) sum += v, ++count;
    if (count) timing.rows.push_back({stage, fixed(sum / count, " ms")});
  }
  HtmlTable quality{"Quality and input (means over the frames)", {}};
  if (report.contains("mean_psnr_noisy_db"))
    quality.rows.push_back(
        {"PSNR noisy", fixed(report["mean_psnr_noisy_db"].get<double>(), " dB", 2)});
  if (report.contains("mean_psnr_denoised_db"))
    quality.rows.push_back(
        {"PSNR denoised", fixed(report["mean_psnr_denoised_db"].get<double>(), " dB", 2)});
  quality.rows.push_back(
      {"replaced samples", report.value("replaced_samples", nlohmann::json(0)).dump()});
  quality.rows.push_back(
      {"repaired pixels", report.value("repairs", nlohmann::json::object()).dump()});
  quality.rows.push_back(
      {"fallback pixels", report.value("fallback_pixels", nlohmann::json(0)).dump()});
  quality.rows.push_back(
      {"input warnings",
       std::to_string(report.value("input_warnings", nlohmann::json::array()).size()) +
           " (report.json lists them)"});
  page.tables = {run, timing, quality};
  if (report.contains("timing")) {  // the frame loop's summary (app/frame_timing.h)
    const nlohmann::json& t = report["timing"];
    const auto ms = [&](const char* key) { return fixed(t.value(key, 0.0), " ms", 2); };
    HtmlTable wall{"Where a frame's wall time goes (stages overlap: docs/cli.md)", {}};
    wall.rows = {{"read (median)", ms("median_read_ms")},
                 {"denoise (median)", ms("median_denoise_ms")},
                 {"write (median)", ms("median_write_ms")},
                 {"stages' sum (mean)", ms("stage_sum_ms_per_frame")},
                 {"wall time per frame", ms("wall_ms_per_frame")},
                 {"frames in flight (at most)", std::to_string(t.value("frames_in_flight", 0))},
                 {"speed-up over the sum", fixed(t.value("speedup_over_stage_sum", 0.0), "x", 2)}};
    page.tables.push_back(std::move(wall));
  }
  page.wipe_left = "denoised";
  page.wipe_right = "reference";
  return page;
}

HtmlReport compare_page(const nlohmann::json& report, std::vector<std::vector<HtmlImage>> images,
                        const std::string& images_note) {
  const nlohmann::json& frames = report.at("frames");
  const std::string a = report.value("a", std::string()), b = report.value("b", std::string());
  HtmlReport page;
  page.title = "svgf compare: " + a + " against " + b;
  page.subtitle =
      frames_text(frames.size()) + "; PSNR, SSIM, relMSE and FLIP of A against B (docs/metrics.md)";
  for (const auto& f : frames) page.frames.push_back(f.value("file", std::string()));
  page.plots.push_back(
      plot_of(frames, "PSNR (dB, higher is better)", false, {{"A vs B", "psnr_db"}}));
  page.plots.push_back(plot_of(frames, "SSIM (higher is better)", false, {{"A vs B", "ssim"}}));
  page.plots.push_back(plot_of(frames, "relMSE (lower is better)", true, {{"A vs B", "relmse"}}));
  page.plots.push_back(plot_of(frames, "FLIP (lower is better)", false, {{"A vs B", "flip"}}));
  page.images = std::move(images);
  page.images_note = images_note;
  page.colour_bar = error_map_colour_bar();
  page.wipe_left = "A";
  page.wipe_right = "reference";  // B's name when it is a sequence; otherwise the second image
  for (const auto& set : page.images)
    for (const HtmlImage& im : set)
      if (im.name == "B") page.wipe_right = "B";

  int identical = 0;
  for (const auto& f : frames) identical += f.value("identical", false) ? 1 : 0;
  HtmlTable config{"Configuration",
                   {{"A", a},
                    {"B", b},
                    {"frames", std::to_string(frames.size())},
                    {"identical frames", std::to_string(identical) + " (no finite PSNR)"},
                    {"FLIP observer", "67 pixels per degree"}}};
  const nlohmann::json mean = report.value("mean", nlohmann::json::object());
  auto mean_of = [&](const char* key, const char* unit, int digits) {
    return mean.contains(key) && mean[key].is_number()
               ? fixed(mean[key].get<double>(), unit, digits)
               : std::string("none");
  };
  HtmlTable means{"Means over the frames",
                  {{"PSNR (frames that differ)", mean_of("psnr_db", " dB", 3)},
                   {"SSIM", mean_of("ssim", "", 5)},
                   {"relMSE", mean_of("relmse", "", 6)},
                   {"FLIP", mean_of("flip", "", 5)}}};
  page.tables = {config, means};
  return page;
}

}  // namespace svgf::app
