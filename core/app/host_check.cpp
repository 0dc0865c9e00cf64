#include "core/app/host_check.h"

#include <fmt/format.h>
#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <thread>

namespace prism {
#if defined(__x86_64__)
namespace {

/// Seconds for `count` dependent additions on the calling thread.
double time_add_chain(uint64_t count) {
  const auto start = std::chrono::steady_clock::now();
  uint64_t x = 0;
  for (uint64_t i = 0; i < count; ++i) {
    // One add per iteration that the compiler can neither fold nor vectorise.
    __asm__ volatile("add $1, %0" : "+r"(x));
  }
  const auto end = std::chrono::steady_clock::now();
  return x == count ? std::chrono::duration<double>(end - start).count() : 0.0;
}

/// The chain's speed on `cpu`, or 0 if the thread cannot be pinned there.
double speed_on(int cpu) {
  double best = 0.0;
  std::thread worker([&] {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(cpu, &set);
    if (pthread_setaffinity_np(pthread_self(), sizeof(set), &set) != 0) return;
    constexpr uint64_t kAdds = 5'000'000;  // about 1.5 ms at 3.5 GHz
    for (int attempt = 0; attempt < 3; ++attempt) {
      const double seconds = time_add_chain(kAdds);
      if (seconds > 0.0) best = std::max(best, double(kAdds) / seconds * 1e-9);
    }
  });
  worker.join();
  return best;
}

}  // namespace
#endif

std::vector<CpuSpeed> measure_cpu_speeds() {
  std::vector<CpuSpeed> out;
#if defined(__x86_64__)
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof(allowed), &allowed) != 0) return out;
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu) {
    if (!CPU_ISSET(cpu, &allowed)) continue;
    const double speed = speed_on(cpu);
    if (speed > 0.0) out.push_back({cpu, speed});
  }
#endif
  return out;
}

std::string format_cpu_speeds(const std::vector<CpuSpeed>& speeds) {
  std::string line;
  for (const CpuSpeed& s : speeds) {
    line += fmt::format("{}cpu{} {:.2f}", line.empty() ? "" : ", ", s.cpu, s.gadds_per_s);
  }
  return line;
}

std::string describe_slow_cpus(const std::vector<CpuSpeed>& speeds, double threshold) {
  if (speeds.size() < 2) return {};
  double fastest = 0.0;
  for (const CpuSpeed& s : speeds) fastest = std::max(fastest, s.gadds_per_s);
  std::vector<CpuSpeed> slow;
  for (const CpuSpeed& s : speeds) {
    if (s.gadds_per_s < threshold * fastest) slow.push_back(s);
  }
  if (slow.empty()) return {};
  return fmt::format(
      "{} (fastest {:.2f} G adds/s): another thread shares these cores, so timings on them run "
      "slow",
      format_cpu_speeds(slow), fastest);
}

}  // namespace prism
