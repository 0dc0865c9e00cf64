// Third-party OCIO configs installed on this machine (Blender's, an ACES studio config, ...)
// work through $OCIO without code changes: prism renders, writes the EXR in the config's
// scene_linear space and a PNG through its default display and view. The test looks for
// configs where Debian installs them (blender-data: /usr/share/blender/*/datafiles/
// colormanagement/config.ocio; /usr/share/ocio, /usr/share/color/opencolorio) and in
// $PRISM_EXTRA_OCIO_CONFIGS (colon-separated config.ocio paths, e.g. an ACES studio config
// unpacked by hand). It skips with a message when none is installed.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "color/color_pipeline.h"
#include "color/image_output.h"
#include "tests/support/app_test_helpers.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

/// Every config.ocio below `dir`, at most `depth` folders down.
void find_configs(const fs::path& dir, int depth, std::set<fs::path>& found) {
  std::error_code ec;
  if (depth < 0 || !fs::is_directory(dir, ec)) return;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.is_directory(ec)) {
      find_configs(entry.path(), depth - 1, found);
    } else if (entry.path().extension() == ".ocio") {
      found.insert(fs::canonical(entry.path(), ec));
    }
  }
}

std::vector<fs::path> installed_configs() {
  std::set<fs::path> found;
  find_configs("/usr/share/blender", 4, found);
  find_configs("/usr/share/ocio", 3, found);
  find_configs("/usr/share/color/opencolorio", 3, found);
  if (const char* extra = std::getenv("PRISM_EXTRA_OCIO_CONFIGS")) {
    std::stringstream list(extra);
    for (std::string item; std::getline(list, item, ':');) {
      if (!item.empty()) found.insert(fs::path(item));
    }
  }
  return {found.begin(), found.end()};
}

/// Sets $OCIO for one test and puts the caller's value back afterwards.
class ScopedOcio {
 public:
  explicit ScopedOcio(const std::string& value) {
    if (const char* v = std::getenv("OCIO")) saved_ = v;
    setenv("OCIO", value.c_str(), 1);
  }
  ~ScopedOcio() {
    if (saved_) {
      setenv("OCIO", saved_->c_str(), 1);
    } else {
      unsetenv("OCIO");
    }
  }
  ScopedOcio(const ScopedOcio&) = delete;
  ScopedOcio& operator=(const ScopedOcio&) = delete;

 private:
  std::optional<std::string> saved_;
};

TEST(ColorInstalledConfigs, RenderThroughOcioWithoutCodeChanges) {
  const std::vector<fs::path> configs = installed_configs();
  if (configs.empty()) {
    GTEST_SKIP() << "no third-party OCIO config installed (apt-get install blender-data, or set "
                    "PRISM_EXTRA_OCIO_CONFIGS=/path/to/config.ocio): skipping";
  }
  for (const fs::path& config : configs) {
    SCOPED_TRACE(config.string());
    const ScopedOcio ocio(config.string());
    const ColorPipeline pipeline({});  // what prism will choose from this config
    test::TestDirs dirs("installed_ocio");
    const std::string scene = dirs.scene("tiny.dae", test::kTinyCollada);
    const fs::path exr = dirs.out / "tiny.exr";
    const test::ProgramResult r =
        test::run_prism({"render", scene, "--integrator", "direct", "--spp", "4", "--resolution",
                         "32", "24", "--quiet", "--output", exr.string(), "--png"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_TRUE(fs::exists(exr));
    ASSERT_TRUE(fs::exists(dirs.out / "tiny.png"));

    const ImageFileContents written = read_image_file(exr);
    EXPECT_EQ(written.attribute("prism:ocioConfigSource"), config.string());
    EXPECT_EQ(written.attribute("prism:colorSpace"), pipeline.output_space());
    EXPECT_EQ(written.attribute("prism:workingSpace"), pipeline.working_space());
    // The scene is lit: some pixel is bright, and none is NaN or infinite.
    float brightest = 0.0f;
    for (float value : written.image.pixels) {
      ASSERT_TRUE(std::isfinite(value));
      brightest = std::max(brightest, value);
    }
    EXPECT_GT(brightest, 0.0f);
    const ImageFileContents display = read_image_file(dirs.out / "tiny.png");
    EXPECT_EQ(display.format, "png");
  }
}

}  // namespace
}  // namespace prism
