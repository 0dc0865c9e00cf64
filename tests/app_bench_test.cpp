// `prism bench` end to end (core/app/bench_command): a JSON row per backend, thread count and
// ray set, and its option errors.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

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

/// The rows of `prism bench` on the tiny scene (a floor and a wall: most bounce rays leave it,
/// so its shadow and bounce ray sets are smaller than its primary one) at 24 x 24 primary rays,
/// one thread, embree and bvh:sah:bvh8, with `extra` options.
nlohmann::json bench_tiny_rows(const test::TestDirs& dirs, const std::vector<std::string>& extra) {
  const std::filesystem::path json = dirs.out / "bench.json";
  std::vector<std::string> args = {"bench",        dirs.scene("tiny.dae", test::kTinyCollada),
                                   "--json",       json.string(),
                                   "--resolution", "24",
                                   "--threads",    "1",
                                   "--backend",    "bvh:sah:bvh8"};
  args.insert(args.end(), extra.begin(), extra.end());
  const test::ProgramResult r = test::run_prism(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(json);
  return nlohmann::json::parse(in);
}

TEST(AppBench, SmallRaySetsAreTracedOverAsManyRaysAsTheLargest) {
  const test::TestDirs dirs("bench_pass_rays");
  const nlohmann::json rows = bench_tiny_rows(dirs, {});
  size_t largest = 0;
  for (const auto& row : rows) largest = std::max(largest, row["rays"].get<size_t>());
  ASSERT_GT(largest, 0u);
  bool some_repeated = false;
  for (const auto& row : rows) {
    const size_t rays = row["rays"].get<size_t>(), per_pass = row["rays_per_pass"].get<size_t>();
    // Whole repeats of the set, the fewest that reach the largest set's size.
    EXPECT_EQ(per_pass % rays, 0u) << row.dump();
    EXPECT_GE(per_pass, largest) << row.dump();
    EXPECT_LT(per_pass - rays, largest) << row.dump();
    some_repeated = some_repeated || per_pass > rays;
    EXPECT_TRUE(row["valid"].get<bool>()) << row.dump();
  }
  EXPECT_TRUE(some_repeated) << "every set as large as the largest: nothing checked";

  // --min-pass-rays 1: every set once, and the hit counts (of one time through) the same.
  const nlohmann::json once = bench_tiny_rows(dirs, {"--min-pass-rays", "1"});
  ASSERT_EQ(once.size(), rows.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(once[i]["rays_per_pass"], once[i]["rays"]) << once[i].dump();
    EXPECT_EQ(once[i]["hits"], rows[i]["hits"]) << once[i].dump();
  }
  const nlohmann::json fixed = bench_tiny_rows(dirs, {"--min-pass-rays", "5000"});
  for (const auto& row : fixed) {
    const size_t rays = row["rays"].get<size_t>();
    EXPECT_EQ(row["rays_per_pass"].get<size_t>(), (5000 + rays - 1) / rays * rays) << row.dump();
  }
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
  EXPECT_EQ(test::run_prism({"bench", "gen:sphere:1k", "--json", json, "--min-pass-rays", "-1"})
                .exit_code,
            2);
}

}  // namespace
}  // namespace prism
