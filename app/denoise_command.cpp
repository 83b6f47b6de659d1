// svgf denoise: a sequence folder in, denoised EXR frames, PNG previews and a report out.
#include "app/denoise_command.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include <nlohmann/json.hpp>

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

const char* const kDenoiseUsage =
    "usage: svgf denoise IN_DIR OUT_DIR [options]\n"
    "\n"
    "Denoises the sequence in IN_DIR (frame_NNNN.exr + manifest.json) into OUT_DIR:\n"
    "frame_NNNN.exr (linear RGB), preview/ PNGs (noisy | denoised | reference), report.json\n"
    "and report.csv (per-frame time, replaced samples, PSNR and relMSE against the reference).\n"
    "\n"
    "options:\n"
    "  --method M                svgf, gaussian, wavelet, jbf, jbf-atrous (default svgf)\n"
    "  --backend cpu|cuda|auto   where to run (default auto: CUDA if a device is present)\n"
    "  --mode exact|fast         exact: bitwise CPU == GPU; fast: GPU only (default exact)\n"
    "  --threads N               CPU threads, 0 = all cores (default 0)\n"
    "  --frames N                denoise only the first N frames\n"
    "  --iterations N            svgf, wavelet: a-trous iterations (default 4)\n"
    "  --feedback-tap N          a-trous iteration fed back as history, -1 none (default 1)\n"
    "  --alpha A                 color temporal blend floor (default 0.05)\n"
    "  --moments-alpha A         moments temporal blend floor (default 0.2)\n"
    "  --phi-color X             luminance edge-stopping (default 10)\n"
    "  --phi-normal X            normal edge-stopping exponent (default 128)\n"
    "  --phi-depth X             depth edge-stopping, 0 = no depth term (default 1)\n"
    "  --sigma S                 gaussian: standard deviation in pixels (default 2)\n"
    "  --radius R                gaussian: taps either side, 0 = ceil(3 sigma) (default 0)\n"
    "  --kernel-size K           wavelet: taps per axis, 3, 5, 7 or 9 (default 5)\n"
    "  --sigma-depth S           wavelet: depth weight scale sigma_Z (default 1)\n"
    "  --sigma-normal S          wavelet: normal weight exponent sigma_N (default 64)\n"
    "  --sigma-luma S            wavelet: luma weight scale sigma_L (default 4)\n"
    "  --jbf-radius R            jbf: window radius in pixels (default 16)\n"
    "  --jbf-levels N            jbf-atrous: levels of 5x5 taps at 1, 2, 4, ... (default 4)\n"
    "  --jbf-sigma-coord S       jbf: pixel distance scale (default 32)\n"
    "  --jbf-sigma-color S       jbf: color distance scale (default 0.6)\n"
    "  --jbf-sigma-normal S      jbf: normal angle scale, radians (default 0.1)\n"
    "  --jbf-sigma-plane S       jbf: tangent-plane distance scale (default 0.1)\n"
    "  --exposure E              preview exposure (default 1)\n"
    "  --no-preview              skip the PNG previews\n";

