#include "bench/host_probe.h"

#include <sys/resource.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <fstream>
#include <thread>
#include <utility>
#include <vector>

#include "kernels_cpu/cpu_variant.h"

namespace svgf::bench {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A ceiling is the best the machine does: other processes and a VM's steal only slow a run
// down, so the fastest of several is the estimate that moves least from run to run (a median
// of three moved the 2-core VMs' floor by a fifth between runs; docs/benchmarks.md, "Floor").
double fastest_of(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

// A body's run() compiled like each CPU kernel variant (kernels_cpu/CMakeLists.txt), and with
// this file's own flags (SVGF_CPU_ARCH_FLAGS in a build of one custom variant). Noinline
// functions with the body inlined: nothing of one is shared with another.
template <class Body, class... Args>
__attribute__((noinline)) auto on_default(Args... a) {
  return Body::run(a...);
}
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
template <class Body, class... Args>
__attribute__((noinline, target("arch=x86-64-v2"))) auto on_v2(Args... a) {
  return Body::run(a...);
}
template <class Body, class... Args>
__attribute__((noinline, target("arch=x86-64-v3"))) auto on_v3(Args... a) {
  return Body::run(a...);
}
template <class Body, class... Args>
__attribute__((noinline, target("arch=x86-64-v4,prefer-vector-width=512"))) auto on_v4(
    Args... a) {
  return Body::run(a...);
}
#endif

// The body as the variant the kernels run (cpu::pick_variant) is compiled.
template <class Body, class... Args>
auto as_kernel_variant() -> decltype(&on_default<Body, Args...>) {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  const std::string id = cpu::pick_variant("").id;
  if (id == "v2") return on_v2<Body, Args...>;
  if (id == "v3") return on_v3<Body, Args...>;
  if (id == "v4") return on_v4<Body, Args...>;
#endif
  return on_default<Body, Args...>;
}

// Seconds of the fastest of `reps` runs of work(t) on n workers at once.
template <class Work>
double fastest_parallel_run(tbb::task_arena& arena, int n, int reps, const Work& work) {
  std::vector<double> s;
  for (int rep = 0; rep < reps; ++rep) {
    const auto t0 = std::chrono::steady_clock::now();
    arena.execute([&] { tbb::parallel_for(0, n, work); });
    s.push_back(seconds_since(t0));
  }
  return fastest_of(s);
}

// Independent mul->add chains, kLanes floats of them. How many it takes to cover the latency
// depends on the machine: 8 vectors of 16 floats left a Zen 5 core's four 512-bit pipes at two
// thirds of what 16 vectors reach (148 against 221 G ops/s, 2026-12-04), while 32 vectors spill
// registers. So each variant runs 64, 128 and 256 lanes (4 to 32 vectors) and the fastest counts.
template <int kLanes>
struct IndependentChains {
  __attribute__((always_inline)) static float run(long iterations, float m, float a) {
    float acc[kLanes];
    for (int k = 0; k < kLanes; ++k) acc[k] = 1.f + 1e-3f * static_cast<float>(k);
    for (long i = 0; i < iterations; ++i)
      for (int k = 0; k < kLanes; ++k) acc[k] = acc[k] * m + a;
    float s = 0.f;
    for (int k = 0; k < kLanes; ++k) s += acc[k];
    return s;
  }
};
constexpr std::array<int, 3> kChainLanes = {64, 128, 256};

// n values, each through kLength dependent operations (v * m + a, kLength / 2 times): the
// values are independent, each one's operations are not.
template <int kLength>
struct DependentChains {
  __attribute__((always_inline)) static void run(const float* __restrict in,
                                                 float* __restrict out, int n, float m,
                                                 float a) {
    for (int i = 0; i < n; ++i) {
      float v = in[i];
#pragma GCC unroll 64
      for (int k = 0; k < kLength / 2; ++k) v = v * m + a;
      out[i] = v;
    }
  }
};

// One kernel a lane count of kChainLanes, one a length of kDependentChainLengths.
template <size_t... I>
auto independent_chain_kernels(std::index_sequence<I...>) {
  return std::array{as_kernel_variant<IndependentChains<kChainLanes[I]>, long, float, float>()...};
}
template <size_t... I>
auto dependent_chain_kernels(std::index_sequence<I...>) {
  return std::array{as_kernel_variant<DependentChains<kDependentChainLengths[I]>, const float*,
                                      float*, int, float, float>()...};
}

}  // namespace

std::array<double, 3> load_average() {
  std::array<double, 3> l{};
  std::ifstream f("/proc/loadavg");
  f >> l[0] >> l[1] >> l[2];
  return l;
}

HostInfo query_host() {
  HostInfo h;
  h.hardware_threads = static_cast<int>(std::thread::hardware_concurrency());
  std::ifstream f("/proc/cpuinfo");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("model name", 0) == 0) {
      const size_t colon = line.find(':');
      if (colon != std::string::npos) h.cpu_model = line.substr(colon + 2);
      break;
    }
  char name[256] = {};
  if (gethostname(name, sizeof name - 1) == 0) h.hostname = name;
  h.load = load_average();
  h.cpu_kernels = cpu::pick_variant("").name;
  return h;
}

