// `prism merge` end to end (core/app/merge_command): parts of a frame (crops, sample ranges, both,
// on pass boundaries or not, merged in one go or in steps) add up to the single render bit for
// bit; parts that overlap, leave a gap, belong to another render, were stopped early or are not
// parts are refused with one line and no output. Small renders (64 x 48, 8 spp): each test runs
// prism a few times, in well under a second each.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "color/image_output.h"
#include "core/app/merge_command.h"
#include "core/app/render_state.h"
#include "core/error.h"
#include "tests/support/app_test_helpers.h"
#include "tests/support/test_support.h"

namespace prism::test {
namespace {

namespace fs = std::filesystem;

const std::string kCornell = PRISM_SOURCE_DIR "/scenes/data/cornell_spheres.json";

/// What every render of these tests has: the scene, 64 x 48, float EXRs, no progress output.
std::vector<std::string> common_args(const std::string& scene) {
  return {"render", scene, "-r", "64", "48", "--exr-type", "float", "-q"};
}

/// One frame split into parts: renders into `dirs.out`, merges into `merged` (a folder that
/// stays empty when a merge fails).
struct Frame {
  TestDirs dirs;
  fs::path merged;
  std::vector<std::string> render_args;  ///< every part's and the single render's options

  Frame(const std::string& tag, const std::string& scene,
        const std::vector<std::string>& options = {"-s", "8"})
      : dirs(tag), merged(dirs.root / "merged"), render_args(common_args(scene)) {
    fs::create_directories(merged);
    render_args.insert(render_args.end(), options.begin(), options.end());
  }

  /// Renders out/`name` with the frame's options and `extra` (--crop, --samples, ...).
  std::string render(const std::string& name, const std::vector<std::string>& extra = {}) const {
    std::vector<std::string> args = render_args;
    args.insert(args.end(), extra.begin(), extra.end());
    const std::string path = (dirs.out / name).string();
    args.insert(args.end(), {"-f", path});
    const ProgramResult r = run_prism(args);
    EXPECT_EQ(r.exit_code, 0) << name << ": " << r.err;
    return path;
  }
  std::string crop(const std::string& name, int x0, int y0, int x1, int y1,
                   std::vector<std::string> extra = {}) const {
    extra.insert(extra.end(), {"--crop", std::to_string(x0), std::to_string(y0), std::to_string(x1),
                               std::to_string(y1)});
    return render(name, extra);
  }
  std::string samples(const std::string& name, int first, int last,
                      std::vector<std::string> extra = {}) const {
    extra.insert(extra.end(), {"--samples", std::to_string(first), std::to_string(last)});
    return render(name, extra);
  }

