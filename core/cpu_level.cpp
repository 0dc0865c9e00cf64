// Compiled for any x86-64 CPU whatever PRISM_CPU_LEVEL says (core/CMakeLists.txt): this file
// checks, before any other code of the program or module runs, that the CPU can run the rest.
// It calls no inline function of a header that other files also compile (their copies would be
// built for x86-64-v3, and the linker keeps one of them): only builtins and write(2).

#include "core/cpu_level.h"

#include <unistd.h>

#include <cstring>

namespace prism {

CpuLevelFeatures cpu_level_features() {
  __builtin_cpu_init();
  CpuLevelFeatures cpu;
  cpu.avx = __builtin_cpu_supports("avx");
  cpu.avx2 = __builtin_cpu_supports("avx2");
  cpu.bmi = __builtin_cpu_supports("bmi");
  cpu.bmi2 = __builtin_cpu_supports("bmi2");
  cpu.fma = __builtin_cpu_supports("fma");
#if defined(__clang__)
  // clang 14 cannot ask for these three; every CPU with AVX2 and BMI2 has them.
  cpu.f16c = cpu.lzcnt = cpu.movbe = cpu.avx2 && cpu.bmi2;
#else
  cpu.f16c = __builtin_cpu_supports("f16c");
  cpu.lzcnt = __builtin_cpu_supports("lzcnt");
  cpu.movbe = __builtin_cpu_supports("movbe");
#endif
  return cpu;
}

const char* first_missing_x86_64_v3_feature(const CpuLevelFeatures& cpu) {
  if (!cpu.avx) return "AVX";
  if (!cpu.avx2) return "AVX2";
  if (!cpu.bmi) return "BMI";
  if (!cpu.bmi2) return "BMI2";
  if (!cpu.f16c) return "F16C";
  if (!cpu.fma) return "FMA";
  if (!cpu.lzcnt) return "LZCNT";
  if (!cpu.movbe) return "MOVBE";
  return nullptr;
}

#if defined(PRISM_REQUIRES_X86_64_V3)
namespace {

void write_stderr(const char* text) {
  ssize_t ignored = ::write(STDERR_FILENO, text, std::strlen(text));
  (void)ignored;
}

/// Runs before the constructors of the program's (or Python module's) other files (priority
/// 101 is the first one available to programs): a CPU without x86-64-v3 gets one line and exit
/// code 3 (a resource failure, README "Exit codes") instead of an illegal instruction later.
[[gnu::constructor(101)]] void require_x86_64_v3() {
  const char* missing = first_missing_x86_64_v3_feature(cpu_level_features());
  if (!missing) return;
  write_stderr("prism: error: this CPU lacks ");
  write_stderr(missing);
  write_stderr(
      ", which this build of prism needs (it is compiled for x86-64-v3: AVX2, FMA, BMI2); "
      "build it with cmake -DPRISM_CPU_LEVEL=x86-64 to run on any x86-64 CPU\n");
  _exit(3);
}

}  // namespace
#endif

}  // namespace prism