namespace {

DenoiserConfig config_from(const Options& o) {
  DenoiserConfig c;
  c.method = parse_method(o.get("method", "svgf"));
  c.backend = parse_backend(o.get("backend", "auto"));
  c.mode = parse_mode(o.get("mode", "exact"));
  c.threads = o.get_int("threads", 0, 0, 1024);
  SvgfParams& p = c.svgf;
  p.iterations = o.get_int("iterations", p.iterations, 0, 12);
  p.feedback_tap = o.get_int("feedback-tap", p.feedback_tap, -1, 11);
  p.alpha = o.get_float("alpha", p.alpha);
  p.moments_alpha = o.get_float("moments-alpha", p.moments_alpha);
  p.phi_color = o.get_float("phi-color", p.phi_color);
  p.phi_normal = o.get_float("phi-normal", p.phi_normal);
  p.phi_depth = o.get_float("phi-depth", p.phi_depth);
  if (!(p.alpha > 0.f && p.alpha <= 1.f) || !(p.moments_alpha > 0.f && p.moments_alpha <= 1.f))
    throw UsageError("--alpha and --moments-alpha must lie in (0, 1]");
  const auto finite_at_least = [](float v, float lo) { return std::isfinite(v) && v >= lo; };
  if (!finite_at_least(p.phi_depth, 0.f) || !finite_at_least(p.phi_normal, 0.f) ||
      !(finite_at_least(p.phi_color, 0.f) && p.phi_color > 0.f))
    throw UsageError("--phi-depth and --phi-normal must be finite and >= 0, --phi-color > 0");
  GaussianParams& g = c.gaussian;
  g.sigma = o.get_float("sigma", g.sigma);
  g.radius = o.get_int("radius", g.radius, 0, 1024);
  WaveletParams& v = c.wavelet;
  v.iterations = o.get_int("iterations", v.iterations, 0, 12);
  v.kernel_size = o.get_int("kernel-size", v.kernel_size, 3, 9);
  v.sigma_depth = o.get_float("sigma-depth", v.sigma_depth);
  v.sigma_normal = o.get_float("sigma-normal", v.sigma_normal);
  v.sigma_luma = o.get_float("sigma-luma", v.sigma_luma);
  JbfParams& j = c.jbf;
  j.radius = o.get_int("jbf-radius", j.radius, 1, 64);
  j.levels = o.get_int("jbf-levels", c.method == Method::JbfAtrous ? 4 : 0, 0, 10);
  j.sigma_coord = o.get_float("jbf-sigma-coord", j.sigma_coord);
  j.sigma_color = o.get_float("jbf-sigma-color", j.sigma_color);
  j.sigma_normal = o.get_float("jbf-sigma-normal", j.sigma_normal);
  j.sigma_plane = o.get_float("jbf-sigma-plane", j.sigma_plane);
  try {
    g.validate();
    v.validate();
    j.validate();
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
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

}  // namespace

int denoise_command(const std::vector<std::string>& args) {
  const Options o(args,
                  {"method", "backend", "mode", "threads", "frames", "iterations", "feedback-tap",
                   "alpha", "moments-alpha", "phi-color", "phi-normal", "phi-depth", "sigma",
                   "radius", "kernel-size", "sigma-depth", "sigma-normal", "sigma-luma",
                   "jbf-radius", "jbf-levels", "jbf-sigma-coord", "jbf-sigma-color",
                   "jbf-sigma-normal", "jbf-sigma-plane", "exposure"},
                  {"no-preview", "help"});
  if (o.has("help")) {
    std::fputs(kDenoiseUsage, stdout);
    return 0;
  }
  if (o.positional().size() != 2) throw UsageError("denoise needs IN_DIR and OUT_DIR");
  const std::string in_dir = o.positional()[0], out_dir = o.positional()[1];
  const DenoiserConfig config = config_from(o);
  const float exposure = o.get_float("exposure", 1.f);
  const bool previews = !o.has("no-preview");

  const io::Sequence sequence(in_dir);
  const int frames = std::min(sequence.size(), o.get_int("frames", sequence.size(), 1, 1 << 20));
  std::error_code ec;
  fs::create_directories(fs::path(out_dir) / (previews ? "preview" : ""), ec);
  if (ec) throw io::IoError(out_dir + ": cannot create the output folder (" + ec.message() + ")");

  auto denoiser = make_denoiser(config);
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
    const Frame in = sequence.read(k);
    if (sequence.is_camera_cut(k)) denoiser->reset();
    const auto t0 = std::chrono::steady_clock::now();
    denoiser->denoise(in, out);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    total_ms += ms;
    const FrameReport& r = denoiser->last_report();
    replaced_total += r.replaced_samples;

    const std::string name = io::frame_file_name(k);
    io::write_rgb_exr((fs::path(out_dir) / name).string(), out);
    if (previews)
      write_preview((fs::path(out_dir) / "preview" / (name.substr(0, name.size() - 4) + ".png")).string(),
                    in, out, exposure);

    nlohmann::json fr;
    fr["frame"] = k;
    fr["time_ms"] = ms;
    fr["filter_ms"] = r.times.filter_ms();
    for (const auto& [stage, stage_ms] : r.times.entries()) fr["stage_ms"][stage] = stage_ms;
    fr["replaced_samples"] = r.replaced_samples;
    csv << k << ',' << ms << ',' << r.times.filter_ms() << ',' << r.replaced_samples;
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