  /// Runs `prism merge PARTS... -f merged/OUTPUT EXTRA...`.
  ProgramResult merge(const std::vector<std::string>& parts, const std::string& output,
                      const std::vector<std::string>& extra = {}) const {
    std::vector<std::string> args = {"merge"};
    args.insert(args.end(), parts.begin(), parts.end());
    args.insert(args.end(), {"-f", (merged / output).string()});
    args.insert(args.end(), extra.begin(), extra.end());
    return run_prism(args);
  }
};

/// Every channel of the first image of two EXRs, bit for bit, with their windows and names.
void expect_same_pixels(const fs::path& expected, const fs::path& actual) {
  const ImageFileContents a = read_image_file(expected);
  const ImageFileContents b = read_image_file(actual);
  EXPECT_EQ(a.image.channel_names, b.image.channel_names);
  EXPECT_EQ(a.channel_formats, b.channel_formats);
  EXPECT_EQ(a.image.width, b.image.width);
  EXPECT_EQ(a.image.height, b.image.height);
  EXPECT_EQ(a.image.x, b.image.x);
  EXPECT_EQ(a.image.y, b.image.y);
  EXPECT_EQ(a.image.full_width, b.image.full_width);
  EXPECT_EQ(a.image.full_height, b.image.full_height);
  ASSERT_EQ(a.image.pixels.size(), b.image.pixels.size());
  size_t differing = 0;
  for (size_t i = 0; i < a.image.pixels.size(); ++i) {
    differing += std::memcmp(&a.image.pixels[i], &b.image.pixels[i], sizeof(float)) != 0;
  }
  EXPECT_EQ(differing, 0u) << actual << " differs from " << expected << " in " << differing
                           << " of " << a.image.pixels.size() << " values";
}

/// A merge that worked: exit 0, one summary line naming the output.
void expect_merged(const ProgramResult& r, const std::string& what) {
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(line_count(r.out), 1u) << r.out;
  EXPECT_NE(r.out.find(what), std::string::npos) << r.out;
}

/// A refused merge: exit 2, one line naming `mentions`, nothing written.
void expect_refused(const Frame& frame, const ProgramResult& r,
                    const std::vector<std::string>& mentions) {
  expect_one_line_error(r, 2, mentions);
  EXPECT_EQ(r.out, "");
  EXPECT_TRUE(dir_entries(frame.merged).empty()) << "a refused merge wrote a file";
}

TEST(AppMerge, TwoByTwoCropsAddUpToTheRenderBitForBit) {
  const Frame frame("merge_grid", kCornell);
  const std::string full = frame.render("full.exr");
  // Given in any order: integer sums do not depend on it.
  const std::vector<std::string> parts = {
      frame.crop("c11.exr", 32, 24, 64, 48), frame.crop("c00.exr", 0, 0, 32, 24),
      frame.crop("c10.exr", 32, 0, 64, 24), frame.crop("c01.exr", 0, 24, 32, 48)};
  const ProgramResult r = frame.merge(parts, "frame.exr", {"--png"});
  expect_merged(r, "merged 4 parts: 64x48 at 8 spp");
  EXPECT_EQ(dir_entries(frame.merged), (std::vector<std::string>{"frame.exr", "frame.png"}));
  expect_same_pixels(full, frame.merged / "frame.exr");

  // The provenance: the parts' settings, what was merged, a whole frame (no crop, no state).
  const ImageFileContents merged = read_image_file(frame.merged / "frame.exr");
  const ImageFileContents single = read_image_file(full);
  for (const char* key :
       {"prism:scene", "prism:integrator", "prism:seed", "prism:spp", "prism:resolution",
        "prism:params", "prism:samples", "prism:colorSpace"}) {
    EXPECT_EQ(merged.attribute(key), single.attribute(key)) << key;
  }
  EXPECT_EQ(merged.attribute("prism:crop"), "");
  EXPECT_EQ(merged.attribute(kRenderStateAttribute), "");
  EXPECT_EQ(merged.attribute("prism:camera_samples"), std::to_string(64 * 48 * 8));
  const auto from = nlohmann::json::parse(merged.attribute("prism:mergedFrom"));
  ASSERT_EQ(from.size(), 4u);
  EXPECT_EQ(from[0]["file"], parts[0]);
  EXPECT_EQ(from[0]["window"], nlohmann::json({32, 24, 64, 48}));
  EXPECT_EQ(from[0]["samples"], nlohmann::json({0, 8}));
  double render_ms = 0.0;
  for (const auto& part : parts) {
    render_ms += std::stod(read_image_file(part).attribute("prism:render_ms"));
  }
  EXPECT_NEAR(std::stod(merged.attribute("prism:render_ms")), render_ms, 0.01);
}

TEST(AppMerge, UnevenCropsAddUpToTheRenderBitForBit) {
  // Edges off the 16-pixel tiles, slivers one pixel wide, a layout no grid makes.
  const Frame frame("merge_uneven", kCornell);
  const std::string full = frame.render("full.exr");
  const ProgramResult r =
      frame.merge({frame.crop("a.exr", 0, 0, 13, 48), frame.crop("b.exr", 13, 0, 64, 5),
                   frame.crop("c.exr", 13, 5, 14, 48), frame.crop("d.exr", 14, 5, 64, 47),
                   frame.crop("e.exr", 14, 47, 64, 48)},
                  "frame.exr");
  expect_merged(r, "merged 5 parts");
  expect_same_pixels(full, frame.merged / "frame.exr");
}

TEST(AppMerge, SampleRangesAddUpToTheRenderBitForBit) {
  const Frame frame("merge_samples", kCornell);
  const std::string full = frame.render("full.exr");
  // Two ranges on pass boundaries (one sample per pass at 8 spp).
  expect_merged(
      frame.merge({frame.samples("s0.exr", 0, 4), frame.samples("s1.exr", 4, 8)}, "two.exr"),
      "merged 2 parts");
  expect_same_pixels(full, frame.merged / "two.exr");
  // Three ranges off the passes of 4 samples, in another order.
  const std::vector<std::string> passes = {"--pass-samples", "4"};
  expect_merged(
      frame.merge({frame.samples("t2.exr", 7, 8, passes), frame.samples("t0.exr", 0, 3, passes),
                   frame.samples("t1.exr", 3, 7, passes)},
                  "three.exr"),
      "merged 3 parts");
  expect_same_pixels(full, frame.merged / "three.exr");
}

TEST(AppMerge, CropsTimesSampleRangesAddUpToTheRenderBitForBit) {
  // Samples [0, 5) of the whole image, then [5, 8) in three crops of two different layouts.
  const Frame frame("merge_mixed", kCornell);
  const std::string full = frame.render("full.exr");
  const ProgramResult r =
      frame.merge({frame.samples("first.exr", 0, 5),
                   frame.crop("left.exr", 0, 0, 21, 48, {"--samples", "5", "8"}),
                   frame.crop("top.exr", 21, 0, 64, 30, {"--samples", "5", "8"}),
                   frame.crop("bottom.exr", 21, 30, 64, 48, {"--samples", "5", "8"})},
                  "frame.exr");
  expect_merged(r, "merged 4 parts");
  expect_same_pixels(full, frame.merged / "frame.exr");
}

TEST(AppMerge, MergedPartsMergeFurther) {
  const Frame frame("merge_steps", kCornell);
  const std::string full = frame.render("full.exr");
  // Crops: top half, then bottom half, then the two halves.
  ProgramResult r = frame.merge(
      {frame.crop("c00.exr", 0, 0, 32, 24), frame.crop("c10.exr", 32, 0, 64, 24)}, "top.exr");
  expect_merged(r, "merged 2 parts into a part (x in [0, 64), y in [0, 24), samples [0, 8)");
  EXPECT_NE(r.out.find("merge it with the rest"), std::string::npos) << r.out;
  const ImageFileContents top = read_image_file(frame.merged / "top.exr");
  EXPECT_EQ(top.attribute("prism:crop"), "0 0 64 24");
  EXPECT_NE(top.attribute(kRenderStateAttribute), "");
  r = frame.merge({frame.crop("c01.exr", 0, 24, 32, 48), frame.crop("c11.exr", 32, 24, 64, 48)},
                  "bottom.exr");
  expect_merged(r, "into a part");
  r = frame.merge({(frame.merged / "bottom.exr").string(), (frame.merged / "top.exr").string()},
                  "frame.exr");
  expect_merged(r, "merged 2 parts: 64x48");
  expect_same_pixels(full, frame.merged / "frame.exr");
  const auto from = nlohmann::json::parse(
      read_image_file(frame.merged / "frame.exr").attribute("prism:mergedFrom"));
  ASSERT_EQ(from.size(), 2u);
  EXPECT_EQ(from[1]["mergedFrom"].size(), 2u) << from.dump();  // the parts of top.exr

  // Sample ranges: [0, 2) + [2, 5), then + [5, 8); the partial result in a part's own terms.
  r = frame.merge({frame.samples("s0.exr", 0, 2), frame.samples("s1.exr", 2, 5)}, "s05.exr");
  expect_merged(r, "samples [0, 5)");
  const RenderState part = read_render_state(frame.merged / "s05.exr");
  EXPECT_EQ(part.record.samples, (SampleRange{0, 5}));
  EXPECT_EQ(part.record.options.sample_range, (std::pair<int, int>(0, 5)));
  EXPECT_FALSE(part.record.options.crop.has_value());
  r = frame.merge({frame.samples("s2.exr", 5, 8), (frame.merged / "s05.exr").string()},
                  "samples.exr");
  expect_merged(r, "merged 2 parts: 64x48");
  expect_same_pixels(full, frame.merged / "samples.exr");
}

TEST(AppMerge, Cs184SceneSplitsAddUpToTheRenderBitForBit) {
  PRISM_REQUIRE_CS184(scene, "CBspheres_lambertian.dae");
  const Frame frame("merge_cs184", scene.string());
  const std::string full = frame.render("full.exr");
  const ProgramResult r =
      frame.merge({frame.crop("left.exr", 0, 0, 40, 48),
                   frame.crop("right0.exr", 40, 0, 64, 48, {"--samples", "0", "3"}),
                   frame.crop("right1.exr", 40, 0, 64, 48, {"--samples", "3", "8"})},
                  "frame.exr");
  expect_merged(r, "merged 3 parts");
  expect_same_pixels(full, frame.merged / "frame.exr");
}

TEST(AppMerge, AdaptiveCropsAddUpToTheRenderBitForBit) {
  const Frame frame("merge_adaptive", kCornell, {"-s", "32", "-a", "4", "0.2"});
  const std::string full = frame.render("full.exr");
  const std::string left = frame.crop("left.exr", 0, 0, 24, 48);
  const std::string right = frame.crop("right.exr", 24, 0, 64, 48);
  const ProgramResult r = frame.merge({left, right}, "frame.exr");
  expect_merged(r, "merged 2 parts: 64x48 at 32 spp");
  expect_same_pixels(full, frame.merged / "frame.exr");
  // Adaptive sampling stopped pixels early, and the merge kept where.
  const ImageFileContents merged = read_image_file(frame.merged / "frame.exr");
  EXPECT_LT(std::stod(merged.attribute("prism:camera_samples")), 64.0 * 48 * 32);
  // Like the render, the merge draws the sample-rate picture.
  EXPECT_EQ(dir_entries(frame.merged), (std::vector<std::string>{"frame.exr", "frame_rate.png"}));
  EXPECT_EQ(read_image_file(frame.merged / "frame_rate.png").image.pixels,
            read_image_file(frame.dirs.out / "full_rate.png").image.pixels);

  // A merged part keeps every pixel's state, the adaptive sampler's too.
  const std::string top = frame.crop("top.exr", 0, 0, 64, 20);
  ASSERT_EQ(frame.merge({top}, "top.exr").exit_code, 0);
  const RenderState original = read_render_state(top);
  const RenderState copy = read_render_state(frame.merged / "top.exr");
  ASSERT_EQ(original.film.pixels().size(), copy.film.pixels().size());
  EXPECT_EQ(std::memcmp(original.film.pixels().data(), copy.film.pixels().data(),
                        original.film.pixels().size_bytes()),
            0);
}

TEST(AppMerge, OverlappingPartsAreRefusedNamingBoth) {
  const Frame frame("merge_overlap", kCornell);
  const std::string left = frame.crop("left.exr", 0, 0, 40, 48);
  const std::string right = frame.crop("right.exr", 32, 0, 64, 48);
  expect_refused(frame, frame.merge({left, right}, "frame.exr"),
                 {"right.exr: overlaps " + left, "x in [32, 40), y in [0, 48), samples [0, 8)"});
  const std::string early = frame.samples("early.exr", 0, 5);
  const std::string late = frame.samples("late.exr", 4, 8);
  expect_refused(frame, frame.merge({early, late}, "frame.exr"),
                 {"late.exr: overlaps " + early, "samples [4, 5)"});
  expect_refused(frame, frame.merge({left, right, left}, "frame.exr"), {"left.exr"});
}

TEST(AppMerge, GapsAreRefusedNamingWhatIsMissing) {
  const Frame frame("merge_gap", kCornell);
  // Three crops of a 2 x 2 grid: the union is not a rectangle.
  const std::vector<std::string> three = {frame.crop("c00.exr", 0, 0, 32, 24),
                                          frame.crop("c10.exr", 32, 0, 64, 24),
                                          frame.crop("c01.exr", 0, 24, 32, 48)};
  expect_refused(frame, frame.merge(three, "frame.exr"),
                 {"the parts leave a gap: x in [32, 64), y in [24, 48), samples [0, 8) are in no "
                  "part"});
  // A hole between two crops.
  expect_refused(
      frame,
      frame.merge({frame.crop("l.exr", 0, 0, 30, 48), frame.crop("r.exr", 34, 0, 64, 48)},
                  "frame.exr"),
      {"x in [30, 34), y in [0, 48), samples [0, 8) are in no part"});
  // Samples [0, 4) + [6, 8).
  expect_refused(
      frame,
      frame.merge({frame.samples("s0.exr", 0, 4), frame.samples("s1.exr", 6, 8)}, "frame.exr"),
      {"x in [0, 64), y in [0, 48), samples [4, 6) are in no part"});
}

TEST(AppMerge, PartsOfAnotherRenderAreRefusedNamingTheFile) {
  const Frame frame("merge_identity", kCornell, {"-s", "8", "--seed", "1"});
  const std::string left = frame.crop("left.exr", 0, 0, 32, 48);
  const auto right_with = [&](const std::string& name, const std::vector<std::string>& options) {
    std::vector<std::string> args = common_args(kCornell);
    args.insert(args.end(), options.begin(), options.end());
    const std::string path = (frame.dirs.out / name).string();
    args.insert(args.end(), {"--crop", "32", "0", "64", "48", "-f", path});
    EXPECT_EQ(run_prism(args).exit_code, 0) << name;
    return path;
  };
  expect_refused(frame,
                 frame.merge({left, right_with("seed.exr", {"-s", "8", "--seed", "2"})}, "f.exr"),
                 {"seed.exr: part of a different render: 'seed' is \"2\", " + left + " has \"1\""});
  expect_refused(
      frame,
      frame.merge(
          {left, right_with("direct.exr", {"-s", "8", "--seed", "1", "--integrator", "direct"})},
          "f.exr"),
      {"direct.exr: part of a different render: 'integrator'"});
  expect_refused(frame,
                 frame.merge({left, right_with("spp.exr", {"-s", "16", "--seed", "1"})}, "f.exr"),
                 {"spp.exr: part of a different render: 'spp' is 16, " + left + " has 8"});
  // Another scene at the same settings.
  const std::string tiny = frame.dirs.scene("tiny.dae", kTinyCollada);
  std::vector<std::string> args = frame.render_args;
  args[1] = tiny;
  const std::string other = (frame.dirs.out / "other.exr").string();
  args.insert(args.end(), {"--crop", "32", "0", "64", "48", "-f", other});
  ASSERT_EQ(run_prism(args).exit_code, 0);
  expect_refused(frame, frame.merge({left, other}, "f.exr"),
                 {"other.exr: part of a different render: 'scene'"});
}

TEST(AppMerge, PartStoppedEarlyIsRefused) {
  // Far more samples than 50 ms allow: the time limit stops the part after a few passes, and the
  // render still writes it (with prism:stoppedBy).
  const Frame frame("merge_stopped", kCornell);
  std::vector<std::string> args = common_args(kCornell);
  const std::string stopped = (frame.dirs.out / "stopped.exr").string();
  args.insert(args.end(), {"-s", "2048", "--pass-samples", "1", "--time-limit", "0.05", "--crop",
                           "0", "0", "32", "48", "-f", stopped});
  const ProgramResult rendered = run_prism(args);
  ASSERT_EQ(rendered.exit_code, 0) << rendered.err;
  ASSERT_NE(rendered.out.find("stopped by time limit"), std::string::npos) << rendered.out;
  expect_refused(
      frame, frame.merge({stopped}, "f.exr"),
      {"stopped.exr: the part is incomplete", "stopped by time limit", "samples [0, 2048)"});
}

TEST(AppMerge, FilesThatAreNotPartsAreRefused) {
  const Frame frame("merge_not_parts", kCornell);
  const std::string left = frame.crop("left.exr", 0, 0, 32, 48);
  const std::string right = frame.crop("right.exr", 32, 0, 64, 48);
  // A whole render's output is an image, not a part.
  expect_refused(frame, frame.merge({left, frame.render("full.exr")}, "f.exr"),
                 {"full.exr", "has no render state"});
  const std::string png = frame.render("right.png", {"--crop", "32", "0", "64", "48"});
  expect_refused(frame, frame.merge({left, png}, "f.exr"), {"right.png", "not an OpenEXR file"});
  expect_refused(frame, frame.merge({left, (frame.dirs.out / "missing.exr").string()}, "f.exr"),
                 {"missing.exr", "not a file"});

  // Damaged parts: truncated; bytes flipped in the state's pixels near the end of the file; the
  // render state in the header made invalid JSON.
  std::ifstream in(right, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const fs::path damaged = frame.dirs.out / "damaged.exr";
  write_text(damaged, bytes.substr(0, bytes.size() * 2 / 3));
  expect_refused(frame, frame.merge({left, damaged.string()}, "f.exr"),
                 {"damaged.exr", "cannot read the state"});
  for (const size_t from_end : {size_t(100), size_t(5000)}) {
    std::string flipped = bytes;
    for (size_t i = 0; i < 8; ++i) flipped[flipped.size() - from_end + i] ^= char(0x5a);
    write_text(damaged, flipped);
    expect_refused(frame, frame.merge({left, damaged.string()}, "f.exr"), {"damaged.exr"});
  }
  std::string header = bytes;
  const size_t at = header.find("\"identity\":{");
  ASSERT_NE(at, std::string::npos);
  header[at + std::strlen("\"identity\":")] = '[';
  write_text(damaged, header);
  expect_refused(frame, frame.merge({left, damaged.string()}, "f.exr"),
                 {"damaged.exr", "not valid JSON"});
}

TEST(AppMerge, OutputIsCheckedFirstAndAPartialResultMustBeAnExr) {
  const Frame frame("merge_output", kCornell);
  const std::string left = frame.crop("left.exr", 0, 0, 32, 48);
  // The output folder is checked before any part is read: exit 3 naming it, not the parts.
  const ProgramResult r = run_prism(
      {"merge", left, "missing_part.exr", "-f", (frame.dirs.root / "no/such/dir/f.exr").string()});
  expect_one_line_error(r, 3, {"no/such/dir"});
  expect_refused(frame, frame.merge({left}, "f.tga"), {"--output (-f)"});
  // Half the frame is a part: only an EXR holds it.
  expect_refused(frame, frame.merge({left}, "f.png"),
                 {"--output (-f)", "x in [0, 32), y in [0, 48), samples [0, 8)", "FILE.exr"});
  expect_one_line_error(run_prism({"merge", left}), 2, {"--output"});
  expect_one_line_error(run_prism({"merge", "-f", "x.exr"}), 2, {"parts is required"});
}

/// check_part_coverage on boxes alone, beyond what renders test: every tiling is accepted, and
/// the first overlap or a gap is named.
TEST(AppMerge, CoverageCheckIsExact) {
  const auto part = [](const std::string& file, int x0, int y0, int x1, int y1, uint32_t s0,
                       uint32_t s1) {
    return PartExtent{file, PixelRect{{x0, y0}, {x1, y1}}, SampleRange{s0, s1}};
  };
  // An L-shaped layer under a layer split the other way; a box not at the origin.
  const std::vector<PartExtent> tiling = {part("a", 0, 0, 10, 4, 0, 3), part("b", 0, 4, 3, 8, 0, 3),
                                          part("c", 3, 4, 10, 8, 0, 3), part("d", 0, 0, 5, 8, 3, 9),
                                          part("e", 5, 0, 10, 8, 3, 9)};
  const PartsCoverage box = check_part_coverage(tiling);
  EXPECT_EQ(box.window, (PixelRect{{0, 0}, {10, 8}}));
  EXPECT_EQ(box.samples, (SampleRange{0, 9}));
  const PartsCoverage inner = check_part_coverage({part("p", 7, 5, 9, 6, 2, 4)});
  EXPECT_EQ(inner.window, (PixelRect{{7, 5}, {9, 6}}));
  EXPECT_EQ(inner.samples, (SampleRange{2, 4}));

  const auto message = [](const std::vector<PartExtent>& parts) {
    try {
      check_part_coverage(parts);
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kInput);
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  std::vector<PartExtent> overlap = tiling;
  overlap.push_back(part("f", 9, 7, 12, 8, 8, 10));
  EXPECT_EQ(message(overlap),
            "f: overlaps e: x in [9, 10), y in [7, 8), samples [8, 9) are in both (every sample "
            "of a pixel must come from one part)");
  std::vector<PartExtent> gap = tiling;
  gap.erase(gap.begin() + 2);  // c
  EXPECT_EQ(message(gap),
            "the parts leave a gap: x in [3, 10), y in [4, 8), samples [0, 3) are in no part (the "
            "parts span x in [0, 10), y in [0, 8), samples [0, 9))");
  // Volumes that add up are not enough: the parts must also be disjoint.
  EXPECT_NE(message({part("a", 0, 0, 2, 1, 0, 1), part("b", 0, 0, 1, 1, 0, 1),
                     part("c", 2, 0, 3, 1, 0, 1)})
                .find("b: overlaps a"),
            std::string::npos);
}

}  // namespace
}  // namespace prism::test
