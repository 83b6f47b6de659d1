#pragma once
// The CPU as the benchmark reports it: model, cores, load, and measured ceilings for the CPU
// floor (copy bandwidth, and the rate of the un-fused float multiply/add the kernels compile to).
#include <array>
#include <string>

namespace svgf::bench {

struct HostInfo {
  std::string cpu_model;
  int hardware_threads = 0;
  std::array<double, 3> load{};  // /proc/loadavg at the time of the query
  std::string hostname;
  std::string cpu_kernels;  // the CPU kernel variant that runs (kernels_cpu/cpu_variant.h)
};

HostInfo query_host();
std::array<double, 3> load_average();

// CPU time used by the whole machine and by this process, to tell how much of the machine
// other processes took while a measurement ran (load averages lag by a minute).
struct CpuUsage {
  double machine_busy_s = 0;  // all CPUs, from /proc/stat (idle and iowait excluded)
  double process_s = 0;       // this process, user + system
  double wall_s = 0;          // a steady clock
};
CpuUsage cpu_usage();
// Share of the machine's CPUs that other processes used between a and b (0: quiet, 1: all).
double others_share(const CpuUsage& a, const CpuUsage& b);

// memcpy of 256 MiB split over `threads` workers; bytes read + written per second, the fastest
// of 12 copies.
double host_copy_gbs(int threads);
// Float operations per second of independent vectorized multiply-then-add chains on `threads`
// workers, compiled like the CPU kernel variant that runs (kernels_cpu/cpu_variant.h), no FMA:
// the rate the a-trous loops could reach if nothing else limited them. The fastest of 7 runs.
double host_float_ops_per_s(int threads);

// The lengths host_chain_ops_per_s measures, in its result's order.
inline constexpr std::array<int, 3> kDependentChainLengths = {8, 32, 64};
// Float operations per second of a loop over values in L1 whose iterations are independent but
// each a chain of N dependent multiplies and adds (one value, N/2 of each, alternating), for
// each N of kDependentChainLengths, on `threads` workers, compiled like the kernel variant that
// runs: what the core's out-of-order window allows when every operation waits on the one
// before. host_float_ops_per_s has chains too, but as many in flight as the registers hold;
// here one a vector, so a long chain's operations wait in the window and crowd out the next
// iterations'. An exact a-trous tap is a chain of about 30, though a shorter one did not make
// its rows faster (docs/benchmarks.md, "CPU: what limits it"). The fastest of 5 runs each.
std::array<double, 3> host_chain_ops_per_s(int threads);

}  // namespace svgf::bench
