#pragma once

namespace prism {

/// The instruction-set features of x86-64-v3 (AVX2, FMA, BMI, ...) that prism's default build
/// is compiled for (PRISM_CPU_LEVEL in CMakeLists.txt), one flag each.
struct CpuLevelFeatures {
  bool avx = false;
  bool avx2 = false;
  bool bmi = false;
  bool bmi2 = false;
  bool f16c = false;
  bool fma = false;
  bool lzcnt = false;
  bool movbe = false;
};

/// The features of the CPU this process runs on (with the OS saving the AVX registers).
/// Compiled for any x86-64 CPU, so it may run before anything else is known to be safe.
CpuLevelFeatures cpu_level_features();

/// The name of the first feature of x86-64-v3 that `cpu` lacks, or nullptr when it has them all.
/// A string literal: no allocation, so callable where nothing built for x86-64-v3 may run.
const char* first_missing_x86_64_v3_feature(const CpuLevelFeatures& cpu);

}  // namespace prism
