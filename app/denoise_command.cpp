// svgf denoise: a sequence folder in, denoised EXR frames, PNG previews and a report out.
#include "app/denoise_command.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "app/frame_order.h"
#include "app/method_options.h"
#include "app/options.h"
#include "app/progress_bar.h"
#include "pipeline/make_denoiser.h"
#include "core/tonemap.h"
#include "io/atomic_file.h"
#include "io/exr_frame.h"
#include "io/png.h"
#include "io/sequence.h"
#include "kernels_cpu/parallel_for.h"
#include "metrics/image_metrics.h"

namespace fs = std::filesystem;

namespace svgf::app {

namespace {

// The options before and after the method parameters (app/method_options.h).
const char* const kUsageHead =
    "usage: svgf denoise IN_DIR OUT_DIR [options]\n"
    "\n"
    "Denoises the sequence in IN_DIR (frame_NNNN.exr + manifest.json) into OUT_DIR:\n"
    "frame_NNNN.exr (linear RGB), preview/ PNGs (noisy | denoised | reference), report.json\n"
    "and report.csv (per-frame time, replaced samples, PSNR and relMSE against the reference).\n"
    "Frames are read in the order of their frame numbers, and each output keeps its input's\n"
    "number; the history restarts at camera cuts and at gaps in the numbering.\n"
    "OUT_DIR may not be IN_DIR, lie inside it or hold it (a usage error, exit 2).\n"
    "\n"
    "options:\n"
    "  --method M                svgf, gaussian, wavelet, jbf, jbf-atrous (default svgf)\n"
    "  --backend cpu|cuda|auto   where to run (default auto: CUDA if a device is present)\n"
    "  --mode exact|fast         exact: bitwise CPU == GPU; fast: GPU only (default exact)\n"
    "  --threads N               CPU threads, 0 = all cores (default 0)\n"
    "  --frames N                denoise only the first N frames (by frame number)\n";
const char* const kUsageTail =
    "  --exposure E              preview exposure (default 1)\n"
    "  --no-verify               skip checking each frame file's SHA-256 against the manifest\n"
    "                            (checked for every frame before any output by default)\n"
    "  --no-preview              skip the PNG previews\n";

}  // namespace

std::string denoise_usage() {
  return std::string(kUsageHead) + kMethodParamUsage + kUsageTail;
}

namespace {

DenoiserConfig config_from(const Options& o) {
  DenoiserConfig c;
  c.method = parse_method(o.get("method", "svgf"));
  c.backend = parse_backend(o.get("backend", "auto"));
  c.mode = parse_mode(o.get("mode", "exact"));
  c.threads = o.get_int("threads", 0, 0, 1024);
  // A flag the chosen method does not read is an error, not silently ignored: the report
  // would otherwise describe a setting that was never used.
  check_params_apply(o, to_string(c.method));
  read_method_params(o, c);
  return c;
}

// Previews side by side: noisy | denoised | reference (when present), one PNG per frame.
void write_preview(const std::string& path, const Frame& in, const Image& out, float exposure) {
  const int w = in.width(), h = in.height();
  const int panels = in.has_reference() ? 3 : 2;
  std::vector<uint8_t> strip(static_cast<size_t>(w) * panels * h * 3);
  std::vector<uint8_t> panel(static_cast<size_t>(w) * h * 3);
  const Image* images[3] = {&in.color, &out, &in.reference};
  for (int p = 0; p < panels; ++p) {
    cpu::for_each_pixel(w, h, TonemapKernel{w, images[p]->rgb(), panel.data(), exposure});
    for (int y = 0; y < h; ++y)
      std::copy_n(&panel[static_cast<size_t>(y) * w * 3], w * 3,
                  &strip[(static_cast<size_t>(y) * w * panels + static_cast<size_t>(p) * w) * 3]);
  }
  io::write_png_rgb8(path, strip.data(), w * panels, h);
}

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

// True when `inner` is `outer` or lies inside it, after resolving ., .. and symbolic links
// (weakly: the output folder need not exist yet).
bool same_or_inside(const fs::path& inner, const fs::path& outer) {
  const fs::path a = fs::weakly_canonical(fs::absolute(inner));
  const fs::path b = fs::weakly_canonical(fs::absolute(outer));
  auto ia = a.begin();
  for (auto ib = b.begin(); ib != b.end(); ++ib, ++ia) {
    if (ib->empty()) continue;  // the trailing "" of a path ending in a separator
    if (ia == a.end() || *ia != *ib) return false;
  }
  return true;
}

// The output is written frame by frame: an output folder that is the input folder or holds it,
// or lies inside it, would overwrite or mix with the input (issue 15: `svgf denoise X X`
// replaced every input frame). Refused before anything is read or written.
void check_folders_apart(const std::string& in_dir, const std::string& out_dir) {
  if (same_or_inside(out_dir, in_dir))
    throw UsageError("OUT_DIR '" + out_dir + "' is IN_DIR '" + in_dir +
                     "' or inside it: the output would overwrite or mix with the input");
  if (same_or_inside(in_dir, out_dir))
    throw UsageError("IN_DIR '" + in_dir + "' is inside OUT_DIR '" + out_dir +
                     "': the output would mix with the input");
}

// Everything that can be checked before the output exists, so that bad input never leaves a
// half-written output: every frame's header (size against the manifest, channels; no pixels
// read), the numbering (all frames: the order needs every number), then the SHA-256 of each
// frame to be read. Returns the first `limit` frames in the order of their numbers.
std::vector<PlannedFrame> validate_sequence(const io::Sequence& sequence, int limit, bool verify) {
  std::vector<FrameInput> inputs;
  for (int k = 0; k < sequence.size(); ++k)
    inputs.push_back({sequence.path(k), sequence.read_header(k).index});
  std::vector<PlannedFrame> plan =
      plan_frames(inputs, sequence.manifest().camera_cuts,
                  (fs::path(sequence.dir()) / "manifest.json").string());
  if (static_cast<int>(plan.size()) > limit) plan.resize(static_cast<size_t>(limit));
  if (verify)
    for (const PlannedFrame& p : plan) sequence.verify_checksum(p.position);
  return plan;
}

}  // namespace

int denoise_command(const std::vector<std::string>& args) {
  std::set<std::string> valued = {"method", "backend", "mode", "threads", "frames", "exposure"};
  valued.insert(method_param_flags().begin(), method_param_flags().end());
  const Options o(args, valued, {"no-preview", "no-verify", "help"});
  if (o.has("help")) {
    std::fputs(denoise_usage().c_str(), stdout);
    return 0;
  }
  if (o.positional().size() != 2) throw UsageError("denoise needs IN_DIR and OUT_DIR");
  const std::string in_dir = o.positional()[0], out_dir = o.positional()[1];
  check_folders_apart(in_dir, out_dir);
  // Every argument is checked before anything is read or written: a bad value or an impossible
  // combination (fast mode on the CPU) is a usage error, exit 2.
  DenoiserConfig config;
  std::unique_ptr<Denoiser> denoiser;
  try {
    config = config_from(o);
    denoiser = make_denoiser(config);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  const float exposure = o.get_float("exposure", 1.f);
  if (!(exposure > 0.f) || !std::isfinite(exposure))
    throw UsageError("--exposure must be a finite number > 0, got '" + o.get("exposure", "") + "'");
  const bool previews = !o.has("no-preview");
  const int frame_limit = o.get_int("frames", 1 << 20, 1, 1 << 20);

  const io::Sequence sequence(in_dir);
  const std::vector<PlannedFrame> plan =
      validate_sequence(sequence, frame_limit, !o.has("no-verify"));
  const int frames = static_cast<int>(plan.size());
  std::error_code ec;
  fs::create_directories(fs::path(out_dir) / (previews ? "preview" : ""), ec);
  if (ec) throw io::IoError(out_dir + ": cannot create the output folder (" + ec.message() + ")");

  std::fprintf(stderr, "svgf: %s: %d frames of %dx%d (%s) with %s\n", in_dir.c_str(), frames,
               sequence.manifest().width, sequence.manifest().height,
               sequence.manifest().scene.c_str(), denoiser->description().c_str());
  std::string why_not_cuda;
  if (config.backend == Backend::Auto && !cuda_available(&why_not_cuda))
    std::fprintf(stderr, "svgf: --backend auto chose the CPU: %s\n", why_not_cuda.c_str());

  nlohmann::json report;
  report["input"] = in_dir;
  report["scene"] = sequence.manifest().scene;
  report["width"] = sequence.manifest().width;
  report["height"] = sequence.manifest().height;
  report["denoiser"] = denoiser->description();
  report["frames"] = nlohmann::json::array();
  std::ostringstream csv;
  csv << "frame,time_ms,filter_ms,replaced_samples,psnr_noisy_db,psnr_denoised_db,relmse_noisy,"
         "relmse_denoised\n";

  ProgressBar bar("denoise", frames);
  double total_ms = 0, psnr_sum = 0, noisy_psnr_sum = 0;
  int64_t replaced_total = 0;
  int with_reference = 0;
  Image out;
  for (int k = 0; k < frames; ++k) {
    const PlannedFrame& planned = plan[static_cast<size_t>(k)];
    const Frame in = sequence.read(planned.position);
    if (!planned.reset.empty()) denoiser->reset();
    const auto t0 = std::chrono::steady_clock::now();
    denoiser->denoise(in, out);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    total_ms += ms;
    const FrameReport& r = denoiser->last_report();
    replaced_total += r.replaced_samples;

    const std::string name = io::frame_file_name(planned.number);  // never renumbered
    io::write_rgb_exr((fs::path(out_dir) / name).string(), out);
    if (previews)
      write_preview((fs::path(out_dir) / "preview" / (name.substr(0, name.size() - 4) + ".png")).string(),
                    in, out, exposure);

    nlohmann::json fr;
    fr["frame"] = planned.number;
    fr["input"] = fs::path(sequence.path(planned.position)).filename().string();
    if (!planned.reset.empty()) fr["history_reset"] = planned.reset;
    fr["time_ms"] = ms;
    fr["filter_ms"] = r.times.filter_ms();
    for (const auto& [stage, stage_ms] : r.times.entries()) fr["stage_ms"][stage] = stage_ms;
    fr["replaced_samples"] = r.replaced_samples;
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
      psnr_sum += p_out;
      noisy_psnr_sum += p_noisy;
      ++with_reference;
      detail += ", PSNR " + fixed(p_out, 2) + " dB";
    } else {
      csv << ",,,,";
    }
    csv << '\n';
    report["frames"].push_back(fr);
    bar.update(k + 1, detail);
  }

  report["mean_time_ms"] = total_ms / frames;
  report["replaced_samples"] = replaced_total;
  if (with_reference) {
    report["mean_psnr_noisy_db"] = noisy_psnr_sum / with_reference;
    report["mean_psnr_denoised_db"] = psnr_sum / with_reference;
  }
  const std::string json_text = report.dump(2) + "\n", csv_text = csv.str();
  io::write_atomically((fs::path(out_dir) / "report.json").string(),
                       [&](const std::string& tmp) { std::ofstream(tmp) << json_text; });
  io::write_atomically((fs::path(out_dir) / "report.csv").string(),
                       [&](const std::string& tmp) { std::ofstream(tmp) << csv_text; });

  std::printf("denoised %d frames of %s into %s\n", frames, in_dir.c_str(), out_dir.c_str());
  std::printf("  denoiser          %s\n", denoiser->description().c_str());
  std::printf("  time per frame    %s ms (mean, I/O excluded)\n", fixed(total_ms / frames, 2).c_str());
  std::printf("  replaced samples  %lld (NaN, Inf or negative color set to 0)\n",
              static_cast<long long>(replaced_total));
  if (with_reference)
    std::printf("  PSNR              %s dB noisy -> %s dB denoised (mean over %d frames)\n",
                fixed(noisy_psnr_sum / with_reference, 2).c_str(),
                fixed(psnr_sum / with_reference, 2).c_str(), with_reference);
  std::printf("  report            %s/report.json, report.csv\n", out_dir.c_str());
  return 0;
}

}  // namespace svgf::app
