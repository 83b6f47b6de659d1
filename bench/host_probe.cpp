#include "bench/host_probe.h"

#include <sys/resource.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <fstream>
#include <thread>
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

// Independent mul->add chains, kLanes floats of them. How many it takes to cover the latency
// depends on the machine: 8 vectors of 16 floats left a Zen 5 core's four 512-bit pipes at two
// thirds of what 16 vectors reach (148 against 221 G ops/s, 2026-12-04), while 32 vectors spill
// registers. So each variant runs 64, 128 and 256 lanes (4 to 32 vectors) and the fastest counts.
template <int kLanes>
__attribute__((always_inline)) inline float ops_chains(long iterations, float m, float a) {
  float acc[kLanes];
  for (int k = 0; k < kLanes; ++k) acc[k] = 1.f + 1e-3f * static_cast<float>(k);
  for (long i = 0; i < iterations; ++i)
    for (int k = 0; k < kLanes; ++k) acc[k] = acc[k] * m + a;
  float s = 0.f;
  for (int k = 0; k < kLanes; ++k) s += acc[k];
  return s;
}
constexpr int kChainLanes[] = {64, 128, 256};

// The chains compiled like each CPU kernel variant (kernels_cpu/CMakeLists.txt), and with this
// file's own flags (SVGF_CPU_ARCH_FLAGS in a build of one custom variant). Static functions
// with the chains inlined: nothing of one is shared with another.
using OpsKernel = float (*)(long, float, float);
template <int kLanes>
__attribute__((noinline)) float ops_default(long n, float m, float a) {
  return ops_chains<kLanes>(n, m, a);
}
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
template <int kLanes>
__attribute__((noinline, target("arch=x86-64-v2"))) float ops_v2(long n, float m, float a) {
  return ops_chains<kLanes>(n, m, a);
}
template <int kLanes>
__attribute__((noinline, target("arch=x86-64-v3"))) float ops_v3(long n, float m, float a) {
  return ops_chains<kLanes>(n, m, a);
}
template <int kLanes>
__attribute__((noinline, target("arch=x86-64-v4,prefer-vector-width=512"))) float ops_v4(
    long n, float m, float a) {
  return ops_chains<kLanes>(n, m, a);
}
#endif

// One kernel a lane count of kChainLanes.
struct OpsKernels {
  OpsKernel of_lanes[3];
};

// The chains as the variant the kernels run (cpu::pick_variant) is compiled.
OpsKernels ops_kernels() {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  const std::string id = cpu::pick_variant("").id;
  if (id == "v2") return {{ops_v2<64>, ops_v2<128>, ops_v2<256>}};
  if (id == "v3") return {{ops_v3<64>, ops_v3<128>, ops_v3<256>}};
  if (id == "v4") return {{ops_v4<64>, ops_v4<128>, ops_v4<256>}};
#endif
  return {{ops_default<64>, ops_default<128>, ops_default<256>}};
}

// n values, each through `length` dependent operations (v * m + a, length / 2 times): the
// values are independent, each one's operations are not.
template <int kLength>
__attribute__((always_inline)) inline void dependent_chains(const float* __restrict in,
                                                            float* __restrict out, int n,
                                                            float m, float a) {
  for (int i = 0; i < n; ++i) {
    float v = in[i];
#pragma GCC unroll 64
    for (int k = 0; k < kLength / 2; ++k) v = v * m + a;
    out[i] = v;
  }
}
using ChainKernel = void (*)(const float*, float*, int, float, float);
template <int kLength>
__attribute__((noinline)) void chains_default(const float* in, float* out, int n, float m,
                                              float a) {
  dependent_chains<kLength>(in, out, n, m, a);
}
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
template <int kLength>
__attribute__((noinline, target("arch=x86-64-v2"))) void chains_v2(const float* in, float* out,
                                                                   int n, float m, float a) {
  dependent_chains<kLength>(in, out, n, m, a);
}
template <int kLength>
__attribute__((noinline, target("arch=x86-64-v3"))) void chains_v3(const float* in, float* out,
                                                                   int n, float m, float a) {
  dependent_chains<kLength>(in, out, n, m, a);
}
template <int kLength>
__attribute__((noinline, target("arch=x86-64-v4,prefer-vector-width=512"))) void chains_v4(
    const float* in, float* out, int n, float m, float a) {
  dependent_chains<kLength>(in, out, n, m, a);
}
#endif
static_assert(kDependentChainLengths[0] == 8 && kDependentChainLengths[1] == 32 &&
              kDependentChainLengths[2] == 64);

// One kernel a length of kDependentChainLengths, as the variant that runs is compiled.
std::array<ChainKernel, 3> chain_kernels() {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  const std::string id = cpu::pick_variant("").id;
  if (id == "v2") return {chains_v2<8>, chains_v2<32>, chains_v2<64>};
  if (id == "v3") return {chains_v3<8>, chains_v3<32>, chains_v3<64>};
  if (id == "v4") return {chains_v4<8>, chains_v4<32>, chains_v4<64>};
#endif
  return {chains_default<8>, chains_default<32>, chains_default<64>};
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
  const OpsKernels kernels = ops_kernels();
  tbb::task_arena arena(n);
  std::vector<float> results(static_cast<size_t>(n));
  double best = 0;
  for (int c = 0; c < 3; ++c) {
    // About 0.1 s a thread for every lane count: thread start-up is noise.
    const long iterations = 40'000'000L * 128 / kChainLanes[c];
    std::vector<double> s;
    for (int rep = 0; rep < 7; ++rep) {
      const auto t0 = std::chrono::steady_clock::now();
      arena.execute([&] {
        tbb::parallel_for(0, n, [&](int t) {
          results[static_cast<size_t>(t)] = kernels.of_lanes[c](iterations, 0.999f, 0.001f);
        });
      });
      s.push_back(seconds_since(t0));
    }
    best = std::max(best, 2.0 * kChainLanes[c] * static_cast<double>(iterations) * n /
                              fastest_of(s));
  }
  volatile float sink = 0.f;  // the results are used, so the loops are not removed
  for (float r : results) sink = sink + r;
  return best;
}

std::array<double, 3> host_chain_ops_per_s(int threads) {
  const int n = std::max(threads, 1);
  constexpr int kValues = 2048;  // 8 KiB in, 8 KiB out a worker: L1
  const std::array<ChainKernel, 3> kernels = chain_kernels();
  tbb::task_arena arena(n);
  std::vector<std::vector<float>> in(static_cast<size_t>(n)), out(static_cast<size_t>(n));
  for (int t = 0; t < n; ++t) {
    in[static_cast<size_t>(t)].assign(kValues, 1.f);
    out[static_cast<size_t>(t)].assign(kValues, 0.f);
  }
  std::array<double, 3> rates{};
  for (size_t c = 0; c < kernels.size(); ++c) {
    const int length = kDependentChainLengths[c];
    const long passes = (1L << 20) / length;  // about 2^31 operations a worker
    std::vector<double> s;
    for (int rep = 0; rep < 5; ++rep) {
      const auto t0 = std::chrono::steady_clock::now();
      arena.execute([&] {
        tbb::parallel_for(0, n, [&](int t) {
          const float* a = in[static_cast<size_t>(t)].data();
          float* b = out[static_cast<size_t>(t)].data();
          for (long p = 0; p < passes; ++p) kernels[c](a, b, kValues, 0.999f, 0.001f);
        });
      });
      s.push_back(seconds_since(t0));
    }
    rates[c] = static_cast<double>(length) * kValues * static_cast<double>(passes) * n /
               fastest_of(s);
  }
  return rates;
}

}  // namespace svgf::bench
