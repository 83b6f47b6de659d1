#include "bench/atrous_probe.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "kernels_cpu/cpu_variant.h"
#include "kernels_cpu/svgf_rows.h"
#include "methods/svgf/atrous.h"

namespace svgf::bench {

double resident_atrous_ns_per_tap(int threads) {
  constexpr int kWidth = 1280, kHeight = 64;
  const size_t n = static_cast<size_t>(kWidth) * kHeight;
  // A slanted, gently curved surface with a noisy signal: every weight is an ordinary number
  // (the row loops are branch-free, so the values change no instruction, only the sums).
  std::vector<float> depth(n), dx(n, 0.01f), dy(n, 0.02f), nx(n), ny(n), nz(n);
  std::vector<float> signal[2][4];
  for (auto& buffer : signal)
    for (auto& plane : buffer) plane.assign(n, 0.f);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const size_t i = static_cast<size_t>(y) * kWidth + x;
      depth[i] = 2.f + 0.01f * x + 0.02f * y;
      const float tilt = 0.2f * std::sin(0.05f * static_cast<float>(x + 3 * y));
      nx[i] = tilt;
      ny[i] = 0.f;
      nz[i] = std::sqrt(1.f - tilt * tilt);
      const float noise = static_cast<float>((i * 2654435761u) % 1000u) / 1000.f;
      for (int c = 0; c < 3; ++c) signal[0][c][i] = 0.5f + noise * (0.5f + 0.25f * c);
      signal[0][3][i] = 0.05f + 0.1f * noise;
    }
  GuideView guides;
  guides.width = kWidth;
  guides.height = kHeight;
  guides.depth = depth.data();
  guides.depth_dx = dx.data();
  guides.depth_dy = dy.data();
  guides.normal = {nx.data(), ny.data(), nz.data()};
  const auto view = [&](int b) {
    return IllumVarView({signal[b][0].data(), signal[b][1].data(), signal[b][2].data()},
                        signal[b][3].data());
  };
  const auto atrous_rows = cpu::pick_variant("").atrous_rows;
  tbb::task_arena arena(std::max(threads, 1));
  constexpr int kIterations = 16;
  std::vector<double> seconds;
  for (int rep = 0; rep < 8; ++rep) {  // the first warms the caches and the threads
    const auto t0 = std::chrono::steady_clock::now();
    arena.execute([&] {
      for (int it = 0; it < kIterations; ++it) {
        const int in = it % 2;  // ping-pong, as the frame's iterations
        atrous_rows(AtrousKernel{guides, view(in), view(1 - in), 1 << (it % 2), SvgfParams{}},
                    kWidth, kHeight, cpu::AtrousRowOutputs{});
      }
    });
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (rep > 0) seconds.push_back(s);
  }
  // The taps inside the frame (a tap row or column outside is skipped, as the kernel skips it).
  double taps = 0;
  for (int step = 1; step <= 2; ++step)
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        int inside = 0;
        for (int dy = -2; dy <= 2; ++dy)
          for (int dx = -2; dx <= 2; ++dx)
            inside += (dx != 0 || dy != 0) && guides.inside(x + dx * step, y + dy * step);
        taps += inside * (kIterations / 2.0);
      }
  return *std::min_element(seconds.begin(), seconds.end()) * 1e9 / taps;
}

}  // namespace svgf::bench
