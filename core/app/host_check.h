#pragma once

#include <string>
#include <vector>

namespace prism {

/// How fast one CPU runs a chain of dependent one-cycle integer additions.
struct CpuSpeed {
  int cpu = 0;               ///< the operating system's CPU number
  double gadds_per_s = 0.0;  ///< billions of additions per second, the best of a few tries
};

/// Times the chain on every CPU this process may run on (a few milliseconds each, one CPU at a
/// time on a thread pinned to it). An uncontended core runs it at about its clock rate; a core
/// whose other hardware thread is busy, here or in another virtual machine on the same host,
/// runs it at about half (the two threads take the front end in turns), while its vector units'
/// throughput barely changes. Such a core runs the BVH's kernels about a third slower and
/// Embree's less (docs/PERFORMANCE.md, "2026-12-06, sixth session"). Empty where the
/// CPU set or the pinning is not available, or off x86-64.
std::vector<CpuSpeed> measure_cpu_speeds();

/// The CPUs and their speeds on one line: "cpu0 3.45, cpu1 3.44" (billions of additions per
/// second).
std::string format_cpu_speeds(const std::vector<CpuSpeed>& speeds);

/// One line naming the CPUs that ran the chain at less than `threshold` of the fastest, with
/// their speeds, or an empty string when none did (or fewer than two CPUs were measured).
std::string describe_slow_cpus(const std::vector<CpuSpeed>& speeds, double threshold = 0.8);

}  // namespace prism
