// core/cpu_level.h: the start-up check of the CPU names the first x86-64-v3 feature it lacks, and
// reads the features of the CPU it runs on as the compiler's own builtin does.

#include <gtest/gtest.h>

#include <string>

#include "core/cpu_level.h"

namespace prism {
namespace {

CpuLevelFeatures all_features() {
  CpuLevelFeatures cpu;
  cpu.avx = cpu.avx2 = cpu.bmi = cpu.bmi2 = cpu.f16c = cpu.fma = cpu.lzcnt = cpu.movbe = true;
  return cpu;
}

TEST(CoreCpuLevel, NothingMissingWithEveryFeature) {
  EXPECT_EQ(first_missing_x86_64_v3_feature(all_features()), nullptr);
}

TEST(CoreCpuLevel, NamesEachMissingFeature) {
  const struct {
    bool CpuLevelFeatures::*flag;
    std::string name;
  } features[] = {{&CpuLevelFeatures::avx, "AVX"},     {&CpuLevelFeatures::avx2, "AVX2"},
                  {&CpuLevelFeatures::bmi, "BMI"},     {&CpuLevelFeatures::bmi2, "BMI2"},
                  {&CpuLevelFeatures::f16c, "F16C"},   {&CpuLevelFeatures::fma, "FMA"},
                  {&CpuLevelFeatures::lzcnt, "LZCNT"}, {&CpuLevelFeatures::movbe, "MOVBE"}};
  for (const auto& feature : features) {
    CpuLevelFeatures cpu = all_features();
    cpu.*feature.flag = false;
    const char* missing = first_missing_x86_64_v3_feature(cpu);
    ASSERT_NE(missing, nullptr) << feature.name;
    EXPECT_EQ(std::string(missing), feature.name);
  }
  // Several missing: the first in the order above.
  CpuLevelFeatures old_cpu;  // none at all
  EXPECT_EQ(std::string(first_missing_x86_64_v3_feature(old_cpu)), "AVX");
}

TEST(CoreCpuLevel, ReadsThisCpuAsTheBuiltinDoes) {
  __builtin_cpu_init();
  const CpuLevelFeatures cpu = cpu_level_features();
  EXPECT_EQ(cpu.avx, __builtin_cpu_supports("avx") != 0);
  EXPECT_EQ(cpu.avx2, __builtin_cpu_supports("avx2") != 0);
  EXPECT_EQ(cpu.bmi2, __builtin_cpu_supports("bmi2") != 0);
  EXPECT_EQ(cpu.fma, __builtin_cpu_supports("fma") != 0);
#if !defined(__clang__)
  // This program runs, so the CPU has what it was compiled for.
  if (__builtin_cpu_supports("x86-64-v3")) {
    EXPECT_EQ(first_missing_x86_64_v3_feature(cpu), nullptr);
  } else {
    EXPECT_NE(first_missing_x86_64_v3_feature(cpu), nullptr);
  }
#endif
}

}  // namespace
}  // namespace prism
