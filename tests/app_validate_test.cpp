// `prism validate` end to end (core/app/validate_command): the verdict line, the failures
// (replay) file and the heatmap, the replay, and the exact rule against brute force.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/support/app_test_helpers.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {

TEST(AppValidate, PassesWritesItsFilesAndReplays) {
  const test::TestDirs dirs("validate");
  const std::string failures = (dirs.out / "failures.txt").string();
  const std::string heatmap = (dirs.out / "heat.png").string();
  const test::ProgramResult r =
      test::run_prism({"validate", "gen:grid:200", "--rays", "900", "--failures", failures,
                       "--heatmap", heatmap, "--set", "embree.refine=false"});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("hard=0"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(heatmap));
  ASSERT_TRUE(std::filesystem::exists(failures));
  const test::ProgramResult replay = test::run_prism({"validate", "--replay", failures});
  EXPECT_EQ(replay.exit_code, 0) << replay.out << replay.err;
  // bvh against brute force follows the exact rule: not a single ray may differ.
  const test::ProgramResult exact =
      test::run_prism({"validate", "gen:soup:500", "--rays", "400", "--against", "brute",
                       "--failures", failures, "--heatmap", heatmap});
  ASSERT_EQ(exact.exit_code, 0) << exact.out << exact.err;
  EXPECT_NE(exact.out.find("exact"), std::string::npos) << exact.out;
  EXPECT_EQ(exact.out.find("tie=1"), std::string::npos) << exact.out;
}

TEST(AppValidate, ReplayTakesTheBackendsTheCommandLineNames) {
  const test::TestDirs dirs("validate_replay");
  const std::string failures = (dirs.out / "failures.txt").string();
  const std::string heatmap = (dirs.out / "heat.png").string();
  const test::ProgramResult r = test::run_prism(
      {"validate", "gen:grid:200", "--rays", "300", "--failures", failures, "--heatmap", heatmap});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const test::ProgramResult from_file = test::run_prism({"validate", "--replay", failures});
  ASSERT_EQ(from_file.exit_code, 0) << from_file.out << from_file.err;
  EXPECT_NE(from_file.out.find("bvh vs embree"), std::string::npos) << from_file.out;
  const test::ProgramResult flags =
      test::run_prism({"validate", "--replay", failures, "--accel", "brute", "--against", "bvh"});
  ASSERT_EQ(flags.exit_code, 0) << flags.out << flags.err;
  EXPECT_NE(flags.out.find("brute vs bvh"), std::string::npos) << flags.out;
}

}  // namespace
}  // namespace prism
