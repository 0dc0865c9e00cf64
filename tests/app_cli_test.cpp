// The prism program's commands, run as a user runs them: exit codes, files written, output.

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "color/image_output.h"
#include "scenes/scene_loader.h"
#include "tests/support/app_test_helpers.h"
#include "tests/support/test_support.h"

namespace prism::test {
namespace {

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

size_t line_count(const std::string& text) {
  return size_t(std::count(text.begin(), text.end(), '\n'));
}

TEST(AppCli, RenderWritesValidExrWithProvenance) {
  const TestDirs dirs("app_render");
  const std::string scene = dirs.scene("tiny.dae", kTinyCollada);
  const auto out = dirs.out / "tiny.exr";
  const auto r = run_prism({"render", scene, "--resolution", "32", "24", "--spp", "1", "--seed",
                            "7", "-f", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(dir_entries(dirs.out), std::vector<std::string>{"tiny.exr"});  // no temp file left
  EXPECT_EQ(line_count(r.out), 1u) << r.out;
  EXPECT_NE(r.out.find(out.string()), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("bvh"), std::string::npos) << r.out;

  const ImageFileContents exr = read_image_file(out);
  EXPECT_EQ(exr.format, "openexr");
  EXPECT_EQ(exr.image.width, 32);
  EXPECT_EQ(exr.image.height, 24);
  for (const char* channel : {"R", "G", "B"}) {
    EXPECT_GE(exr.channel(channel), 0) << "no channel " << channel;
  }
  EXPECT_EQ(exr.image.count_non_finite(), 0u);
  EXPECT_EQ(exr.attribute("prism:accelerator"), "bvh");
  EXPECT_EQ(exr.attribute("prism:spp"), "1");
  EXPECT_EQ(exr.attribute("prism:seed"), "7");
  EXPECT_EQ(exr.attribute("prism:resolution"), "32x24");
  EXPECT_EQ(exr.attribute("prism:non_finite_samples"), "0");
  EXPECT_EQ(exr.attribute("prism:scene"), scene);
  for (const char* name : {"prism:version", "prism:integrator", "prism:sampler", "prism:build_ms",
                           "prism:render_ms", "prism:command_line"}) {
    EXPECT_NE(exr.attribute(name), "") << "missing " << name;
  }
}

TEST(AppCli, HomeworkStyleArgumentsRenderWithoutTheRenderWord) {
  const TestDirs dirs("app_homework");
  const std::string scene = dirs.scene("tiny.dae", kTinyCollada);
  const auto png = dirs.out / "tiny.png";
  const auto r = run_prism(
      {"-t", "2", "-s", "1", "-l", "1", "-m", "2", "-r", "32", "24", "-f", png.string(), scene});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // A PNG output alone writes only the PNG.
  EXPECT_EQ(dir_entries(dirs.out), std::vector<std::string>{"tiny.png"});
  EXPECT_EQ(read_bytes(png).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
}

TEST(AppCli, PngAndExrFlagsAddTheOtherFormatBeside) {
  const TestDirs dirs("app_formats");
  const std::string scene = dirs.scene("tiny.dae", kTinyCollada);
  const std::vector<std::string> base = {"render", scene, "-r", "32", "24", "-s", "1", "--quiet"};
  auto args = base;
  // A parameter of an accelerator not in use is ignored with a warning, not an error.
  args.insert(args.end(),
              {"-f", (dirs.out / "a.exr").string(), "--png", "--set", "embree.robust=true"});
  auto r = run_prism(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: --set embree.robust ignored"), std::string::npos) << r.err;
  args = base;
  args.insert(args.end(), {"-f", (dirs.out / "b.png").string(), "--exr"});
  r = run_prism(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(dir_entries(dirs.out), (std::vector<std::string>{"a.exr", "a.png", "b.exr", "b.png"}));
  EXPECT_EQ(read_image_file(dirs.out / "b.exr").format, "openexr");
}

TEST(AppCli, ThreadCountDoesNotChangePixels) {
  const TestDirs dirs("app_threads");
  const std::string scene = dirs.scene("tiny.dae", kTinyCollada);
  std::vector<std::vector<float>> pixels;
  for (const char* threads : {"1", "2"}) {
    const auto out = dirs.out / (std::string("t") + threads + ".exr");
    const auto r = run_prism({"render", scene, "-r", "40", "30", "-s", "3", "--seed", "11",
                              "--exr-type", "float", "-t", threads, "-q", "-f", out.string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    pixels.push_back(read_image_file(out).image.pixels);
  }
  ASSERT_FALSE(pixels[0].empty());
  EXPECT_TRUE(pixels[0] == pixels[1]) << "pixels differ between 1 and 2 threads";
  EXPECT_TRUE(std::any_of(pixels[0].begin(), pixels[0].end(), [](float v) { return v > 0.0f; }))
      << "the image is black: the comparison would prove nothing";
}

/// R, G, B, AOV and variance values of an EXR prism wrote (written as float: exact).
std::vector<float> exr_pixels(const std::filesystem::path& path) {
  return read_image_file(path).image.pixels;
}

TEST(AppCli, IntegratorFlagsAreAliasesOfItsParameters) {
  const TestDirs dirs("app_aliases");
  const std::string scene = default_scene_path().string();
  const std::vector<std::string> base = {"render", scene, "-r", "32",         "24",
                                         "-s",     "2",   "-q", "--exr-type", "float",
                                         "--seed", "5",   "-t", "2",          "--integrator"};
  const auto render = [&](const std::string& integrator, const std::string& output,
                          std::vector<std::string> extra) {
    std::vector<std::string> args = base;
    args.push_back(integrator);
    args.insert(args.end(), extra.begin(), extra.end());
    args.insert(args.end(), {"-f", (dirs.out / output).string()});
    return run_prism(args);
  };
  // -m 3 is path.max_depth=3, bit for bit; both at once are fine when they agree.
  for (const auto& [output, extra] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {"flag.exr", {"-m", "3"}},
           {"set.exr", {"--set", "path.max_depth=3"}},
           {"both.exr", {"-m", "3", "--set", "path.max_depth=3"}},
           {"other.exr", {"-m", "1"}}}) {
    const ProgramResult r = render("path", output, extra);
    ASSERT_EQ(r.exit_code, 0) << output << ": " << r.err;
    EXPECT_TRUE(r.err.empty()) << output << ": " << r.err;
  }
  const std::vector<float> flag = exr_pixels(dirs.out / "flag.exr");
  ASSERT_FALSE(flag.empty());
  EXPECT_TRUE(flag == exr_pixels(dirs.out / "set.exr")) << "-m 3 differs from path.max_depth=3";
  EXPECT_TRUE(flag == exr_pixels(dirs.out / "both.exr"));
  EXPECT_FALSE(flag == exr_pixels(dirs.out / "other.exr")) << "-m has no effect: proves nothing";
  // The provenance records the depth in effect either way; --set keys alone under prism:params.
  const ImageFileContents by_flag = read_image_file(dirs.out / "flag.exr");
  const ImageFileContents by_set = read_image_file(dirs.out / "set.exr");
  EXPECT_EQ(by_flag.attribute("prism:max_depth"), "3");
  EXPECT_EQ(by_set.attribute("prism:max_depth"), "3");
  EXPECT_EQ(by_flag.attribute("prism:params"), "");
  EXPECT_EQ(by_set.attribute("prism:params"), "path.max_depth=3");

  // An integrator without the parameters ignores the flags, silently (the homework's command
  // lines pass -l and -m to every integrator); the provenance still records them.
  ProgramResult r = render("normals", "normals.exr", {"-l", "4", "-m", "2", "-H"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const ImageFileContents normals = read_image_file(dirs.out / "normals.exr");
  EXPECT_EQ(normals.attribute("prism:light_samples"), "4");
  EXPECT_EQ(normals.attribute("prism:max_depth"), "2");

  // A flag and its key with different values: a usage error naming both.
  expect_one_line_error(render("path", "conflict.exr", {"-m", "3", "--set", "path.max_depth=4"}), 2,
                        {"-m 3", "path.max_depth=4"});
  expect_one_line_error(
      render("direct", "conflict.exr", {"-H", "--set", "direct.hemisphere=false"}), 2,
      {"-H", "direct.hemisphere=false"});
  // A key the integrator does not have stays unknown, flag or not.
  expect_one_line_error(render("normals", "unknown.exr", {"--set", "normals.max_depth=3"}), 2,
                        {"unknown parameter 'normals.max_depth'"});
  expect_one_line_error(render("direct", "unknown.exr", {"-m", "3", "--set", "direct.max_depth=3"}),
                        2, {"unknown parameter 'direct.max_depth'"});
  EXPECT_FALSE(std::filesystem::exists(dirs.out / "conflict.exr"));
  EXPECT_FALSE(std::filesystem::exists(dirs.out / "unknown.exr"));
}

TEST(AppCli, SceneFileMaxDepthIsTheIntegratorsUnlessTheCommandLineGivesOne) {
  const TestDirs dirs("app_scene_depth");
  std::ifstream in(default_scene_path());
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const std::string shallow =
      dirs.scene("shallow.json", replaced(text, "\"max_depth\": 5", "\"max_depth\": 1"));
  const auto render = [&](const std::string& scene, const std::string& output,
                          std::vector<std::string> extra) {
    std::vector<std::string> args = {
        "render", scene,        "-r",    "32", "24", "-s", "2",
        "-q",     "--exr-type", "float", "-t", "2",  "-f", (dirs.out / output).string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const ProgramResult r = run_prism(args);
    EXPECT_EQ(r.exit_code, 0) << output << ": " << r.err;
    EXPECT_TRUE(r.err.empty()) << output << ": " << r.err;
    return exr_pixels(dirs.out / output);
  };
  const std::string original = default_scene_path().string();
  EXPECT_TRUE(render(shallow, "scene.exr", {}) == render(original, "m1.exr", {"-m", "1"}));
  // The command line overrides the scene file, by flag or by --set.
  const std::vector<float> m3 = render(original, "m3.exr", {"-m", "3"});
  EXPECT_TRUE(render(shallow, "flag.exr", {"-m", "3"}) == m3);
  EXPECT_TRUE(render(shallow, "set.exr", {"--set", "path.max_depth=3"}) == m3);
  EXPECT_EQ(read_image_file(dirs.out / "scene.exr").attribute("prism:max_depth"), "1");
  EXPECT_EQ(read_image_file(dirs.out / "set.exr").attribute("prism:max_depth"), "3");
}

TEST(AppCli, DefaultSceneRendersWithoutSceneArgument) {
  const TestDirs dirs("app_default");
  const auto out = dirs.out / "default.exr";
  const auto r = run_prism({"render", "-r", "32", "24", "-s", "1", "-q", "-f", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_image_file(out).image.width, 32);
}

TEST(AppCli, InfoReportsCountsAndEveryAccelerator) {
  const TestDirs dirs("app_info");
  const auto r = run_prism({"info", dirs.scene("tiny.dae", kTinyCollada)});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("triangles        4\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("lights           1 (point 1)"), std::string::npos) << r.out;
  for (const char* name : {"brute", "bvh", "embree"}) {
    EXPECT_NE(r.out.find(std::string("  ") + name + " "), std::string::npos) << r.out;
  }
}

TEST(AppCli, InfoOnCs184BunnyPrintsTriangleCount) {
  PRISM_REQUIRE_CS184(scene, "CBbunny.dae");
  const auto r = run_prism({"info", scene.string(), "--accel", "bvh"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("triangles        28588\n"), std::string::npos) << r.out;
}

TEST(AppCli, ListNamesEveryTable) {
  const auto r = run_prism({"list"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* name :
       {"brute", "bvh", "embree", "normals", ".dae", ".json", "noisy_sphere", ".exr", ".png"}) {
    EXPECT_NE(r.out.find(name), std::string::npos) << "missing " << name << " in\n" << r.out;
  }
}

TEST(AppCli, VersionAndHelp) {
  auto r = run_prism({"--version"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out.rfind("prism ", 0), 0u) << r.out;
  r = run_prism({"render", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  for (const char* text : {"--accel", "--spp", "--set", "Output:", ".exr"}) {
    EXPECT_NE(r.out.find(text), std::string::npos) << "help lacks " << text;
  }
}

TEST(AppCli, ColorspacesListsTheConfig) {
  const auto r = run_prism({"colorspaces"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("colour spaces"), std::string::npos) << r.out;
  EXPECT_GT(line_count(r.out), 4u) << r.out;
}

}  // namespace
}  // namespace prism::test
