#include "app/compare_command.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/command_line.h"
#include "app/report_images.h"
#include "app/report_pages.h"
#include "io/atomic_file.h"
#include "io/exr_frame.h"
#include "io/io_error.h"
#include "io/png.h"
#include "io/printable.h"
#include "metrics/flip.h"
#include "metrics/image_metrics.h"
#include "metrics/ssim.h"

namespace fs = std::filesystem;

namespace svgf::app {
namespace {

using json = nlohmann::json;

bool is_frame_name(const std::string& name) {
  return name.size() > 4 && name.rfind("frame_", 0) == 0 &&
         name.compare(name.size() - 4, 4, ".exr") == 0;
}

// The frame files of a folder (frame_*.exr, by name), or the one file given.
std::vector<std::string> images_of(const std::string& path) {
  if (!fs::is_directory(path)) {
    if (!fs::is_regular_file(path)) throw UsageError("'" + path + "' is neither a file nor a folder");
    return {fs::path(path).filename().string()};
  }
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(path))
    if (e.is_regular_file() && is_frame_name(e.path().filename().string()))
      names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  if (names.empty()) throw UsageError("no frame_*.exr files in '" + path + "'");
  return names;
}

std::string file_in(const std::string& path, const std::string& name) {
  return fs::is_directory(path) ? (fs::path(path) / name).string() : path;
}

// An image to compare against: a sequence frame (a folder with manifest.json) gives its
// reference channel (and its noisy color into `noisy`, when given); any other EXR its R, G, B.
Image reference_image(const std::string& b, const std::string& name, Image* noisy = nullptr) {
  const std::string file = file_in(b, name);
  if (fs::is_directory(b) && fs::exists(fs::path(b) / "manifest.json")) {
    Frame f = io::read_frame(file);
    if (!f.has_reference())
      throw io::IoError(file + ": a sequence frame without a 'reference' channel");
    if (noisy) *noisy = std::move(f.color);
    return std::move(f.reference);
  }
  return io::read_rgb_exr(file);
}

json finite_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// The FLIP error map as a gray PNG (0: no visible difference, white: the largest).
void write_flip_png(const std::string& path, const Image& map) {
  std::vector<uint8_t> rgb(map.pixel_count() * 3);
  for (size_t i = 0; i < map.pixel_count(); ++i) {
    const float v = std::min(1.f, std::max(0.f, map.plane(0)[i]));
    rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = static_cast<uint8_t>(std::lround(v * 255.f));
  }
  io::write_png_rgb8(path, rgb.data(), map.width(), map.height());
}

// Where the page goes: --html FILE, else beside --json FILE (with .html for its extension, or
// FILE.html when that is FILE); none without either.
struct CompareArgs {
  std::string a, b, json, html, diff;
};

std::string page_path(const CompareArgs& o) {
  const std::string& json_path = o.json;
  if (!o.html.empty()) {
    if (o.html == json_path)
      throw UsageError("--html and --json name the same file '" + json_path + "'");
    return o.html;
  }
  if (json_path.empty()) return "";
  const std::string beside = fs::path(json_path).replace_extension(".html").string();
  return beside == json_path ? json_path + ".html" : beside;
}

int run_compare(const CompareArgs& o) {
  const std::string& a = o.a;
  const std::string& b = o.b;
  const std::vector<std::string> names = images_of(a);
  const std::string& diff_dir = o.diff;
  const std::string html_path = page_path(o);
  std::vector<std::vector<HtmlImage>> images;
  if (!diff_dir.empty()) fs::create_directories(diff_dir);

  json frames = json::array();
  double sum[4] = {0, 0, 0, 0};
  int finite_psnr = 0;
  std::printf("%-24s %10s %8s %10s %8s\n", "frame", "PSNR dB", "SSIM", "relMSE", "FLIP");
  for (const std::string& name : names) {
    const std::string fa = file_in(a, name);
    const Image ia = io::read_rgb_exr(fa);
    Image noisy;
    const Image ib =
        reference_image(b, fs::is_directory(b) ? name : fs::path(b).filename().string(), &noisy);
    if (ia.width() != ib.width() || ia.height() != ib.height())
      throw io::IoError(fa + " is " + std::to_string(ia.width()) + "x" + std::to_string(ia.height()) +
                        ", its counterpart in " + b + " " + std::to_string(ib.width()) + "x" +
                        std::to_string(ib.height()));
    const double psnr = metrics::psnr(ia, ib), ssim = metrics::ssim(ia, ib),
                 rel = metrics::relmse(ia, ib);
    const Image flip_map = metrics::flip_map(ia, ib);
    const double flip = metrics::flip_mean(flip_map);  // the map is kept for --diff
    frames.push_back({{"file", name}, {"psnr_db", finite_or_null(psnr)}, {"identical", !std::isfinite(psnr)},
                      {"ssim", ssim}, {"relmse", rel}, {"flip", flip}});
    if (std::isfinite(psnr)) {
      sum[0] += psnr;
      ++finite_psnr;
    }
    sum[1] += ssim;
    sum[2] += rel;
    sum[3] += flip;
    std::printf("%-24s %10.3f %8.5f %10.6f %8.5f\n", name.c_str(), psnr, ssim, rel, flip);
    images.emplace_back();
    if (!html_path.empty() && html_frame_has_images(static_cast<int>(images.size()) - 1,
                                                    static_cast<int>(names.size())))
      images.back() = compare_images(ia, ib, noisy.empty() ? nullptr : &noisy, flip_map);
    if (!diff_dir.empty())
      write_flip_png((fs::path(diff_dir) / (name.substr(0, name.size() - 4) + "_flip.png")).string(),
                     flip_map);
  }
  const double n = static_cast<double>(names.size());
  const json mean = {{"psnr_db", finite_psnr ? json(sum[0] / finite_psnr) : json(nullptr)},
                     {"ssim", sum[1] / n},
                     {"relmse", sum[2] / n},
                     {"flip", sum[3] / n}};
  std::printf("%-24s %10.3f %8.5f %10.6f %8.5f   (PSNR over the %d frames that differ)\n", "mean",
              finite_psnr ? sum[0] / finite_psnr : INFINITY, sum[1] / n, sum[2] / n, sum[3] / n,
              finite_psnr);
  const json report{{"a", a}, {"b", b}, {"frames", frames}, {"mean", mean}};
  if (!o.json.empty()) io::write_file_atomically(o.json, report.dump(2) + "\n");
  if (!html_path.empty())
    io::write_file_atomically(
        html_path, html_report(compare_page(report, std::move(images),
                                            html_images_note(static_cast<int>(names.size())))));
  return 0;
}

}  // namespace

