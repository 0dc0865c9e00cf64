// Every class of bad input to the prism program: the documented exit code, one line on stderr
// that names the culprit, and nothing (not even a temporary file) left in the output folder.

#include <gtest/gtest.h>

#include "tests/support/app_test_helpers.h"
#include "tests/support/child_process.h"
#include "tests/support/test_support.h"

namespace prism::test {
namespace {

class AppBadInput : public ::testing::Test {
 protected:
  AppBadInput() : dirs_("app_bad") {}

  /// Runs `prism render <args...> -r 32 24 -s 1 -f out/image.exr`.
  ProgramResult render(std::vector<std::string> args) {
    args.insert(args.begin(), "render");
    args.insert(args.end(), {"-r", "32", "24", "-s", "1", "-f", out_file().string()});
    return run_prism(args);
  }
  std::filesystem::path out_file() const { return dirs_.out / "image.exr"; }
  std::string tiny_scene() const { return dirs_.scene("tiny.dae", kTinyCollada); }

  void expect_nothing_written() {
    EXPECT_EQ(dir_entries(dirs_.out), std::vector<std::string>{}) << "files left behind";
  }

  TestDirs dirs_;
};

TEST_F(AppBadInput, MalformedXml) {
  const std::string text = kTinyCollada.substr(0, kTinyCollada.find("<library_geometries>") + 30);
  const auto r = render({dirs_.scene("broken.dae", text)});
  expect_one_line_error(r, 2, {"broken.dae"});
  expect_nothing_written();
}

TEST_F(AppBadInput, MalformedJson) {
  const auto r = render({dirs_.scene("broken.json", "{\n  \"camera\": { \"fov\": 40,\n")});
  expect_one_line_error(r, 2, {"broken.json"});
  expect_nothing_written();
}

TEST_F(AppBadInput, DanglingReference) {
  const auto scene = dirs_.scene(
      "dangling.dae", replaced(kTinyCollada, "url=\"#box-mesh\"", "url=\"#no-such-mesh\""));
  const auto r = render({scene});
  expect_one_line_error(r, 2, {"dangling.dae", "no-such-mesh"});
  expect_nothing_written();
}

TEST_F(AppBadInput, BadNumber) {
  const auto scene =
      dirs_.scene("badnumber.dae", replaced(kTinyCollada, "1 1 2 -1 1 2<", "1 1 2 -1 1 2x5<"));
  const auto r = render({scene});
  expect_one_line_error(r, 2, {"badnumber.dae", "2x5"});
  expect_nothing_written();
}

TEST_F(AppBadInput, ShortMatrixAboveGeometry) {
  // Tolerated above a camera (a warning), an error above geometry the homework would lose.
  const auto scene = dirs_.scene(
      "short.dae",
      replaced(kTinyCollada, "1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1<", "1 0 0 0 0 1 0 0 0 0 1 0 0 0 0<"));
  const auto r = render({scene});
  expect_one_line_error(r, 2, {"short.dae:", "<matrix>", "15 numbers, not 16", "#box-mesh"});
  expect_nothing_written();
}

TEST_F(AppBadInput, NonFiniteNumber) {
  for (const char* bad : {"nan", "inf", "1e999"}) {
    SCOPED_TRACE(bad);
    const auto scene = dirs_.scene(
        "nonfinite.dae",
        replaced(kTinyCollada, "1 1 2 -1 1 2<", std::string("1 1 2 -1 1 ") + bad + "<"));
    const auto r = render({scene});
    expect_one_line_error(r, 2, {"nonfinite.dae"});
    expect_nothing_written();
  }
}

TEST_F(AppBadInput, MissingMeshFile) {
  // A native scene naming a mesh file that does not exist.
  const std::string text = R"({
  "camera": { "position": [0, 1, 4], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 40 },
  "materials": [ { "name": "grey", "type": "diffuse", "reflectance": [0.5, 0.5, 0.5] } ],
  "meshes": [ { "name": "thing", "material": "grey", "file": "no_such_mesh.obj" } ]
})";
  const auto r = render({dirs_.scene("missing_mesh.json", text)});
  expect_one_line_error(r, 2, {"no_such_mesh.obj"});
  expect_nothing_written();
}

TEST_F(AppBadInput, MissingSceneFile) {
  const auto r = render({(dirs_.in / "nowhere.dae").string()});
  expect_one_line_error(r, 2, {"nowhere.dae"});
  expect_nothing_written();
}

