// denoise_sequence IN_DIR OUT_DIR: reads a sequence (frame_NNNN.exr + manifest.json), denoises
// every frame with SVGF's defaults and writes OUT_DIR/frame_NNNN.exr, the same files
// `svgf denoise IN_DIR OUT_DIR` writes for a sequence numbered 0, 1, 2, ... (docs/api.md).
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>

#include "io/exr_frame.h"          // io::write_rgb_exr
#include "io/sequence.h"           // io::Sequence, io::frame_file_name
#include "metrics/image_metrics.h" // metrics::psnr
#include "pipeline/make_denoiser.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: denoise_sequence IN_DIR OUT_DIR\n");
    return 2;
  }
  try {
    // Reads and checks the manifest; frames are read one at a time below.
    const svgf::io::Sequence sequence(argv[1]);
    const std::filesystem::path out_dir = argv[2];
    std::filesystem::create_directories(out_dir);

    // SVGF in exact mode; Auto runs on CUDA when this build has it and a device is present
    // (exact mode gives the same bits on either).
    svgf::DenoiserConfig config;
    config.backend = svgf::Backend::Auto;
    const std::unique_ptr<svgf::Denoiser> denoiser = svgf::make_denoiser(config);
    std::printf("%s: %d frames, %s\n", argv[1], sequence.size(), denoiser->description().c_str());

    svgf::Image denoised;  // RGB, reused from frame to frame
    for (int k = 0; k < sequence.size(); ++k) {
      const svgf::Frame frame = sequence.read(k);  // throws io::IoError naming the file
      // A camera cut (the manifest lists frame numbers) starts the history anew.
      if (sequence.is_camera_cut(frame.index)) denoiser->reset();

      const auto start = std::chrono::steady_clock::now();
      denoiser->denoise(frame, denoised);
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();

      // One RGB EXR per frame, written atomically, named by the input's frame number.
      svgf::io::write_rgb_exr((out_dir / svgf::io::frame_file_name(frame.index)).string(),
                              denoised);
      std::printf("frame %d: %.2f ms", frame.index, ms);
      if (frame.has_reference())
        std::printf(", PSNR %.2f dB", svgf::metrics::psnr(denoised, frame.reference));
      std::printf("\n");
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "denoise_sequence: %s\n", e.what());
    return 1;
  }
}