CLI::App* add_compare_command(CLI::App& svgf, int& status) {
  auto o = std::make_shared<CompareArgs>();
  CLI::App* sub = svgf.add_subcommand(
      "compare", "PSNR, SSIM, relMSE and FLIP of A's frames against B's");
  sub->footer(
      "PSNR, SSIM, relMSE and FLIP (docs/metrics.md) of A's images against B's, per frame and\n"
      "mean. A and B are EXR files or folders of frame_NNNN.exr (matched by name); a sequence\n"
      "folder (with manifest.json) as B gives each frame's reference channel.");
  sub->add_option("A", o->a, "an EXR file or a folder of frame_NNNN.exr")->required();
  sub->add_option("B", o->b, "the same, or a sequence folder (its reference channel)")->required();
  sub->add_option("--json", o->json,
                  "also write the numbers as JSON, and a page of plots and images beside it "
                  "(FILE with .html; docs/report.md)")
      ->type_name("FILE");
  sub->add_option("--html", o->html, "write that page as FILE")->type_name("FILE");
  sub->add_option("--diff", o->diff, "write each frame's FLIP error map as DIR/<name>_flip.png")
      ->type_name("DIR");
  sub->callback([o, &status] { status = run_compare(*o); });
  return sub;
}

int compare_command(const std::vector<std::string>& args) {
  return cli::run_subcommand("svgf", add_compare_command, args);
}

}  // namespace svgf::app
