// Progressive passes end to end (`prism render`): the image is the same bits, in every channel,
// whatever the pass size (--pass-samples) and the thread count, with and without adaptive
// sampling, on a bundled scene and a CS184 scene; a render stopped by --time-limit stops at a
// whole pass, says so in its EXR, and holds exactly the image of a render of the samples it
// took (--samples 0 K).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "color/image_output.h"
#include "core/app/render_options.h"
#include "tests/support/app_test_helpers.h"
#include "tests/support/image_compare.h"
#include "tests/support/test_support.h"

namespace prism::test {
namespace {

namespace fs = std::filesystem;

const fs::path kSpheres = fs::path(PRISM_SOURCE_DIR) / "scenes" / "data" / "cornell_spheres.json";

/// The sample count of every pixel.
std::vector<float> sample_counts(const Image& image) {
  const std::vector<float> counts = channel_values(image, "sampleCount.Y");
  EXPECT_FALSE(counts.empty()) << "no sampleCount.Y channel";
  return counts;
}

/// Renders `scene` with `spp` samples once per (pass size, threads) of `runs` (plus `extra`
/// options) and expects every image to equal the first bit for bit.
void expect_same_bits_for_passes_and_threads(const fs::path& scene, int spp,
                                             const std::vector<std::pair<int, int>>& runs,
                                             const std::vector<std::string>& extra = {}) {
  TestDirs dirs("passes");
  std::vector<std::string> base = {"-s", std::to_string(spp)};
  base.insert(base.end(), extra.begin(), extra.end());
  std::optional<Image> reference;
  for (const auto& [pass_samples, threads] : runs) {
    SCOPED_TRACE("--pass-samples " + std::to_string(pass_samples) + " -t " +
                 std::to_string(threads));
    std::vector<std::string> args = base;
    for (const std::string& a : {std::string("--pass-samples"), std::to_string(pass_samples),
                                 std::string("-t"), std::to_string(threads)}) {
      args.push_back(a);
    }
    const fs::path out =
        dirs.out / ("p" + std::to_string(pass_samples) + "_t" + std::to_string(threads) + ".exr");
    const ImageFileContents file = render_small_float_exr(scene, out, args);
    const int passes = (spp + pass_samples - 1) / pass_samples;
    EXPECT_EQ(file.attribute("prism:passes"),
              std::to_string(passes) + " of " + std::to_string(passes));
    EXPECT_EQ(file.attribute("prism:stoppedBy"), "-");
    if (!reference) {
      reference = file.image;
    } else {
      EXPECT_TRUE(same_bits(file.image, *reference));
    }
  }
}

TEST(AppPasses, DefaultPassesHoldAtLeastFourSamples) {
  // spp -> samples per pass without --pass-samples: all of them below 4, then 4 up to 256 spp
  // (64 passes there), then spp / 64 (about 64 passes).
  const std::pair<int, int> expected[] = {{1, 1},   {2, 2},   {3, 3},     {4, 4},    {5, 4},
                                          {16, 4},  {64, 4},  {255, 4},   {256, 4},  {257, 4},
                                          {320, 5}, {512, 8}, {1000, 15}, {4096, 64}};
  for (const auto& [spp, pass_samples] : expected) {
    EXPECT_EQ(default_pass_samples(spp), pass_samples) << spp << " spp";
  }
  // A render takes it when --pass-samples is not given, and says so in its EXR.
  const TestDirs dirs("passes_default");
  for (const auto& [spp, passes] : {std::pair{"3", "1 of 1"}, std::pair{"64", "16 of 16"}}) {
    const fs::path out = dirs.out / (std::string("s") + spp + ".exr");
    const ProgramResult r = run_prism(
        {"render", kSpheres.string(), "-r", "8", "6", "-s", spp, "-q", "-f", out.string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(read_image_file(out).attribute("prism:passes"), passes) << spp << " spp";
  }
}

TEST(AppPasses, BundledSceneIsTheSameForAnyPassSizeAndThreadCount) {
  // 12 samples: passes of 1, 3 (dividing), 5 (a shorter last pass), 12 (one pass).
  expect_same_bits_for_passes_and_threads(kSpheres, 12, {{1, 1}, {1, 2}, {3, 2}, {5, 1}, {12, 2}});
}

TEST(AppPasses, Cs184SceneIsTheSameForAnyPassSizeAndThreadCount) {
  PRISM_REQUIRE_CS184(scene, "CBspheres_lambertian.dae");
  expect_same_bits_for_passes_and_threads(scene, 8, {{1, 2}, {3, 1}, {8, 2}}, {"-m", "3"});
}

TEST(AppPasses, AdaptiveSamplingIsTheSameForAnyPassSizeAndThreadCount) {
  // Batches of 4 against passes of 1, 3 (batches straddle passes), 4, 5 and all 32.
  expect_same_bits_for_passes_and_threads(kSpheres, 32, {{1, 1}, {3, 2}, {4, 1}, {5, 2}, {32, 2}},
                                          {"-a", "4", "0.05"});
  // ... and adaptive sampling did stop pixels early, at a whole batch.
  TestDirs dirs("passes_adaptive");
  const Image image = render_small_float_exr(kSpheres, dirs.out / "a.exr",
                                             {"-s", "32", "-a", "4", "0.05", "--pass-samples", "3"})
                          .image;
  size_t early = 0;
  for (float count : sample_counts(image)) {
    EXPECT_GE(count, 4.0f);
    EXPECT_LE(count, 32.0f);
    EXPECT_EQ(std::fmod(count, 4.0f), 0.0f) << count << " samples: not whole batches";
    early += count < 32.0f;
  }
  EXPECT_GT(early, 0u) << "no pixel converged before 32 samples: the test shows nothing";
}

TEST(AppPasses, Cs184AdaptiveSamplingIsTheSameForAnyPassSizeAndThreadCount) {
  PRISM_REQUIRE_CS184(scene, "CBspheres_lambertian.dae");
  expect_same_bits_for_passes_and_threads(scene, 16, {{1, 1}, {3, 2}, {16, 2}},
                                          {"-a", "4", "0.05", "-m", "3"});
}

/// Renders `scene` with a time limit so small that it stops after a few of many passes, and
/// checks the stop: exit 0, recorded, whole passes, and the image of the samples taken.
void expect_time_limit_stops_at_a_whole_pass(const fs::path& scene,
                                             const std::vector<std::string>& extra) {
  TestDirs dirs("passes_limit");
  // 256 samples in passes of 4: 64 passes of about 12k camera samples each, on one thread so
  // that even a fast machine is far from done at the limit.
  std::vector<std::string> args = {"-s", "256", "--time-limit", "0.05", "-t", "1"};
  args.insert(args.end(), extra.begin(), extra.end());
  const ImageFileContents stopped = render_small_float_exr(scene, dirs.out / "stopped.exr", args);
  EXPECT_EQ(stopped.attribute("prism:stoppedBy"), "time limit");
  int k = -1, n = -1;
  ASSERT_EQ(std::sscanf(stopped.attribute("prism:passes").c_str(), "%d of %d", &k, &n), 2)
      << stopped.attribute("prism:passes");
  EXPECT_EQ(n, 64);
  ASSERT_GE(k, 1) << "at least one pass runs";
  ASSERT_LT(k, n) << "the time limit did not stop the render";
  const int taken = k * 4;
  for (float count : sample_counts(stopped.image)) {
    ASSERT_EQ(count, float(taken)) << "a pixel is not at a whole pass";
  }
  EXPECT_EQ(stopped.attribute("prism:samples"), "0 256");
  EXPECT_EQ(stopped.attribute("prism:camera_samples"), std::to_string(64 * 48 * taken));

  // The same render limited to the samples it took: a part file whose first image is the image.
  std::vector<std::string> part_args = {"-s", "256", "--samples", "0", std::to_string(taken)};
  part_args.insert(part_args.end(), extra.begin(), extra.end());
  const ImageFileContents part = render_small_float_exr(scene, dirs.out / "part.exr", part_args);
  EXPECT_EQ(part.attribute("prism:stoppedBy"), "-");
  EXPECT_EQ(part.attribute("prism:samples"), "0 " + std::to_string(taken));
  EXPECT_TRUE(same_bits(stopped.image, part.image));
}

TEST(AppPasses, TimeLimitStopsAtAWholePassWithTheImageOfItsSamples) {
  expect_time_limit_stops_at_a_whole_pass(kSpheres, {});
}

TEST(AppPasses, Cs184TimeLimitStopsAtAWholePassWithTheImageOfItsSamples) {
  PRISM_REQUIRE_CS184(scene, "CBspheres_lambertian.dae");
  expect_time_limit_stops_at_a_whole_pass(scene, {});
}

}  // namespace
}  // namespace prism::test
