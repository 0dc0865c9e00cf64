// The fuzz corpora replayed (tests/fuzz/README.md): every committed seed and every regression
// input of every fuzz target runs through the target's function, as the fuzzer ran it, in the
// normal build. A pass is returning (a prism::Error inside the target counts); an escaping
// exception fails the test naming the input, a crash stops it.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tests/fuzz/fuzz_targets.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {

using test::read_bytes;

namespace fs = std::filesystem;

const fs::path kFuzzDir = fs::path(PRISM_SOURCE_DIR) / "tests" / "fuzz";

/// The files of `folder`, sorted; none when it does not exist.
std::vector<fs::path> files_in(const fs::path& folder) {
  std::vector<fs::path> files;
  if (!fs::is_directory(folder)) return files;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::string> target_names() {
  std::vector<std::string> names;
  for (const auto& target : fuzz::targets()) names.emplace_back(target.name);
  return names;
}

class AppFuzzCorpus : public testing::TestWithParam<std::string> {};

/// Every seed and regression input of the target: no exception but prism::Error escapes.
TEST_P(AppFuzzCorpus, ReplaysWithoutCrash) {
  const fuzz::Target* target = fuzz::find_target(GetParam());
  ASSERT_NE(target, nullptr);
  std::vector<fs::path> inputs = files_in(kFuzzDir / "corpus" / target->name);
  ASSERT_FALSE(inputs.empty()) << "no seeds in tests/fuzz/corpus/" << target->name;
  const std::vector<fs::path> regressions = files_in(kFuzzDir / "regressions" / target->name);
  inputs.insert(inputs.end(), regressions.begin(), regressions.end());
  for (const fs::path& input : inputs) {
    const std::string bytes = read_bytes(input);
    try {
      target->run(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
    } catch (const std::exception& e) {
      ADD_FAILURE() << input << ": " << e.what();
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Targets, AppFuzzCorpus, testing::ValuesIn(target_names()),
                         [](const testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });

/// Every corpus and regression folder belongs to a target (no corpus left behind by a rename).
TEST(AppFuzzCorpus, FoldersNameTargets) {
  for (const char* kind : {"corpus", "regressions"}) {
    if (!fs::is_directory(kFuzzDir / kind)) continue;
    for (const auto& entry : fs::directory_iterator(kFuzzDir / kind)) {
      EXPECT_NE(fuzz::find_target(entry.path().filename().string()), nullptr)
          << entry.path() << " names no fuzz target";
    }
  }
}

}  // namespace
}  // namespace prism
