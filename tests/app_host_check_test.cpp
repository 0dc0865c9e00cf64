// The host check of `prism bench` (core/app/host_check): every CPU the process may use is timed,
// and CPUs well below the fastest are named.

#include <gtest/gtest.h>
#include <sched.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/app/host_check.h"

namespace prism {
namespace {

TEST(AppHostCheck, TimesEveryCpuTheProcessMayUse) {
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  ASSERT_EQ(sched_getaffinity(0, sizeof(allowed), &allowed), 0);
  const std::vector<CpuSpeed> speeds = measure_cpu_speeds();
  ASSERT_EQ(speeds.size(), size_t(CPU_COUNT(&allowed)));
  for (const CpuSpeed& s : speeds) {
    EXPECT_TRUE(CPU_ISSET(s.cpu, &allowed)) << s.cpu;
    // Any CPU of this century adds faster than 0.05 and slower than 20 billion times a second.
    EXPECT_TRUE(std::isfinite(s.gadds_per_s) && s.gadds_per_s > 0.05 && s.gadds_per_s < 20.0)
        << "cpu" << s.cpu << ": " << s.gadds_per_s;
  }
}

TEST(AppHostCheck, FormatsEveryCpuOnOneLine) {
  EXPECT_EQ(format_cpu_speeds({{0, 3.456}, {3, 1.9}}), "cpu0 3.46, cpu3 1.90");
  EXPECT_EQ(format_cpu_speeds({}), "");
}

TEST(AppHostCheck, NamesOnlyTheCpusWellBelowTheFastest) {
  EXPECT_EQ(describe_slow_cpus({{0, 3.5}, {1, 3.4}}), "");
  EXPECT_EQ(describe_slow_cpus({{0, 1.9}}), "");  // nothing to compare with
  const std::string slow = describe_slow_cpus({{0, 3.5}, {1, 1.95}, {2, 3.3}, {3, 2.7}});
  EXPECT_NE(slow.find("cpu1 1.95"), std::string::npos) << slow;
  EXPECT_NE(slow.find("cpu3 2.70"), std::string::npos) << slow;
  EXPECT_EQ(slow.find("cpu0"), std::string::npos) << slow;
  EXPECT_EQ(slow.find("cpu2"), std::string::npos) << slow;
  EXPECT_NE(slow.find("fastest 3.50"), std::string::npos) << slow;
  EXPECT_EQ(describe_slow_cpus({{0, 3.5}, {1, 2.7}}, 0.7), "");
}

}  // namespace
}  // namespace prism
