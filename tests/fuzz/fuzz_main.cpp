// The libFuzzer program (build-fuzz/prism_fuzz, PRISM_FUZZ=ON): runs the target that
// $PRISM_FUZZ_TARGET names (tests/fuzz/fuzz_targets.h). scripts/fuzz sets it.

#include <cstdio>
#include <cstdlib>
#include <string>

#include "tests/fuzz/fuzz_targets.h"

namespace {
const prism::fuzz::Target* g_target = nullptr;
}  // namespace

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  const char* name = std::getenv("PRISM_FUZZ_TARGET");
  g_target = name ? prism::fuzz::find_target(name) : nullptr;
  if (!g_target) {
    std::fprintf(stderr, "prism_fuzz: set PRISM_FUZZ_TARGET to one of:");
    for (const auto& target : prism::fuzz::targets()) std::fprintf(stderr, " %s", target.name);
    std::fprintf(stderr, "\n");
    std::exit(2);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  g_target->run(data, size);
  return 0;
}
