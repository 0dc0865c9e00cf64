// prism's colour pipeline against OpenColorIO's own command-line tools (opencolorio-tools) on
// the same image and config. `ociodisplay` is an interactive OpenGL viewer that cannot run
// headless; `ocioconvert --view` applies the same display/view transform to a file, so it
// stands in for it. Each test skips with a message when a tool is absent.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <optional>

#include "color/color_pipeline.h"
#include "color/image_output.h"
#include "core/error.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {
namespace fs = std::filesystem;

std::optional<fs::path> find_tool(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return std::nullopt;
  std::string dirs = path;
  size_t begin = 0;
  while (begin <= dirs.size()) {
    const size_t end = std::min(dirs.find(':', begin), dirs.size());
    const fs::path candidate = fs::path(dirs.substr(begin, end - begin)) / name;
    if (end > begin && ::access(candidate.c_str(), X_OK) == 0) return candidate;
    begin = end + 1;
  }
  return std::nullopt;
}

std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

struct ToolRun {
  int exit_code = -1;
  std::string output;
};

// Runs a shell command with stdout and stderr captured.
ToolRun run(const std::string& command) {
  ToolRun result;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return result;
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof(buffer), pipe)) > 0) result.output.append(buffer, n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

class ColorTools : public ::testing::Test {
 protected:
  void SetUp() override {
    if (const char* v = std::getenv("OCIO")) saved_ocio_ = v;
    unsetenv("OCIO");
    dir_ = test::make_temp_dir("color_tools");
    // The tools read the config from a file: the embedded text, as the program uses it.
    config_ = dir_ / "config.ocio";
    test::write_text(config_, bundled_color_config_text());
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
    if (saved_ocio_) setenv("OCIO", saved_ocio_->c_str(), 1);
  }

  // Greys from black to far above white and saturated colours, in linear Rec.709.
  static Image test_image() {
    Image image;
    image.width = 8;
    image.height = 3;
    image.channel_names = {"R", "G", "B"};
    const float greys[] = {0.0f, 0.001f, 0.01f, 0.05f, 0.18f, 0.5f, 1.0f, 16.0f};
    for (float g : greys) image.pixels.insert(image.pixels.end(), {g, g, g});
    const Rgb colors[] = {
        {0.9f, 0.05f, 0.02f}, {0.02f, 0.6f, 0.9f},  {0.1f, 0.8f, 0.05f},  {4.0f, 2.0f, 0.1f},
        {0.3f, 0.0f, 0.6f},   {0.0f, 0.0f, 1.0f},   {1.0f, 1.0f, 0.0f},   {0.7f, 0.4f, 0.3f},
        {8.0f, 0.5f, 0.5f},   {0.01f, 0.02f, 0.5f}, {0.25f, 0.25f, 0.2f}, {2.0f, 3.0f, 6.0f},
        {0.5f, 0.9f, 0.9f},   {0.0f, 0.3f, 0.0f},   {0.6f, 0.1f, 0.7f},   {0.05f, 0.05f, 0.3f}};
    for (const Rgb& c : colors) image.pixels.insert(image.pixels.end(), {c.x, c.y, c.z});
    return image;
  }

  // Writes the image as a float EXR for the tool to read.
  fs::path write_input(const Image& image) {
    ColorOptions options;
    options.ocio_config = config_.string();
    fs::path path = dir_ / "input.exr";
    write_exr(path, image, {}, ColorPipeline(options), ExrOptions{"float", "none"});
    return path;
  }

  fs::path dir_;
  fs::path config_;
  std::optional<std::string> saved_ocio_;
};

TEST_F(ColorTools, OciocheckValidatesTheBundledConfig) {
  const auto tool = find_tool("ociocheck");
  if (!tool) GTEST_SKIP() << "ociocheck (opencolorio-tools) not installed: skipping";
  for (const fs::path& config :
       {fs::path(PRISM_SOURCE_DIR) / "color" / "ocio" / "config.ocio", config_}) {
    const ToolRun r = run(quote(tool->string()) + " --iconfig " + quote(config.string()));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("** Validation **\npassed"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("ERROR"), std::string::npos) << r.output;
  }
}

TEST_F(ColorTools, EveryViewMatchesOcioconvert) {
  const auto tool = find_tool("ocioconvert");
  if (!tool) GTEST_SKIP() << "ocioconvert (opencolorio-tools) not installed: skipping";
  const Image image = test_image();
  const fs::path input = write_input(image);
  for (const char* view : {"Standard", "ACES 1.0 - SDR Video", "Raw"}) {
    SCOPED_TRACE(view);
    const fs::path output = dir_ / "view.exr";
    const ToolRun r = run("OCIO=" + quote(config_.string()) + " " + quote(tool->string()) +
                          " --view " + quote(input.string()) + " 'Linear Rec.709 (sRGB)' " +
                          quote(output.string()) + " 'sRGB - Display' " + quote(view));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const ImageFileContents tool_image = read_image_file(output);
    ColorOptions options;
    options.ocio_config = config_.string();
    options.view = view;
    const Image ours = ColorPipeline(options).working_to_display(image);
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) {
        for (int c = 0; c < 3; ++c) {
          // prism clips display values to [0, 1]; the tool writes them as they come.
          const float want = std::clamp(
              tool_image.image.at(x, y, tool_image.channel(std::string(1, "RGB"[c]))), 0.0f, 1.0f);
          EXPECT_NEAR(ours.at(x, y, c), want, 1e-5f) << "pixel " << x << "," << y << " ch " << c;
        }
      }
    }
  }
}

TEST_F(ColorTools, OutputSpacesMatchOcioconvert) {
  const auto tool = find_tool("ocioconvert");
  if (!tool) GTEST_SKIP() << "ocioconvert (opencolorio-tools) not installed: skipping";
  const Image image = test_image();
  const fs::path input = write_input(image);
  for (const char* space : {"ACEScg", "ACES2065-1", "Linear Rec.2020", "ACEScct"}) {
    SCOPED_TRACE(space);
    const fs::path output = dir_ / "converted.exr";
    const ToolRun r = run("OCIO=" + quote(config_.string()) + " " + quote(tool->string()) + " " +
                          quote(input.string()) + " 'Linear Rec.709 (sRGB)' " +
                          quote(output.string()) + " " + quote(space));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const ImageFileContents tool_image = read_image_file(output);
    ColorOptions options;
    options.ocio_config = config_.string();
    options.output_space = space;
    Image ours = image;
    ColorPipeline(options).working_to_output(ours);
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) {
        for (int c = 0; c < 3; ++c) {
          const float want =
              tool_image.image.at(x, y, tool_image.channel(std::string(1, "RGB"[c])));
          EXPECT_NEAR(ours.at(x, y, c), want, 1e-5f * std::max(1.0f, std::abs(want)))
              << "pixel " << x << "," << y << " ch " << c;
        }
      }
    }
  }
}

}  // namespace
}  // namespace prism
