#pragma once
// What svgf denoise reports: report.json and report.csv of a finished run, and the failure
// report beside OUT_DIR of a run that stopped (docs/frame-format.md, "Output folder").
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/frame_order.h"
#include "app/frame_timing.h"
#include "app/html_report.h"
#include "app/input_warnings.h"
#include "core/denoiser.h"
#include "core/frame.h"

namespace svgf::app {

inline constexpr const char* kReportJson = "report.json";  // written last: marks a whole output
inline constexpr const char* kReportCsv = "report.csv";

// Per-frame times, input repairs and quality against the reference, with their means.
class RunReport {
 public:
  RunReport(const std::string& in_dir, const std::string& scene, int width, int height,
            const std::string& denoiser);
  // Adds one denoised frame; returns the progress bar's detail ("3.2 ms, PSNR 31.20 dB").
  std::string add(const PlannedFrame& planned, const std::string& input_file, double ms,
                  const FrameReport& r, const Frame& in, const Image& out);
  // The read, denoise and write times of the frame last added (its read_ms and write_ms in
  // report.json), for the timing summary.
  void add_times(const FrameTimes& times);
  // The frame loop's wall time and how many frames it held at most: the summary's "timing".
  void set_loop_time(double ms, int in_flight);
  // Input traps found in frame `frame` (app/input_warnings.h): listed in report.json, counted
  // by kind for the summary.
  void add_warnings(int frame, const std::vector<InputWarning>& warnings);
  // Images of the frame last added, for report.html (app/report_images.h).
  void add_images(std::vector<HtmlImage> images);
  // What report.html says about the frames without images (html_images_note by default).
  void set_images_note(std::string note) { images_note_ = std::move(note); }
  // report.csv, report.html, then report.json, each written atomically and checked (an IoError
  // naming the file on a short write), into `folder`.
  void write(const std::string& folder);
  void print_summary(const std::string& in_dir, const std::string& out_dir,
                     const std::string& denoiser) const;
  int frames() const { return frames_; }

 private:
  nlohmann::json json_;
  std::string csv_;
  int frames_ = 0, with_reference_ = 0;
  double total_ms_ = 0, psnr_sum_ = 0, noisy_psnr_sum_ = 0;
  int64_t replaced_total_ = 0;
  int64_t fallback_total_ = 0;
  InputRepairs repairs_total_;  // the sanitize stage's, per kind (docs/bad-input.md)
  int frames_repaired_ = 0;
  struct WarningCount {
    int frames = 0, first_frame = 0;
    std::string text;
  };
  std::map<std::string, WarningCount> warnings_;  // by kind
  std::vector<std::vector<HtmlImage>> images_;     // per frame, for report.html
  std::vector<FrameTimes> times_;                   // per frame
  double loop_ms_ = 0;
  int in_flight_ = 0;
  std::string images_note_;
};

// Where a run stands, for the failure report.
struct RunProgress {
  std::string stage = "reading the input";
  int frame = -1;          // frame number that failed; -1 outside the frame loop, or a signal
  std::string file;        // its input file
  std::string frame_step;  // what failed on it: "read", "denoise" or "write" (app/frame_pipeline.h)
  int frames_written = 0;  // outputs written into the staging folder (discarded on failure)
};

// OUT_DIR's failure report: OUT_DIR + ".failed-report.json", beside it.
std::string failure_report_path(const std::string& out_dir);

// Writes the failure report: what failed, where, and that OUT_DIR was left as it was. Returns
// false (after printing why on stderr) when even that cannot be written; the run's own error
// is what matters then.
bool write_failure_report(const std::string& in_dir, const std::string& out_dir,
                          const RunProgress& progress, const std::string& error,
                          int exit_status);

}  // namespace svgf::app