TEST_F(AppBadInput, UnknownAcceleratorListsTheAvailableOnes) {
  const auto r = render({tiny_scene(), "--accel", "bhv"});
  expect_one_line_error(r, 2, {"bhv", "brute", "bvh", "embree"});
  expect_nothing_written();
}

TEST_F(AppBadInput, UnknownIntegratorListsTheAvailableOnes) {
  const auto r = render({tiny_scene(), "--integrator", "pathh"});
  expect_one_line_error(r, 2, {"pathh", "available", "normals"});
  expect_nothing_written();
}

TEST_F(AppBadInput, UnknownSetKey) {
  const std::string scene = tiny_scene();
  // A typo in a parameter of the accelerator in use, and a key that names no component.
  for (const std::string set : {"bvh.no_such_parameter=4", "bvhh.max_leaf_size=4", "spp=4"}) {
    SCOPED_TRACE(set);
    const auto r = render({scene, "--set", set});
    expect_one_line_error(r, 2, {set.substr(0, set.find('='))});
    expect_nothing_written();
  }
}

TEST_F(AppBadInput, BadOptionValues) {
  const std::string scene = tiny_scene();
  struct Case {
    std::vector<std::string> args;
    std::string mention;
  };
  const std::vector<Case> cases = {
      {{"--spp", "-4"}, "--spp"},
      {{"--spp", "many"}, "--spp"},
      {{"--resolution", "0", "24"}, "--resolution"},
      {{"--resolution", "20000", "24"}, "--resolution"},
      {{"--resolution", "16384", "16384"}, "--resolution"},
      {{"--threads", "-1"}, "--threads"},
      {{"-m", "-1"}, "--max-depth"},
      {{"--seed", "-1"}, "--seed"},
      {{"-b", "nan"}, "--lens-radius"},
      {{"-d", "0"}, "--focal-distance"},
      {{"-a", "64", "-1"}, "--adaptive"},
      {{"--exposure", "nan"}, "--exposure"},
      {{"--exr-type", "double"}, "'double'"},
      {{"--set", "novalue"}, "novalue"},
      {{"--no-such-option"}, "--no-such-option"},
      {{"-e", "sky.exr"}, "sky.exr: environment map (-e): the file does not exist"},
  };
  for (const auto& c : cases) {
    std::vector<std::string> args = {scene};
    args.insert(args.end(), c.args.begin(), c.args.end());
    SCOPED_TRACE(testing::PrintToString(args));
    expect_one_line_error(render(args), 2, {c.mention});
    expect_nothing_written();
  }
}

TEST_F(AppBadInput, UnsupportedOutputExtension) {
  const auto r = run_prism({"render", tiny_scene(), "-r", "32", "24", "-s", "1", "-f",
                            (dirs_.out / "image.bmp").string()});
  expect_one_line_error(r, 2, {"--output", ".bmp"});
  expect_nothing_written();
}

TEST_F(AppBadInput, OutputFolderMissing) {
  const auto target = dirs_.out / "missing" / "image.exr";
  const auto r =
      run_prism({"render", tiny_scene(), "-r", "32", "24", "-s", "1", "-f", target.string()});
  expect_one_line_error(r, 3, {"missing"});
  expect_nothing_written();
}

TEST_F(AppBadInput, OutputFolderReadOnly) {
  namespace fs = std::filesystem;
  // The case's folders readable by the user prism may run as (nobody, below).
  fs::permissions(dirs_.root, fs::perms::others_read | fs::perms::others_exec,
                  fs::perm_options::add);
  fs::permissions(dirs_.in, fs::perms::all);
  fs::permissions(dirs_.out, fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                                 fs::perms::group_exec | fs::perms::others_read |
                                 fs::perms::others_exec);
  // Root ignores permission bits: prism then runs as nobody (drop_root), for whom they hold.
  const auto r = run_prism_limited({"render", tiny_scene(), "-r", "32", "24", "-s", "1", "-f",
                                    out_file().string()},
                                   ProcessLimits{.drop_root = true})
                     .result;
  expect_one_line_error(r, 3, {dirs_.out.string()});
  expect_nothing_written();
}

TEST_F(AppBadInput, UnknownColourSpace) {
  for (const char* option : {"--working-space", "--output-space"}) {
    SCOPED_TRACE(option);
    const auto r = render({tiny_scene(), option, "No Such Space"});
    expect_one_line_error(r, 2, {"No Such Space"});
    expect_nothing_written();
  }
}

}  // namespace
}  // namespace prism::test
