// Environment maps (-e) end to end: the file is read through color/, converted to the working
// space, lights a diffuse sphere as a white furnace would, and bad files are one-line errors.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "color/color_pipeline.h"
#include "color/image_output.h"
#include "core/error.h"
#include "tests/support/app_test_helpers.h"
#include "tests/support/test_support.h"

namespace prism::test {
namespace {

namespace fs = std::filesystem;

// Exact in half precision, and not grey, so a mixed-up channel or a missed conversion shows.
const Rgb kRadiance(0.5f, 1.0f, 2.0f);
const Rgb kAlbedo(0.8f, 0.5f, 0.25f);

/// A diffuse sphere of radius 1 at the origin seen from +z: at 32 x 24 it covers the middle
/// (about 17 pixels across) and leaves the corners and sides to the background.
const std::string kSphereScene = R"({
  "camera": {"position": [0, 0, 4], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 40},
  "materials": [{"name": "grey", "type": "diffuse", "reflectance": [0.8, 0.5, 0.25]}],
  "spheres": [{"center": [0, 0, 0], "radius": 1, "material": "grey"}]
})";

/// A width x height RGB image whose pixel (x, y) is color(x, y).
Image rgb_image(int width, int height, const std::function<Rgb(int, int)>& color) {
  Image image;
  image.width = width;
  image.height = height;
  image.channel_names = {"R", "G", "B"};
  image.pixels.resize(size_t(width) * height * 3);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const Rgb c = color(x, y);
      for (int k = 0; k < 3; ++k) image.at(x, y, k) = c[k];
    }
  }
  return image;
}

/// Writes `image` (in the bundled config's working space) as a half EXR in `output_space`.
void write_env(const fs::path& path, const Image& image, const std::string& output_space = "") {
  ColorOptions options = bundled_config();
  options.output_space = output_space;
  const ColorPipeline pipeline(options);
  write_exr(path, image, {}, pipeline, ExrOptions{"half", "zip"});
}

class AppEnvironment : public testing::Test {
 protected:
  TestDirs dirs_{"app_environment"};

  std::string scene() const { return dirs_.scene("sphere.json", kSphereScene); }

  /// Renders the sphere scene at 32 x 24, 16 spp with the path integrator and -e `env`.
  ProgramResult render(const fs::path& env, const std::string& output = "out.exr") const {
    return run_prism({"render", scene(), "-e", env.string(), "--integrator", "path", "-r", "32",
                      "24", "-s", "16", "--seed", "7", "-q", "-f", (dirs_.out / output).string()});
  }
  ImageFileContents rendered(const std::string& output = "out.exr") const {
    return read_image_file(dirs_.out / output);
  }
  void expect_nothing_written() const {
    EXPECT_TRUE(dir_entries(dirs_.out).empty()) << "output folder not empty";
  }
};

Rgb pixel(const ImageFileContents& file, int x, int y, const std::string& layer = "") {
  const int r = file.channel(layer + "R"), g = file.channel(layer + "G"),
            b = file.channel(layer + "B");
  EXPECT_TRUE(r >= 0 && g >= 0 && b >= 0) << "no channels " << layer << "R/G/B";
  if (r < 0 || g < 0 || b < 0) return Rgb(0.0f);
  return Rgb(file.image.at(x, y, r), file.image.at(x, y, g), file.image.at(x, y, b));
}

/// |a - b| <= tolerance * |b| per channel.
bool near_relative(const Rgb& a, const Rgb& b, float tolerance) {
  for (int k = 0; k < 3; ++k) {
    if (!(std::abs(a[k] - b[k]) <= tolerance * std::abs(b[k]))) return false;
  }
  return true;
}

std::string str(const Rgb& c) {
  return "(" + std::to_string(c.x) + ", " + std::to_string(c.y) + ", " + std::to_string(c.z) + ")";
}

// Half precision holds 11 significant bits: a relative error of at most 2^-11.
constexpr float kHalfTolerance = 1.0f / 1024.0f;