CpuUsage cpu_usage() {
  CpuUsage u;
  std::ifstream f("/proc/stat");
  std::string cpu;
  double user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0, steal = 0;
  f >> cpu >> user >> nice >> system >> idle >> iowait >> irq >> softirq >> steal;
  const double tick = static_cast<double>(sysconf(_SC_CLK_TCK));
  u.machine_busy_s = (user + nice + system + irq + softirq + steal) / tick;
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  u.process_s = static_cast<double>(r.ru_utime.tv_sec + r.ru_stime.tv_sec) +
                1e-6 * static_cast<double>(r.ru_utime.tv_usec + r.ru_stime.tv_usec);
  u.wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  return u;
}

double others_share(const CpuUsage& a, const CpuUsage& b) {
  const double cpus = std::max(1u, std::thread::hardware_concurrency());
  const double wall = b.wall_s - a.wall_s;
  if (wall <= 0) return 0;
  const double others = (b.machine_busy_s - a.machine_busy_s) - (b.process_s - a.process_s);
  return std::max(0.0, others / (wall * cpus));
}

double host_copy_gbs(int threads) {
  const size_t bytes = size_t(256) << 20;
  std::vector<char> a(bytes, 1), b(bytes, 2);
  tbb::task_arena arena(std::max(threads, 1));
  const size_t chunk = bytes / static_cast<size_t>(std::max(threads, 1));
  std::vector<double> s;
  for (int rep = 0; rep < 12; ++rep) {  // the first touches the pages
    const auto t0 = std::chrono::steady_clock::now();
    arena.execute([&] {
      tbb::parallel_for(0, std::max(threads, 1), [&](int t) {
        std::memcpy(b.data() + t * chunk, a.data() + t * chunk, chunk);
      });
    });
    s.push_back(seconds_since(t0));
  }
  return 2.0 * static_cast<double>(bytes) / fastest_of(s) / 1e9;
}

double host_float_ops_per_s(int threads) {
  const int n = std::max(threads, 1);
  const auto kernels = independent_chain_kernels(std::make_index_sequence<kChainLanes.size()>());
  tbb::task_arena arena(n);
  std::vector<float> results(static_cast<size_t>(n));
  double best = 0;
  for (size_t c = 0; c < kernels.size(); ++c) {
    // About 0.1 s a thread for every lane count: thread start-up is noise.
    const long iterations = 40'000'000L * 128 / kChainLanes[c];
    const double seconds = fastest_parallel_run(arena, n, 7, [&](int t) {
      results[static_cast<size_t>(t)] = kernels[c](iterations, 0.999f, 0.001f);
    });
    best = std::max(best, 2.0 * kChainLanes[c] * static_cast<double>(iterations) * n / seconds);
  }
  volatile float sink = 0.f;  // the results are used, so the loops are not removed
  for (float r : results) sink = sink + r;
  return best;
}

std::array<double, 3> host_chain_ops_per_s(int threads) {
  const int n = std::max(threads, 1);
  constexpr int kValues = 2048;  // 8 KiB in, 8 KiB out a worker: L1
  const auto kernels =
      dependent_chain_kernels(std::make_index_sequence<kDependentChainLengths.size()>());
  tbb::task_arena arena(n);
  std::vector<std::vector<float>> in(static_cast<size_t>(n), std::vector<float>(kValues, 1.f));
  std::vector<std::vector<float>> out(static_cast<size_t>(n), std::vector<float>(kValues));
  std::array<double, 3> rates{};
  for (size_t c = 0; c < kernels.size(); ++c) {
    const int length = kDependentChainLengths[c];
    const long passes = (1L << 20) / length;  // about 2^31 operations a worker
    const double seconds = fastest_parallel_run(arena, n, 5, [&](int t) {
      const float* a = in[static_cast<size_t>(t)].data();
      float* b = out[static_cast<size_t>(t)].data();
      for (long p = 0; p < passes; ++p) kernels[c](a, b, kValues, 0.999f, 0.001f);
    });
    rates[c] = static_cast<double>(length) * kValues * static_cast<double>(passes) * n / seconds;
  }
  return rates;
}

}  // namespace svgf::bench
