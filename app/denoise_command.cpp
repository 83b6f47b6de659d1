// svgf denoise: a sequence folder in, denoised EXR frames, PNG previews and a report out.
#include "app/denoise_command.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/command_line.h"
#include "app/folder_checks.h"
#include "app/frame_order.h"
#include "app/frame_pipeline.h"
#include "app/frame_timing.h"
#include "app/input_warnings.h"
#include "app/interrupt.h"
#include "app/method_options.h"
#include "app/report_images.h"
#include "app/run_report.h"
#include "cli/progress_bar.h"
#include "pipeline/make_denoiser.h"
#include "core/tonemap.h"
#include "io/exr_frame.h"
#include "io/png.h"
#include "io/printable.h"
#include "io/sequence.h"
#include "io/staged_folder.h"
#include "kernels_cpu/parallel_for.h"

namespace fs = std::filesystem;

namespace svgf::app {

namespace {

const char* const kDescription =
    "Denoises the sequence in IN_DIR (frame_NNNN.exr + manifest.json) into OUT_DIR:\n"
    "frame_NNNN.exr (linear RGB), preview/ PNGs (noisy | denoised | reference), report.json\n"
    "and report.csv (per-frame time, replaced samples, PSNR and relMSE against the reference),\n"
    "report.html (a self-contained page of plots and images; docs/report.md).\n"
    "Frames are read in the order of their frame numbers, and each output keeps its input's\n"
    "number; the history restarts at camera cuts and at gaps in the numbering.\n"
    "Reading frame N+1, denoising N and writing N-1 overlap (--frames-in-flight); the\n"
    "summary and report.json's \"timing\" say where a frame's wall time goes (docs/cli.md).\n"
    "OUT_DIR may not be IN_DIR, lie inside it or hold it (a usage error, exit 2).\n"
    "The run is written beside OUT_DIR and replaces it as a whole only when it succeeds\n"
    "(OUT_DIR must be absent, empty or an earlier output); a failed run leaves OUT_DIR as\n"
    "it was and says what failed in OUT_DIR.failed-report.json (exit 1; 130 or 143 when\n"
    "SIGINT or SIGTERM stopped it).";

struct DenoiseArgs {
  std::string in_dir, out_dir, method = "svgf", backend = "auto", mode = "exact";
  int threads = 0, frames = 1 << 20, in_flight = 3;
  float exposure = 1.f;
  bool no_preview = false, no_verify = false;
  MethodParamFlags params;
};

DenoiserConfig config_from(const DenoiseArgs& a) {
  DenoiserConfig c;
  c.method = parse_method(a.method);
  c.backend = parse_backend(a.backend);
  c.mode = parse_mode(a.mode);
  c.threads = a.threads;
  // A flag the chosen method does not read is an error, not silently ignored: the report
  // would otherwise describe a setting that was never used.
  a.params.check_apply(to_string(c.method));
  a.params.read(c);
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

// SVGF filtering direct and indirect apart reads both in a frame that has either, and needs
// them in every frame with --svgf-split on: an IoError naming the file otherwise (the denoiser
// refuses the same frames, methods/svgf/denoiser.h).
void check_split_channels(const io::FrameHeader& h, const std::string& path, SplitMode split) {
  if (split == SplitMode::Off) return;
  if (h.has_direct != h.has_indirect)
    throw io::IoError(path + ": channel '" + (h.has_direct ? "direct" : "indirect") +
                      "' without '" + (h.has_direct ? "indirect" : "direct") +
                      "': filtering them apart (--svgf-split) needs both");
  if (split == SplitMode::On && !h.has_direct)
    throw io::IoError(path + ": --svgf-split on needs the channels 'direct' and 'indirect', "
                      "and the frame has neither");
}

// Everything that can be checked before the output exists, so that bad input never leaves a
// half-written output: every frame's header (size against the manifest, channels; no pixels
// read), the numbering (all frames: the order needs every number), then the SHA-256 of each
// frame to be read. Returns the first `limit` frames in the order of their numbers.
// `split`: SVGF's --svgf-split, whose needs each header must meet (docs/svgf.md: Direct and
// indirect).
std::vector<PlannedFrame> validate_sequence(const io::Sequence& sequence, int limit, bool verify,
                                            SplitMode split) {
  std::vector<FrameInput> inputs;
  for (int k = 0; k < sequence.size(); ++k) {
    throw_if_interrupted();
    const io::FrameHeader header = sequence.read_header(k);
    check_split_channels(header, sequence.path(k), split);
    inputs.push_back({sequence.path(k), header.index});
  }
  std::vector<PlannedFrame> plan =
      plan_frames(inputs, sequence.manifest().camera_cuts,
                  (fs::path(sequence.dir()) / "manifest.json").string());
  if (static_cast<int>(plan.size()) > limit) plan.resize(static_cast<size_t>(limit));
  if (verify)
    for (const PlannedFrame& p : plan) {
      throw_if_interrupted();
      sequence.verify_checksum(p.position);
    }
  return plan;
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// One frame on its way through the frame pipeline.
struct FrameWork {
  const PlannedFrame* planned = nullptr;
  Frame in;
  Image out;
  FrameReport denoised;                // the denoiser's report of this frame
  std::vector<InputWarning> warnings;  // found by the denoise stage, reported by the last
  FrameTimes times;
};

// What a run needs once its arguments are accepted.
struct RunSettings {
  std::string in_dir, out_dir;
  SplitMode split = SplitMode::Off;  // SVGF's, Off for the other methods
  int frame_limit = 0;
  int in_flight = 3;  // frames in the pipeline at most; 1: one after another
  bool verify = true, previews = true;
  float exposure = 1.f;
  Backend requested_backend = Backend::Auto;
};

// Validates the input, denoises into a staging folder beside OUT_DIR and swaps it in at the end
// (docs/frame-format.md, "Output folder"): until then OUT_DIR keeps whatever it held.
void run(const RunSettings& s, Denoiser& denoiser, RunProgress& progress) {
  progress.stage = "reading the manifest";
  const io::Sequence sequence(s.in_dir);
  progress.stage = "validating the input";
  const std::vector<PlannedFrame> plan =
      validate_sequence(sequence, s.frame_limit, s.verify, s.split);

  progress.stage = "making the staging folder";
  io::StagedFolder staged(s.out_dir, kReportJson);
  const fs::path folder = staged.path();
  if (s.previews) {
    std::error_code ec;
    fs::create_directories(folder / "preview", ec);
    if (ec) throw io::IoError((folder / "preview").string() + ": cannot create folder (" +
                              ec.message() + ")");
  }

  const int frames = static_cast<int>(plan.size());
  std::fprintf(stderr, "svgf: %s: %d frames of %dx%d (%s) with %s\n", s.in_dir.c_str(), frames,
               sequence.manifest().width, sequence.manifest().height,
               sequence.manifest().scene.c_str(), denoiser.description().c_str());
  std::string why_not_cuda;
  if (s.requested_backend == Backend::Auto && !cuda_available(&why_not_cuda))
    std::fprintf(stderr, "svgf: --backend auto chose the CPU: %s\n", why_not_cuda.c_str());

  RunReport report(s.in_dir, sequence.manifest().scene, sequence.manifest().width,
                   sequence.manifest().height, denoiser.description());
  if (!s.previews) report.set_images_note("No images: the run had --no-preview.");
  cli::ProgressBar bar("denoise", frames);
  bar.show_rate("fps");
  progress.stage = "denoising";
  Camera previous_camera;  // the denoise stage's alone
  bool has_previous = false;
  const auto loop_start = std::chrono::steady_clock::now();
  // Reading frame N+1, denoising N and writing N-1 overlap, each stage serial and in frame order
  // (app/frame_pipeline.h). At most s.in_flight frames (3 by default: one per stage) are held,
  // inputs with all their channels and outputs: the pipeline's memory bound.
  run_frame_pipeline<FrameWork>(
      frames, s.in_flight,
      [&](int k, FrameWork& w) {  // read and decode the input
        w.planned = &plan[static_cast<size_t>(k)];
        throw_if_interrupted();  // a stop reads no more frames
        const auto t0 = std::chrono::steady_clock::now();
        w.in = sequence.read(w.planned->position);
        w.times.read_ms = ms_since(t0);
      },
      [&](FrameWork& w) {  // denoise: the denoiser keeps history, so one frame at a time, in order
        throw_if_interrupted();
        const PlannedFrame& planned = *w.planned;
        if (!planned.reset.empty()) denoiser.reset();
        w.warnings = input_warnings(
            w.in, has_previous && planned.reset.empty() ? &previous_camera : nullptr);
        previous_camera = w.in.camera;
        has_previous = true;
        const auto t0 = std::chrono::steady_clock::now();
        denoiser.denoise(w.in, w.out);
        w.times.denoise_ms = ms_since(t0);
        w.denoised = denoiser.last_report();  // the next frame's denoise replaces it
      },
      [&](FrameWork& w, const StageFailure& failure) {  // write the outputs, report, progress
        // Between frames: a frame is written whole or not at all, and none after a stop.
        throw_if_interrupted();
        const PlannedFrame& planned = *w.planned;
        progress.frame = planned.number;
        progress.file = sequence.path(planned.position);
        progress.frame_step = to_string(failure.error ? failure.step : FrameStep::Write);
        if (failure.error) return;  // rethrown by the pipeline, naming this frame
        const auto t0 = std::chrono::steady_clock::now();
        report.add_warnings(planned.number, w.warnings);
        const std::string name = io::frame_file_name(planned.number);  // never renumbered
        io::write_rgb_exr((folder / name).string(), w.out);
        if (s.previews)
          write_preview((folder / "preview" / (name.substr(0, name.size() - 4) + ".png")).string(),
                        w.in, w.out, s.exposure);
        ++progress.frames_written;
        const std::string detail =
            report.add(planned, fs::path(progress.file).filename().string(), w.times.denoise_ms,
                       w.denoised, w.in, w.out);
        if (s.previews && html_frame_has_images(progress.frames_written - 1, frames))
          report.add_images(denoise_images(w.in, w.out, s.exposure));
        w.times.write_ms = ms_since(t0);
        report.add_times(w.times);
        bar.update(progress.frames_written, detail);
        progress.frame = -1;  // done: a stop before the next frame names none
        progress.file.clear();
        progress.frame_step.clear();
      });
  report.set_loop_time(ms_since(loop_start), s.in_flight);
  progress.stage = "writing the report";
  throw_if_interrupted();
  report.write(staged.path());
  progress.stage = "moving the output into place";
  throw_if_interrupted();  // the last check: a signal during the swap lets it finish
  staged.commit();
  // The run succeeded: a failure report of an earlier run would now describe the wrong output.
  std::error_code ignored;
  fs::remove(failure_report_path(s.out_dir), ignored);
  report.print_summary(s.in_dir, s.out_dir, denoiser.description());
}

int run_denoise(const DenoiseArgs& a) {
  RunSettings settings;
  settings.in_dir = a.in_dir;
  check_folders_apart(settings.in_dir, a.out_dir);
  settings.out_dir = output_folder(a.out_dir, kReportJson);
  // Every argument is checked before anything is read or written: a bad value or an impossible
  // combination (fast mode on the CPU) is a usage error, exit 2.
  DenoiserConfig config;
  std::unique_ptr<Denoiser> denoiser;
  try {
    config = config_from(a);
    denoiser = make_denoiser(config);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  settings.requested_backend = config.backend;
  if (config.method == Method::Svgf) settings.split = config.svgf.split;
  settings.exposure = a.exposure;
  settings.previews = !a.no_preview;
  settings.verify = !a.no_verify;
  settings.frame_limit = a.frames;
  settings.in_flight = a.in_flight;

  // From here on a failure leaves OUT_DIR as it was and says what failed beside it.
  RunProgress progress;
  const InterruptGuard interrupts;
  try {
    run(settings, *denoiser, progress);
    return 0;
  } catch (const Interrupted& e) {
    const int status = 128 + e.signal_number();  // the shell's convention: 130 for SIGINT
    write_failure_report(settings.in_dir, settings.out_dir, progress, e.what(), status);
    std::fprintf(stderr, "svgf: %s; %s left as it was\n", e.what(),
                 io::printable(settings.out_dir).c_str());
    return status;
  } catch (const std::exception& e) {
    if (write_failure_report(settings.in_dir, settings.out_dir, progress, e.what(), 1))
      std::fprintf(stderr, "svgf: %s left as it was; the failure is described in %s\n",
                   io::printable(settings.out_dir).c_str(),
                   io::printable(failure_report_path(settings.out_dir)).c_str());
    throw;
  }
}

}  // namespace

CLI::App* add_denoise_command(CLI::App& svgf, int& status) {
  auto a = std::make_shared<DenoiseArgs>();
  CLI::App* sub = svgf.add_subcommand("denoise", "denoise a frame sequence");
  sub->footer(kDescription);
  sub->add_option("IN_DIR", a->in_dir, "the sequence: frame_NNNN.exr + manifest.json")->required();
  sub->add_option("OUT_DIR", a->out_dir, "the output folder, replaced as a whole")->required();
  sub->add_option("--method", a->method,
                  "svgf, gaussian, wavelet, jbf, jbf-atrous, bmfr (default svgf)")
      ->type_name("M")
      ->check(cli::accepted_by(parse_method));
  sub->add_option("--backend", a->backend,
                  "where to run (default auto: CUDA if a device is present)")
      ->type_name("cpu|cuda|auto")
      ->check(cli::accepted_by(parse_backend));
  sub->add_option("--mode", a->mode, "exact: bitwise CPU == GPU; fast: GPU only (default exact)")
      ->type_name("exact|fast")
      ->check(cli::accepted_by(parse_mode));
  sub->add_option("--threads", a->threads, "CPU threads, 0 = all cores (default 0)")
      ->type_name("N")->check(CLI::Range(0, 1024));
  sub->add_option("--frames", a->frames, "denoise only the first N frames (by frame number)")
      ->type_name("N")->check(CLI::Range(1, 1 << 20));
  sub->add_option("--frames-in-flight", a->in_flight,
                  "frames read, denoised and written at once, each stage in frame order "
                  "(default 3; 1: one frame after another, to time the stages alone)")
      ->type_name("N")->check(CLI::Range(1, 3));
  sub->add_option("--exposure", a->exposure, "preview exposure, finite and > 0 (default 1)")
      ->type_name("E")->check(cli::PositiveFinite);
  sub->add_flag("--no-verify", a->no_verify,
                "skip checking each frame file's SHA-256 against the manifest (checked for "
                "every frame before any output by default)");
  sub->add_flag("--no-preview", a->no_preview,
                "skip the PNG previews (in preview/ and in report.html)");
  a->params.add_to(*sub);
  sub->callback([a, &status] { status = run_denoise(*a); });
  return sub;
}

int denoise_command(const std::vector<std::string>& args) {
  return cli::run_subcommand("svgf", add_denoise_command, args);
}

}  // namespace svgf::app