TEST_F(AppEnvironment, UniformMapIsAWhiteFurnaceForADiffuseSphere) {
  const fs::path env = dirs_.in / "uniform.exr";
  write_env(env, rgb_image(16, 8, [](int, int) { return kRadiance; }));
  const ProgramResult r = render(env);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const ImageFileContents out = rendered();
  EXPECT_EQ(out.attribute("prism:environment"), env.string());
  EXPECT_EQ(out.attribute("prism:environmentColorSpace"), "Linear Rec.709 (sRGB)");

  // The albedo AOV tells pixels that only see the background (0) from pixels whose every sample
  // hit the sphere (the albedo); the edge pixels in between are left out.
  int background = 0, sphere = 0;
  Rgb sum(0.0f), variance_sum(0.0f);
  for (int y = 0; y < out.image.height; ++y) {
    for (int x = 0; x < out.image.width; ++x) {
      const Rgb albedo = pixel(out, x, y, "albedo."), c = pixel(out, x, y);
      if (albedo == Rgb(0.0f)) {
        ++background;
        EXPECT_TRUE(near_relative(c, kRadiance, kHalfTolerance))
            << "background pixel (" << x << ", " << y << ") = " << str(c);
      } else if (near_relative(albedo, kAlbedo, kHalfTolerance)) {
        ++sphere;
        sum += c;
        variance_sum += pixel(out, x, y, "variance.");  // variance of each pixel's mean
      }
    }
  }
  ASSERT_GE(background, 100);
  ASSERT_GE(sphere, 100);
  // A convex diffuse surface under uniform radiance L reflects exactly albedo * L. Tolerance:
  // five standard errors of the mean over the pixels, plus half-precision rounding.
  const Rgb mean = sum / float(sphere), expected = kAlbedo * kRadiance;
  for (int k = 0; k < 3; ++k) {
    const float sigma = std::sqrt(variance_sum[k]) / float(sphere);
    EXPECT_NEAR(mean[k], expected[k], 5.0f * sigma + expected[k] * kHalfTolerance)
        << "channel " << k << ", " << sphere << " sphere pixels";
  }
}

TEST_F(AppEnvironment, FileColourSpaceIsConvertedToTheWorkingSpace) {
  // The file holds ACEScg numbers (its prism:colorSpace says so); rays must still see kRadiance
  // in the working space (linear Rec.709).
  const fs::path env = dirs_.in / "acescg.exr";
  write_env(env, rgb_image(8, 4, [](int, int) { return kRadiance; }), "ACEScg");
  const ImageFileContents file = read_image_file(env);
  ASSERT_EQ(file.attribute("prism:colorSpace"), "ACEScg");
  ASSERT_FALSE(near_relative(pixel(file, 0, 0), kRadiance, 0.05f))
      << "the ACEScg values should differ from the Rec.709 ones";

  const ProgramResult r = render(env);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const ImageFileContents out = rendered();
  EXPECT_EQ(out.attribute("prism:environmentColorSpace"), "ACEScg");
  EXPECT_TRUE(near_relative(pixel(out, 0, 0), kRadiance, 4.0f * kHalfTolerance))
      << str(pixel(out, 0, 0));
}

TEST_F(AppEnvironment, UnknownFileColourSpaceFallsBackToSceneLinearWithAWarning) {
  // Written with a config whose ACEScg space has another name: the bundled config does not know
  // it, so the values are read as they are, as scene_linear.
  std::string config = bundled_color_config_text();
  const std::string from = "name: ACEScg", to = "name: Studio AP1";
  ASSERT_NE(config.find(from), std::string::npos);
  config.replace(config.find(from), from.size(), to);
  write_text(dirs_.in / "studio.ocio", config);
  ColorOptions studio = bundled_config();
  studio.ocio_config = (dirs_.in / "studio.ocio").string();
  studio.output_space = "Studio AP1";
  const fs::path env = dirs_.in / "studio.exr";
  write_exr(env, rgb_image(8, 4, [](int, int) { return kRadiance; }), {}, ColorPipeline(studio),
            ExrOptions{"half", "zip"});
  const Rgb stored = pixel(read_image_file(env), 0, 0);

  const ProgramResult r = render(env);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("prism: warning: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'Studio AP1'"), std::string::npos) << r.err;
  const ImageFileContents out = rendered();
  EXPECT_EQ(out.attribute("prism:environmentColorSpace"), "Linear Rec.709 (sRGB)");
  EXPECT_TRUE(near_relative(pixel(out, 0, 0), stored, kHalfTolerance))
      << str(pixel(out, 0, 0)) << " vs stored " << str(stored);
}

