// Main of svgf_gpu_tests: Catch2 with two extra options, exit code 77 (ctest SKIP_RETURN_CODE)
// when there is no CUDA device to test on, and a closing summary of what was compared.
//   svgf_gpu_tests [--reduced] [--max-frames N] [--fixtures DIR] [Catch2 options and tags]
// Environment: SVGF_GPU_TESTS_REDUCED=1 acts as --reduced; SVGF_FIXTURES_DIR as --fixtures.
// Fixtures are looked for in that folder, else SVGF_SOURCE_DIR/fixtures, else ./fixtures.
#define CATCH_CONFIG_RUNNER
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <catch2/catch.hpp>
#include <cuda_runtime_api.h>

#include "gpu_test_options.h"
#include "kernels_cuda/cuda_denoisers.h"

namespace fs = std::filesystem;

namespace svgf::gpu_test {

Options& options() {
  static Options o;
  return o;
}
Tally& tally() {
  static Tally t;
  return t;
}

std::vector<std::string> fixture_dirs() {
  std::vector<std::string> dirs;
  std::error_code ec;
  const fs::path root(options().fixtures_dir);
  if (root.empty() || !fs::is_directory(root, ec)) return dirs;
  for (const auto& entry : fs::directory_iterator(root, ec))
    if (entry.is_directory() && fs::exists(entry.path() / "manifest.json"))
      dirs.push_back(entry.path().string());
  std::sort(dirs.begin(), dirs.end());
  return dirs;
}

}  // namespace svgf::gpu_test

namespace {

std::string default_fixtures_dir() {
  if (const char* env = std::getenv("SVGF_FIXTURES_DIR")) return env;
  std::error_code ec;
#if defined(SVGF_SOURCE_DIR)
  const fs::path built_in = fs::path(SVGF_SOURCE_DIR) / "fixtures";
  if (fs::is_directory(built_in, ec)) return built_in.string();
#endif
  return "fixtures";  // the repository root as working directory (the GPU machine)
}

void print_device() {
  int device = 0, driver = 0, runtime = 0;
  cudaDeviceProp prop{};
  cudaGetDevice(&device);
  cudaGetDeviceProperties(&prop, device);
  cudaDriverGetVersion(&driver);
  cudaRuntimeGetVersion(&runtime);
  std::printf("device %d: %s, sm_%d%d, %d SMs, %.1f GiB; CUDA driver API %d.%d, runtime %d.%d\n",
              device, prop.name, prop.major, prop.minor, prop.multiProcessorCount,
              static_cast<double>(prop.totalGlobalMem) / (1024.0 * 1024.0 * 1024.0),
              driver / 1000, (driver % 1000) / 10, runtime / 1000, (runtime % 1000) / 10);
}

void print_tally() {
  const auto& t = svgf::gpu_test::tally();
  std::printf("\nsummary: %lld single-stage runs compared bitwise (%lld values); %lld pipeline "
              "frames CPU vs CUDA exact bitwise (%lld output and debug values); %lld frames "
              "in determinism checks; %lld fast-mode frames within tolerance; %lld device-path "
              "frames bitwise equal to the host path's\n",
              static_cast<long long>(t.stage_runs), static_cast<long long>(t.stage_values),
              static_cast<long long>(t.frames), static_cast<long long>(t.frame_values),
              static_cast<long long>(t.determinism_frames),
              static_cast<long long>(t.fast_frames), static_cast<long long>(t.device_frames));
  if (t.fast_frames > 0)
    std::printf("fast vs exact, worst frame: relMSE %.3g (%s); |PSNR delta| %.4f dB (%s)\n",
                t.fast_worst_relmse, t.fast_worst_relmse_at.c_str(), t.fast_worst_psnr_delta,
                t.fast_worst_psnr_at.empty() ? "no reference" : t.fast_worst_psnr_at.c_str());
  std::string seqs;
  for (const auto& s : t.sequences) seqs += (seqs.empty() ? "" : ", ") + s;
  std::printf("sequences: %s\n", seqs.empty() ? "(none)" : seqs.c_str());
}

}  // namespace

int main(int argc, char* argv[]) {
  auto& opt = svgf::gpu_test::options();
  opt.fixtures_dir = default_fixtures_dir();
  if (const char* env = std::getenv("SVGF_GPU_TESTS_REDUCED")) opt.reduced = std::string(env) == "1";

  Catch::Session session;
  using namespace Catch::clara;
  auto cli = session.cli() |
             Opt(opt.reduced)["--reduced"]("fewer sizes and frames (for compute-sanitizer)") |
             Opt(opt.max_frames, "n")["--max-frames"]("at most n frames of each sequence") |
             Opt(opt.fixtures_dir, "dir")["--fixtures"]("folder of fixture sequences");
  session.cli(cli);
  if (const int rc = session.applyCommandLine(argc, argv); rc != 0) return rc;
  if (session.configData().showHelp || session.configData().listTests ||
      session.configData().listTags || session.configData().listTestNamesOnly)
    return session.run();

  std::string why;
  if (!svgf::cuda::device_available(&why)) {
    std::printf("skipped: no CUDA device (%s)\n", why.c_str());
    return 77;
  }
  print_device();
  std::printf("fixtures: %s (%zu sequences)%s\n", opt.fixtures_dir.c_str(),
              svgf::gpu_test::fixture_dirs().size(), opt.reduced ? ", reduced mode" : "");
  const int failed = session.run();
  print_tally();
  return failed == 0 ? 0 : 1;
}
