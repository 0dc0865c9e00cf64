// `prism bench` end to end (core/app/bench_command): a JSON row per backend, thread count and
// ray set, and its option errors.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "tests/support/app_test_helpers.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {

TEST(AppBench, WritesARowPerBackendThreadAndRaySet) {
  const test::TestDirs dirs("bench");
  const std::filesystem::path json = dirs.out / "bench.json";
  const test::ProgramResult r = test::run_prism({"bench", "gen:sphere:2k", "--json", json.string(),
                                                 "--resolution", "24", "--threads", "1,2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(json);
  const nlohmann::json rows = nlohmann::json::parse(in);
  // embree + 3 splits x 3 layouts, each at 2 thread counts on 5 ray sets.
  ASSERT_EQ(rows.size(), 10u * 2u * 5u);
  std::set<std::string> configs;
  for (const auto& row : rows) {
    configs.insert(row["accel"].get<std::string>() + row["split"].get<std::string>() +
                   row["layout"].get<std::string>());
    EXPECT_GT(row["mrays_per_s"].get<double>(), 0.0);
    EXPECT_GE(row["passes"].get<int>(), 5);
    EXPECT_LE(row["mrays_min"].get<double>(), row["mrays_per_s"].get<double>());
    EXPECT_GE(row["mrays_max"].get<double>(), row["mrays_per_s"].get<double>());
    EXPECT_GT(row["bytes_per_triangle"].get<double>(), 0.0);
    // Same rays, exact backends: every hit count equals Embree's on this closed mesh.
    EXPECT_TRUE(row["valid"].get<bool>()) << row.dump();
  }
  EXPECT_EQ(configs.size(), 10u);
  EXPECT_NE(r.out.find("sphere_2k"), std::string::npos) << r.out;  // the summary table
}

TEST(AppBench, RejectsBadOptions) {
  EXPECT_EQ(test::run_prism({"bench", "gen:sphere:1k"}).exit_code, 2);  // no --json
  const test::TestDirs dirs("bench_bad");
  const std::string json = (dirs.out / "b.json").string();
  EXPECT_EQ(test::run_prism({"bench", "gen:sphere:1k", "--json", json, "--passes", "3"}).exit_code,
            2);
  EXPECT_EQ(
      test::run_prism({"bench", "gen:sphere:1k", "--json", json, "--backend", "bvh:x:y"}).exit_code,
      2);
  EXPECT_EQ(test::run_prism({"bench", "gen:cube:1k", "--json", json}).exit_code, 2);
}

}  // namespace
}  // namespace prism