TEST_F(AppEnvironment, RowZeroIsThePoleAlongTheCameraUp) {
  // Upper hemisphere (about the camera's up, +y) red, lower blue: the image's top corners look
  // 20 degrees above the horizon, its bottom corners 20 degrees below.
  const Rgb sky(2.0f, 0.0f, 0.0f), ground(0.0f, 0.0f, 1.0f);
  const fs::path env = dirs_.in / "sky.exr";
  write_env(env, rgb_image(16, 8, [&](int, int y) { return y < 4 ? sky : ground; }));
  const ProgramResult r = render(env);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const ImageFileContents out = rendered();
  for (int x : {0, 31}) {
    EXPECT_EQ(pixel(out, x, 0), sky) << "top row, x = " << x;
    EXPECT_EQ(pixel(out, x, 23), ground) << "bottom row, x = " << x;
  }
}

TEST_F(AppEnvironment, MapThatIsNotTwoToOneRendersWithAWarning) {
  const fs::path env = dirs_.in / "square.exr";
  write_env(env, rgb_image(8, 8, [](int, int) { return kRadiance; }));
  const ProgramResult r = render(env);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("prism: warning: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("8 x 8, not 2:1"), std::string::npos) << r.err;
  EXPECT_TRUE(near_relative(pixel(rendered(), 0, 0), kRadiance, kHalfTolerance));
}

TEST_F(AppEnvironment, BadFilesAreOneLineErrorsNamingTheFile) {
  struct Case {
    std::string name;
    std::function<void(const fs::path&)> make;  ///< creates the file (or not)
    std::vector<std::string> mentions;
  };
  const auto pfm_with = [](float bad) {
    return [bad](const fs::path& path) {
      std::vector<float> values(4 * 2 * 3, 1.0f);
      values[(size_t(1) * 4 + 2) * 3 + 1] = bad;  // pixel (2, 1), G
      write_pfm(path, 4, 2, values);
    };
  };
  const std::vector<Case> cases = {
      {"missing.exr", [](const fs::path&) {}, {"does not exist"}},
      {"folder.exr", [](const fs::path& p) { fs::create_directories(p); }, {"folder"}},
      {"text.exr", [](const fs::path& p) { write_text(p, "not an image\n"); }, {"cannot read"}},
      // A grey PGM: one channel, no R, G, B.
      {"grey.pgm",
       [](const fs::path& p) {
         std::ofstream(p, std::ios::binary) << "P5\n4 2\n255\n" << std::string(8, char(100));
       },
       {"no R, G, B"}},
      {"negative.exr",
       [](const fs::path& p) {
         write_env(p, rgb_image(4, 2, [](int x, int y) {
                     return x == 3 && y == 1 ? Rgb(1.0f, -0.5f, 1.0f) : Rgb(1.0f);
                   }));
       },
       {"pixel (3, 1)", "G = -0.5"}},
      {"nan.pfm", pfm_with(std::numeric_limits<float>::quiet_NaN()), {"pixel (2, 1)", "G = nan"}},
      {"inf.pfm", pfm_with(std::numeric_limits<float>::infinity()), {"pixel (2, 1)", "G = inf"}},
      {"empty.pfm", [](const fs::path& p) { write_pfm(p, 0, 0, {}); }, {}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path env = dirs_.in / c.name;
    c.make(env);
    std::vector<std::string> mentions = c.mentions;
    mentions.push_back(env.string());
    mentions.push_back("environment map (-e)");
    expect_one_line_error(render(env), 2, mentions);
    expect_nothing_written();
  }
}

}  // namespace
}  // namespace prism::test
