// `prism render` end to end (core/app/render_command, render_options): the EXR and its
// provenance, the output formats, the integrator flags as aliases of its parameters, the scene
// file's settings, thread-count independence, the adaptive sampler's rate picture, and the
// render in memory of the Python module (render_in_memory()) against the file.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "color/image_output.h"
#include "core/app/render_driver.h"
#include "scenes/scene_loader.h"
#include "tests/support/app_test_helpers.h"
#include "tests/support/image_compare.h"
#include "tests/support/test_support.h"

namespace prism::test {
namespace {

TEST(AppRender, WritesValidExrWithProvenance) {
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

TEST(AppRender, PngAndExrFlagsAddTheOtherFormatBeside) {
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

TEST(AppRender, ThreadCountDoesNotChangePixels) {
  const TestDirs dirs("app_threads");
  const std::string scene = dirs.scene("tiny.dae", kTinyCollada);
  std::vector<ImagePixels> pixels;
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
ImagePixels exr_pixels(const std::filesystem::path& path) {
  return read_image_file(path).image.pixels;
}

TEST(AppRender, IntegratorFlagsAreAliasesOfItsParameters) {
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
  const ImagePixels flag = exr_pixels(dirs.out / "flag.exr");
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

TEST(AppRender, TwoSidedEmittersFlagIsAnAliasOfItsParameter) {
  const TestDirs dirs("app_two_sided");
  const std::string scene = default_scene_path().string();  // a light quad under the ceiling
  const auto render = [&](const std::string& output, std::vector<std::string> extra) {
    std::vector<std::string> args = {
        "render",     scene,   "-r",     "32", "24", "-s", "2",  "-q",
        "--exr-type", "float", "--seed", "3",  "-t", "2",  "-f", (dirs.out / output).string()};
    args.insert(args.end(), extra.begin(), extra.end());
    return run_prism(args);
  };
  for (const auto& [output, extra] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {"one.exr", {}},
           {"flag.exr", {"--two-sided-emitters"}},
           {"set.exr", {"--set", "path.two_sided_emitters=true"}},
           {"direct.exr", {"--integrator", "direct", "--two-sided-emitters"}},
           {"ao.exr", {"--integrator", "ao", "--two-sided-emitters"}}}) {
    const ProgramResult r = render(output, extra);
    ASSERT_EQ(r.exit_code, 0) << output << ": " << r.err;
    EXPECT_EQ(r.err, "") << output;  // ignored by ao, silently, like -l
  }
  const ImagePixels flag = exr_pixels(dirs.out / "flag.exr");
  EXPECT_TRUE(flag == exr_pixels(dirs.out / "set.exr"));
  EXPECT_FALSE(flag == exr_pixels(dirs.out / "one.exr")) << "the back of the light lit nothing";
  expect_one_line_error(
      render("conflict.exr", {"--two-sided-emitters", "--set", "path.two_sided_emitters=false"}), 2,
      {"--two-sided-emitters", "path.two_sided_emitters=false"});
}

TEST(AppRender, AmbientLightIsASkyOnlyWhenAsked) {
  // kTinyCollada lit by an ambient light: escaping camera rays are black, as in the homework,
  // unless <integrator>.ambient_visible makes it a sky.
  const TestDirs dirs("app_ambient");
  const std::string scene = dirs.scene(
      "ambient.dae",
      replaced(kTinyCollada,
               "<point>\n      <color>1 1 1</color><constant_attenuation>1</constant_attenuation>\n"
               "      <linear_attenuation>0</linear_attenuation><quadratic_attenuation>0</"
               "quadratic_attenuation>\n    </point>",
               "<ambient><color>0.5 0.5 0.5</color></ambient>"));
  for (const std::string integrator : {"path", "direct"}) {
    for (const bool visible : {false, true}) {
      SCOPED_TRACE(integrator + (visible ? " visible" : ""));
      const auto out = dirs.out / (integrator + (visible ? "_sky.exr" : ".exr"));
      // The file's camera looks level over the back wall: the top rows are sky.
      std::vector<std::string> args = {"render",     scene,   "-r",
                                       "32",         "24",    "-s",
                                       "2",          "-q",    "--literal-camera",
                                       "--exr-type", "float", "--integrator",
                                       integrator,   "-f",    out.string()};
      if (visible) args.insert(args.end(), {"--set", integrator + ".ambient_visible=true"});
      const ProgramResult r = run_prism(args);
      ASSERT_EQ(r.exit_code, 0) << r.err;
      const ImageFileContents exr = read_image_file(out);
      const int red = exr.channel("R"), depth = exr.channel("Z");
      ASSERT_GE(red, 0);
      ASSERT_GE(depth, 0);
      int escaped = 0, sky = 0, lit = 0;
      for (int y = 0; y < exr.image.height; ++y) {
        for (int x = 0; x < exr.image.width; ++x) {
          const float v = exr.image.at(x, y, red);
          if (exr.image.at(x, y, depth) == 0.0f) {
            ++escaped;
            sky += v == 0.5f;
            if (!visible) {
              EXPECT_EQ(v, 0.0f) << x << "," << y;
            }
          } else {
            lit += v > 0.0f;
          }
        }
      }
      EXPECT_GT(escaped, 0);
      EXPECT_GT(lit, 0);
      if (visible) {
        EXPECT_GT(sky, 0);
      }
    }
  }
}

TEST(AppRender, SceneFileMaxDepthIsTheIntegratorsUnlessTheCommandLineGivesOne) {
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
  const ImagePixels m3 = render(original, "m3.exr", {"-m", "3"});
  EXPECT_TRUE(render(shallow, "flag.exr", {"-m", "3"}) == m3);
  EXPECT_TRUE(render(shallow, "set.exr", {"--set", "path.max_depth=3"}) == m3);
  EXPECT_EQ(read_image_file(dirs.out / "scene.exr").attribute("prism:max_depth"), "1");
  EXPECT_EQ(read_image_file(dirs.out / "set.exr").attribute("prism:max_depth"), "3");
}

TEST(AppRender, HomeworkFileDefectsWarnAndRenderAsTheHomework) {
  // The camera <matrix> short of its last number (as in the homework's CBgems.dae): one
  // warning line naming file and line, and the image of the intact file.
  const TestDirs dirs("app_defects");
  const std::string full = "1 0 0 0 0 0 -1 -3 0 1 0 1 0 0 0 1";
  const std::string shortened = "1 0 0 0 0 0 -1 -3 0 1 0 1 0 0 0";
  const std::string intact = dirs.scene("intact.dae", kTinyCollada);
  const std::string text = replaced(kTinyCollada, full, shortened);
  const std::string defective = dirs.scene("short.dae", text);
  std::vector<ImagePixels> pixels;
  for (const std::string& scene : {intact, defective}) {
    const auto out = dirs.out / (std::filesystem::path(scene).stem().string() + ".exr");
    const auto r = run_prism({"render", scene, "-r", "32", "24", "-s", "2", "-q", "--exr-type",
                              "float", "-t", "2", "-f", out.string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    if (scene == intact) {
      EXPECT_EQ(r.err, "");
    } else {
      const int line = 1 + int(std::count(text.begin(), text.begin() + text.find(shortened), '\n'));
      EXPECT_EQ(r.err, "prism: warning: " + defective + ":" + std::to_string(line) +
                           ": <matrix>: 15 numbers, not 16; the missing ones are read as 0, as "
                           "the CS184 homework does\n");
    }
    pixels.push_back(exr_pixels(out));
  }
  EXPECT_TRUE(pixels[0] == pixels[1]) << "the short camera matrix frames differently";
}

TEST(AppRender, DefaultSceneRendersWithoutSceneArgument) {
  const TestDirs dirs("app_default");
  const auto out = dirs.out / "default.exr";
  const auto r = run_prism({"render", "-r", "32", "24", "-s", "1", "-q", "-f", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_image_file(out).image.width, 32);
}

TEST(AppRender, AdaptiveRenderWritesTheRatePictureBesideItsOutput) {
  const auto dir = test::make_temp_dir("sample_rate");
  const auto scene = (bundled_scene_dir() / "cornell_spheres.json").string();
  const auto result =
      test::run_prism({"render", scene, "--resolution", "24", "18", "--spp", "64", "-a", "8",
                       "0.05", "--quiet", "--output", (dir / "a.exr").string()});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto rate = read_image_file(dir / "a_rate.png");
  EXPECT_EQ(rate.image.width, 24);
  EXPECT_EQ(rate.image.height, 18);
  const auto exr = read_image_file(dir / "a.exr");
  double total = 0;
  const auto& names = exr.image.channel_names;
  const int channel = int(std::find(names.begin(), names.end(), "sampleCount.Y") - names.begin());
  ASSERT_LT(channel, exr.image.channels());
  for (int y = 0; y < 18; ++y) {
    for (int x = 0; x < 24; ++x) total += exr.image.at(x, y, channel);
  }
  EXPECT_LT(total, 24.0 * 18 * 64);  // some pixels converged before 64 samples
  std::filesystem::remove_all(dir);
}

TEST(AppRender, InMemoryRenderHasThePixelsAndProvenanceOfTheFile) {
  const TestDirs dirs("app_in_memory");
  const std::string scene = (bundled_scene_dir() / "cornell_spheres.json").string();
  const auto out = dirs.out / "a.exr";
  const auto r =
      run_prism({"render", scene, "-r", "40", "30", "-s", "4", "--seed", "5", "-m", "3",
                 "--pass-samples", "1", "--exr-type", "float", "-q", "-f", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const ImageFileContents file = read_image_file(out);

  RenderOptions options;
  options.scene = scene;
  options.resolution = {40, 30};
  options.spp = 4;
  options.seed = "5";
  options.max_depth = 3;
  options.pass_samples = 1;
  options.quiet = true;
  int calls = 0;
  const RenderedFrame frame = render_in_memory(options, [&] { ++calls; });
  EXPECT_EQ(calls, 3);  // 4 passes of 1 sample: called between them
  ASSERT_EQ(frame.image.width, 40);
  ASSERT_EQ(frame.image.height, 30);
  for (const std::string& channel : frame.image.channel_names) {
    const std::vector<float> memory = channel_values(frame.image, channel);
    const std::vector<float> written = channel_values(file.image, channel);
    ASSERT_EQ(written.size(), memory.size()) << channel;
    EXPECT_EQ(std::memcmp(written.data(), memory.data(), memory.size() * sizeof(float)), 0)
        << channel;
  }
  // The attributes the file has, with the same values but for times and the command line.
  for (const auto& [name, value] : frame.metadata) {
    if (name == "prism:build_ms" || name == "prism:render_ms" ||
        name == "prism:samples_per_second" || name == "prism:command_line") {
      EXPECT_NE(file.attribute(name), "") << name;
      continue;
    }
    EXPECT_EQ(value, file.attribute(name)) << name;
  }
}

TEST(AppRender, InMemoryRenderStopsWhenTheHookThrows) {
  RenderOptions options;
  options.resolution = {16, 12};
  options.spp = 8;
  options.pass_samples = 1;
  options.quiet = true;
  int calls = 0;
  const auto stop = [&] {
    if (++calls == 2) throw Error(ErrorKind::kInternal, "stopped");
  };
  EXPECT_THROW(render_in_memory(options, stop), Error);
  EXPECT_EQ(calls, 2);
}

}  // namespace
}  // namespace prism::test
