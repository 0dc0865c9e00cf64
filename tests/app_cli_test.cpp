// The command line (core/app/cli) and the commands that only report: the homework's argument
// form without a command word, info, list, colorspaces, --version and --help. Rendering is in
// app_render_test.cpp, the other commands in app_<command>_test.cpp.

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "core/app/cli.h"
#include "core/error.h"
#include "tests/support/app_test_helpers.h"
#include "tests/support/test_support.h"

namespace prism::test {
namespace {

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

TEST(AppCli, InfoPrintsTheSceneWarnings) {
  const TestDirs dirs("app_info_warn");
  const std::string scene =
      dirs.scene("short.dae", replaced(kTinyCollada, "0 0 0 1</matrix>\n        <instance_camera",
                                       "0 0 0</matrix>\n        <instance_camera"));
  const auto r = run_prism({"info", scene, "--accel", "bvh"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(line_count(r.err), 1u) << r.err;
  EXPECT_EQ(r.err.rfind("prism: warning: " + scene + ":", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("<matrix>: 15 numbers, not 16"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("triangles        4\n"), std::string::npos) << r.out;
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

/// parse_render_arguments() (the render-options fuzz target's entry) reads what run_cli() reads
/// and turns a syntax error into Error(kUsage) in one line.
TEST(AppCli, ParseRenderArgumentsFillsTheOptions) {
  const RenderOptions o = parse_render_arguments(
      {"-s", "8", "-r", "64", "48", "--set", "bvh.max_leaf_size=2", "a.dae"});
  EXPECT_EQ(o.scene, "a.dae");
  EXPECT_EQ(o.spp, 8);
  EXPECT_EQ(o.resolution, std::make_pair(64, 48));
  EXPECT_EQ(o.set, std::vector<std::string>{"bvh.max_leaf_size=2"});
  try {
    parse_render_arguments({"-r", "64"});
    ADD_FAILURE() << "no error for -r with one value";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kUsage);
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace prism::test
