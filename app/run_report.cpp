#include "app/run_report.h"

#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "app/report_pages.h"
#include "io/atomic_file.h"
#include "io/printable.h"
#include "metrics/image_metrics.h"

namespace fs = std::filesystem;

namespace svgf::app {
namespace {

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

// Pixels per kind of repair the sanitize stage made (core/sanitize.h).
nlohmann::json repairs_json(const InputRepairs& r) {
  return {{"color", r.color},   {"albedo", r.albedo},   {"emission", r.emission},
          {"normal", r.normal}, {"surface", r.surface}, {"motion", r.motion}};
}

}  // namespace

RunReport::RunReport(const std::string& in_dir, const std::string& scene, int width, int height,
                     const std::string& denoiser) {
  json_["input"] = in_dir;
  json_["scene"] = scene;
  json_["width"] = width;
  json_["height"] = height;
  json_["denoiser"] = denoiser;
  json_["frames"] = nlohmann::json::array();
  json_["input_warnings"] = nlohmann::json::array();
  csv_ = "frame,time_ms,filter_ms,replaced_samples,psnr_noisy_db,psnr_denoised_db,relmse_noisy,"
         "relmse_denoised\n";
}

std::string RunReport::add(const PlannedFrame& planned, const std::string& input_file, double ms,
                           const FrameReport& r, const Frame& in, const Image& out) {
  ++frames_;
  total_ms_ += ms;
  replaced_total_ += r.replaced_samples;
  fallback_total_ += r.fallback_pixels;
  repairs_total_ += r.repairs;
  frames_repaired_ += r.repairs.total() > 0 ? 1 : 0;
  nlohmann::json fr;
  fr["frame"] = planned.number;
  fr["input"] = input_file;
  if (!planned.reset.empty()) fr["history_reset"] = planned.reset;
  fr["time_ms"] = ms;
  fr["filter_ms"] = r.times.filter_ms();
  for (const auto& [stage, stage_ms] : r.times.entries()) fr["stage_ms"][stage] = stage_ms;
  fr["replaced_samples"] = r.replaced_samples;
  fr["repairs"] = repairs_json(r.repairs);
  fr["fallback_pixels"] = r.fallback_pixels;
  std::ostringstream csv;
  csv << planned.number << ',' << ms << ',' << r.times.filter_ms() << ',' << r.replaced_samples;
  std::string detail = fixed(ms, 1) + " ms";
  if (in.has_reference()) {
    const double p_noisy = metrics::psnr(in.color, in.reference);
    const double p_out = metrics::psnr(out, in.reference);
    const double rel_noisy = metrics::relmse(in.color, in.reference);
    const double rel_out = metrics::relmse(out, in.reference);
    fr["psnr_noisy_db"] = p_noisy;
    fr["psnr_denoised_db"] = p_out;
    fr["relmse_noisy"] = rel_noisy;
    fr["relmse_denoised"] = rel_out;
    csv << ',' << p_noisy << ',' << p_out << ',' << rel_noisy << ',' << rel_out;
    psnr_sum_ += p_out;
    noisy_psnr_sum_ += p_noisy;
    ++with_reference_;
    detail += ", PSNR " + fixed(p_out, 2) + " dB";
  } else {
    csv << ",,,,";
  }
  csv << '\n';
  csv_ += csv.str();
  json_["frames"].push_back(fr);
  images_.emplace_back();
  return detail;
}

void RunReport::add_times(const FrameTimes& times) {
  times_.push_back(times);
  nlohmann::json& fr = json_["frames"].back();
  fr["read_ms"] = times.read_ms;
  fr["write_ms"] = times.write_ms;
}

void RunReport::set_loop_time(double ms, int in_flight) {
  loop_ms_ = ms;
  in_flight_ = in_flight;
}

void RunReport::add_warnings(int frame, const std::vector<InputWarning>& warnings) {
  for (const InputWarning& w : warnings) {
    json_["input_warnings"].push_back({{"frame", frame}, {"kind", w.kind}, {"text", w.text}});
    WarningCount& c = warnings_[w.kind];
    if (c.frames++ == 0) {
      c.first_frame = frame;
      c.text = w.text;
    }
  }
}

void RunReport::add_images(std::vector<HtmlImage> images) {
  if (!images_.empty()) images_.back() = std::move(images);
}

void RunReport::write(const std::string& folder) {
  json_["mean_time_ms"] = total_ms_ / frames_;
  json_["replaced_samples"] = replaced_total_;
  json_["repairs"] = repairs_json(repairs_total_);
  json_["fallback_pixels"] = fallback_total_;
  if (with_reference_) {
    json_["mean_psnr_noisy_db"] = noisy_psnr_sum_ / with_reference_;
    json_["mean_psnr_denoised_db"] = psnr_sum_ / with_reference_;
  }
  if (!times_.empty()) json_["timing"] = to_json(summarize_timing(times_, loop_ms_, in_flight_));
  io::write_file_atomically((fs::path(folder) / kReportCsv).string(), csv_);
  const std::string note = images_note_.empty() ? html_images_note(frames_) : images_note_;
  io::write_file_atomically((fs::path(folder) / kReportHtml).string(),
                            html_report(denoise_page(json_, images_, note)));
  io::write_file_atomically((fs::path(folder) / kReportJson).string(), json_.dump(2) + "\n");
}

void RunReport::print_summary(const std::string& in_dir, const std::string& out_dir,
                              const std::string& denoiser) const {
  std::printf("denoised %d frames of %s into %s\n", frames_, in_dir.c_str(), out_dir.c_str());
  std::printf("  denoiser          %s\n", denoiser.c_str());
  std::printf("  time per frame    %s ms (mean, I/O excluded)\n", fixed(total_ms_ / frames_, 2).c_str());
  if (!times_.empty()) {
    const TimingSummary t = summarize_timing(times_, loop_ms_, in_flight_);
    std::printf("  stages per frame  read %s + denoise %s + write %s ms (medians)\n",
                fixed(t.median_read_ms, 2).c_str(), fixed(t.median_denoise_ms, 2).c_str(),
                fixed(t.median_write_ms, 2).c_str());
    std::printf("  wall per frame    %s ms with %d frame%s in flight; the stages' sum %s ms "
                "(mean): %sx\n",
                fixed(t.wall_ms_per_frame, 2).c_str(), t.in_flight, t.in_flight == 1 ? "" : "s",
                fixed(t.stage_sum_ms_per_frame, 2).c_str(), fixed(t.speedup, 2).c_str());
  }
  std::printf("  replaced samples  %lld (color NaN, Inf, negative or > 1e8, set to 0)\n",
              static_cast<long long>(replaced_total_));
  for (const auto& [kind, c] : warnings_)
    std::fprintf(stderr, "svgf: warning: %s (%d frames, the first %d)\n", c.text.c_str(), c.frames,
                 c.first_frame);
  if (fallback_total_ > 0)
    std::printf("  fallback pixels   %lld (the filter had no result; the method's fallback: "
                "docs/bad-input.md)\n",
                static_cast<long long>(fallback_total_));
  if (frames_repaired_ > 0)
    std::fprintf(stderr,
                 "svgf: warning: bad input repaired in %d of %d frames (pixels: %s; "
                 "docs/bad-input.md has the rule)\n",
                 frames_repaired_, frames_, repairs_json(repairs_total_).dump().c_str());
  if (with_reference_)
    std::printf("  PSNR              %s dB noisy -> %s dB denoised (mean over %d frames)\n",
                fixed(noisy_psnr_sum_ / with_reference_, 2).c_str(),
                fixed(psnr_sum_ / with_reference_, 2).c_str(), with_reference_);
  std::printf("  report            %s/%s, %s, %s\n", out_dir.c_str(), kReportJson, kReportCsv,
              kReportHtml);
}

std::string failure_report_path(const std::string& out_dir) {
  return out_dir + ".failed-report.json";
}

bool write_failure_report(const std::string& in_dir, const std::string& out_dir,
                          const RunProgress& progress, const std::string& error,
                          int exit_status) {
  nlohmann::json j;
  j["status"] = "failed";
  j["exit_status"] = exit_status;
  // Paths and messages may hold bytes that are not UTF-8, which JSON cannot carry: escaped as
  // on stderr (io/printable.h).
  j["input"] = io::printable(in_dir);
  j["output"] = io::printable(out_dir);
  j["stage"] = progress.stage;
  if (progress.frame >= 0) {
    j["frame"] = progress.frame;
    j["file"] = io::printable(progress.file);
    if (!progress.frame_step.empty()) j["frame_step"] = progress.frame_step;
  }
  j["frames_written"] = progress.frames_written;
  j["error"] = io::printable(error);
  const std::string path = failure_report_path(out_dir);
  try {
    std::error_code ignored;
    fs::create_directories(fs::path(path).parent_path(), ignored);
    io::write_file_atomically(path, j.dump(2) + "\n");
    return true;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "svgf: cannot write the failure report: %s\n",
                 io::printable(e.what()).c_str());
    return false;
  }
}

}  // namespace svgf::app
