// The environment map loader (core/app/environment_map): the file's values and colour space,
// and the warnings it gives. The -e option end to end is in app_environment_test.cpp.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "color/color_pipeline.h"
#include "core/app/environment_map.h"
#include "tests/support/app_test_helpers.h"

namespace prism::test {
namespace {

namespace fs = std::filesystem;

// The values the test files hold (exact in RGBE and in half precision).
const Rgb kRadiance(0.5f, 1.0f, 2.0f);

TEST(AppEnvironmentMap, RadianceHdrIsReadAsSceneLinearWithoutWarning) {
  // OpenImageIO labels .hdr (and EXR) files "linear", which names no primaries: scene_linear.
  const TestDirs dirs("environment_loader_hdr");
  const fs::path path = dirs.in / "sky.hdr";
  {
    // Flat RGBE scanlines (width < 8 is never run-length encoded): mantissas 32, 64, 128 with
    // exponent byte 130 decode to 0.5, 1, 2.
    std::ofstream out(path, std::ios::binary);
    out << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n";
    for (int i = 0; i < 8; ++i) out << char(32) << char(64) << char(128) << char(130);
  }
  const ColorPipeline pipeline(bundled_config());
  const EnvironmentMap map = load_environment_map(path, pipeline);
  EXPECT_EQ(map.color_space, "Linear Rec.709 (sRGB)");
  EXPECT_EQ(map.space_rule, "scene_linear");
  EXPECT_TRUE(map.warnings.empty()) << map.warnings.front();
  ASSERT_EQ(map.image.width, 4);
  ASSERT_EQ(map.image.height, 2);
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 4; ++x) {
      EXPECT_EQ(Rgb(map.image.at(x, y, 0), map.image.at(x, y, 1), map.image.at(x, y, 2)),
                kRadiance);
    }
  }
}

TEST(AppEnvironmentMap, PfmKeepsItsValuesAndWarnsAboutItsEncodingLabel) {
  const TestDirs dirs("environment_loader_pfm");
  std::vector<float> values(4 * 2 * 3);
  for (size_t i = 0; i < values.size(); ++i) values[i] = 0.25f * float(i);
  write_pfm(dirs.in / "ramp.pfm", 4, 2, values);
  const ColorPipeline pipeline(bundled_config());
  const EnvironmentMap map = load_environment_map(dirs.in / "ramp.pfm", pipeline);
  EXPECT_EQ(map.color_space, "Linear Rec.709 (sRGB)");
  ASSERT_EQ(map.image.width, 4);
  ASSERT_EQ(map.image.height, 2);
  ASSERT_EQ(map.image.channel_names, (std::vector<std::string>{"R", "G", "B"}));
  EXPECT_EQ(std::vector<float>(map.image.pixels.begin(), map.image.pixels.end()),
            values);  // top row first, no conversion
  // OpenImageIO labels PNM files "Rec709" (an encoded space the config does not have): the
  // values are used as they are, with a warning; the map is 2:1, so there is only that one.
  ASSERT_EQ(map.warnings.size(), 1u);
  EXPECT_NE(map.warnings[0].find("oiio:ColorSpace 'Rec709'"), std::string::npos) << map.warnings[0];
}

}  // namespace
}  // namespace prism::test
