// `prism convert`: display-referred images of a rendered EXR through OCIO views, and its errors.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "color/image_output.h"
#include "tests/support/app_test_helpers.h"
#include "tests/support/test_support.h"

namespace prism::test {
namespace {

const std::string kAcesView = "ACES 1.0 - SDR Video";

/// The tiny scene with a saturated red material: grey would look the same in every RGB space.
std::string red_scene() {
  return replaced(kTinyCollada, "<color sid=\"diffuse\">0.6 0.6 0.6 1</color>",
                  "<color sid=\"diffuse\">0.8 0.15 0.05 1</color>");
}

/// Renders the tiny red scene at 16 x 12, 1 spp, into dirs.in/`name` (plus the PNG beside it that
/// render writes with --png) with extra render flags; fails the test on a non-zero exit.
std::filesystem::path render_exr(const TestDirs& dirs, const std::string& name,
                                 const std::vector<std::string>& extra = {}) {
  const std::string scene = dirs.scene("tiny.dae", red_scene());
  const auto exr = dirs.in / name;
  std::vector<std::string> args = {"render", scene,        "--resolution", "16", "12",
                                   "--spp",  "1",          "--seed",       "3",  "--quiet",
                                   "-f",     exr.string(), "--png"};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto r = run_prism(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return exr;
}

ProgramResult convert(const std::vector<std::string>& args) {
  std::vector<std::string> all = {"convert"};
  all.insert(all.end(), args.begin(), args.end());
  return run_prism(all);
}

/// Largest difference of two 8-bit images in code values (255 when their shapes differ).
int max_code_difference(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height || a.channels() != b.channels()) return 255;
  float worst = 0.0f;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    worst = std::max(worst, std::abs(a.pixels[i] - b.pixels[i]));
  }
  return int(std::lround(worst * 255.0f));
}

void expect_png_16x12(const ImageFileContents& png) {
  EXPECT_EQ(png.format, "png");
  EXPECT_EQ(png.image.width, 16);
  EXPECT_EQ(png.image.height, 12);
  EXPECT_EQ(png.image.channels(), 3);
}

TEST(AppConvert, StandardAndAcesViewsWriteDifferentPngs) {
  const TestDirs dirs("app_convert_views");
  const auto exr = render_exr(dirs, "tiny.exr");
  const auto standard = dirs.out / "standard.png", aces = dirs.out / "aces.png";
  auto r = convert({exr.string(), standard.string(), "--view", "Standard"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(standard.string()), std::string::npos) << r.out;
  r = convert({exr.string(), aces.string(), "--view", kAcesView});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Only the two files: no temporary file left behind.
  EXPECT_EQ(dir_entries(dirs.out), (std::vector<std::string>{"aces.png", "standard.png"}));

  const ImageFileContents a = read_image_file(standard), b = read_image_file(aces);
  expect_png_16x12(a);
  expect_png_16x12(b);
  EXPECT_GT(max_code_difference(a.image, b.image), 5) << "the ACES view changed nothing";
  EXPECT_EQ(a.attribute("prism:view"), "Standard");
  EXPECT_EQ(b.attribute("prism:view"), kAcesView);
  EXPECT_EQ(b.attribute("prism:seed"), "3");  // the render's provenance is carried over

  // The Standard view of the EXR is the PNG the render wrote from its float image, up to the
  // EXR's half precision (one code value).
  const ImageFileContents rendered = read_image_file(dirs.in / "tiny.png");
  EXPECT_LE(max_code_difference(a.image, rendered.image), 1);
}

TEST(AppConvert, AcesViewMatchesARenderThroughTheSameView) {
  const TestDirs dirs("app_convert_aces");
  const auto exr = render_exr(dirs, "tiny.exr", {"--view", kAcesView, "--exposure", "1"});
  const auto png = dirs.out / "aces.png";
  const auto r = convert({exr.string(), png.string(), "--view", kAcesView, "--exposure", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_LE(
      max_code_difference(read_image_file(png).image, read_image_file(dirs.in / "tiny.png").image),
      1);
}

TEST(AppConvert, InputSpaceComesFromTheExrAttribute) {
  const TestDirs dirs("app_convert_space");
  const auto rec709 = render_exr(dirs, "rec709.exr");
  const auto acescg = render_exr(dirs, "acescg.exr", {"--output-space", "ACEScg"});
  ASSERT_EQ(read_image_file(acescg).attribute("prism:colorSpace"), "ACEScg");
  const auto from_rec709 = dirs.out / "a.png", from_acescg = dirs.out / "b.png",
             forced = dirs.out / "c.png";
  ASSERT_EQ(convert({rec709.string(), from_rec709.string()}).exit_code, 0);
  ASSERT_EQ(convert({acescg.string(), from_acescg.string()}).exit_code, 0);
  // Reading ACEScg values as if they were the working space must change the picture.
  ASSERT_EQ(convert({acescg.string(), forced.string(), "--input-space", "lin_rec709"}).exit_code,
            0);
  const Image a = read_image_file(from_rec709).image, b = read_image_file(from_acescg).image,
              c = read_image_file(forced).image;
  EXPECT_LE(max_code_difference(a, b), 1);
  EXPECT_GT(max_code_difference(a, c), 1);

  const auto r = convert({acescg.string(), (dirs.out / "d.png").string(), "--input-space", "nope"});
  expect_one_line_error(r, 2, {"unknown colour space 'nope'", "--input-space", "ACEScg"});
}

TEST(AppConvert, BadViewListsTheViewsAndWritesNothing) {
  const TestDirs dirs("app_convert_badview");
  const auto exr = render_exr(dirs, "tiny.exr");
  const auto r = convert({exr.string(), (dirs.out / "x.png").string(), "--view", "Filmic"});
  expect_one_line_error(r, 2, {"unknown view 'Filmic'", "Standard", kAcesView, "Raw"});
  EXPECT_TRUE(dir_entries(dirs.out).empty());
}

TEST(AppConvert, MissingOrNonExrInputIsExit2NamingTheFile) {
  const TestDirs dirs("app_convert_input");
  const auto missing = dirs.in / "missing.exr";
  auto r = convert({missing.string(), (dirs.out / "x.png").string()});
  expect_one_line_error(r, 2, {missing.string(), "does not exist"});

  const auto exr = render_exr(dirs, "tiny.exr");  // also writes tiny.png
  const auto png = dirs.in / "tiny.png";
  r = convert({png.string(), (dirs.out / "x.png").string()});
  expect_one_line_error(r, 2, {png.string(), "not an OpenEXR file"});

  r = convert({exr.string(), (dirs.out / "x.exr").string()});
  expect_one_line_error(r, 2, {"x.exr", ".png"});
  EXPECT_TRUE(dir_entries(dirs.out).empty());
}

TEST(AppConvert, MissingOutputFolderIsExit3AndWritesNothing) {
  const TestDirs dirs("app_convert_output");
  const auto exr = render_exr(dirs, "tiny.exr");
  const auto target = dirs.out / "no_such_folder" / "x.png";
  const auto r = convert({exr.string(), target.string()});
  expect_one_line_error(r, 3, {target.string(), "does not exist"});
  EXPECT_FALSE(std::filesystem::exists(target.parent_path()));
  EXPECT_TRUE(dir_entries(dirs.out).empty());
}

}  // namespace
}  // namespace prism::test
