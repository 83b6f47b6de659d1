#pragma once
// report.html of svgf denoise and svgf compare: one self-contained page (docs/report.md). Images
// are embedded as data: URIs, plots are inline SVG written here, and a small inline script picks
// the frame and wipes between two of its images; nothing is fetched (the page's
// Content-Security-Policy allows no network at all).
#include <string>
#include <utility>
#include <vector>

namespace svgf::app {

inline constexpr const char* kReportHtml = "report.html";

// Frames that carry images in a page: all of them up to this many, else this many evenly spaced
// (html_frame_has_images).
inline constexpr int kHtmlMaxImageFrames = 64;
// Embedded images are box-downscaled by the smallest whole factor that leaves at most this many
// pixels (1080p: by 6 to 320 x 180; app/report_images.h). With the frame limit it bounds a page:
// an image set of 1-spp noise takes about 9 bytes a pixel as base64, so 0.6 MB a frame, 40 MB
// for 64 frames.
inline constexpr int kHtmlMaxImagePixels = 256 * 256;

struct HtmlImage {
  std::string name;  // "noisy", "denoised", "reference", "FLIP error"
  std::string png;   // PNG bytes
};

// One line of a plot: a value per frame; NaN or infinity where there is none (left out).
struct HtmlSeries {
  std::string name;
  std::vector<double> values;
};

struct HtmlPlot {
  std::string title;  // with its unit: "PSNR (dB)"
  std::vector<HtmlSeries> series;
  bool log_scale = false;  // for values spanning decades (relMSE); non-positive values left out
};

// A table of name/value rows: the configuration, the timings, the means.
struct HtmlTable {
  std::string title;
  std::vector<std::pair<std::string, std::string>> rows;
};

// The colour scale of an error map shown with the images: colours from 0 to 1, linear between.
struct HtmlColourBar {
  std::string label;                 // "FLIP error"
  std::vector<std::string> colours;  // CSS colours, "#rrggbb"; none: no bar
};

struct HtmlReport {
  std::string title;
  std::string subtitle;             // one line under the title
  std::vector<std::string> frames;  // a label per frame, in order ("frame_0003.exr")
  std::vector<HtmlPlot> plots;      // series have one value per frame
  // Per frame (same length as frames, or empty): its images, empty for frames without. The
  // first image set's names are the ones the wipe offers.
  std::vector<std::vector<HtmlImage>> images;
  std::string wipe_left,
      wipe_right;           // the wipe's images at first, by name (default: the first two)
  std::string images_note;  // says which frames carry images, when not all do
  HtmlColourBar colour_bar;
  std::vector<HtmlTable> tables;
};

// The page. Text is HTML-escaped; a series whose length differs from frames throws
// std::invalid_argument.
std::string html_report(const HtmlReport& report);

// Whether the frame at `position` (0-based, in order) of `frames` carries images: every frame
// when frames <= kHtmlMaxImageFrames, else kHtmlMaxImageFrames frames spread evenly from the
// first (position * kHtmlMaxImageFrames / frames changes there).
bool html_frame_has_images(int position, int frames);
// The page's sentence about it; empty when every frame carries images.
std::string html_images_note(int frames);

// RFC 4648 base64 (for data: URIs).
std::string base64(const std::string& bytes);
// Text escaped for HTML element content and quoted attribute values.
std::string html_escape(const std::string& text);

}  // namespace svgf::app
