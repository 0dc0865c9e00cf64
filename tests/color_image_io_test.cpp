// The image module (color/image_io.h): the program starts without OpenImageIO, loads the module
// when it reads or writes an image, and says so in one line when the module is missing.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/support/app_test_helpers.h"
#include "tests/support/child_process.h"
#include "tests/support/test_support.h"

namespace prism::test {
namespace {

/// Runs the program with LD_DEBUG=files, under which the dynamic loader names on stderr every
/// library it loads (and the rest of the test process is unaffected: the variable is unset
/// again before the next run).
ProgramResult run_with_loaded_libraries(const std::vector<std::string>& args) {
  setenv("LD_DEBUG", "files", 1);
  ProgramResult r = run_prism(args);
  unsetenv("LD_DEBUG");
  return r;
}

bool loads_openimageio(const ProgramResult& r) {
  return r.err.find("file=libOpenImageIO.so") != std::string::npos;
}

TEST(ColorImageIo, OpenImageIoIsLoadedOnlyForImages) {
#if defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "ThreadSanitizer builds link OpenImageIO into the program (color/CMakeLists.txt)";
#endif
  const ProgramResult version = run_with_loaded_libraries({"--version"});
  ASSERT_EQ(version.exit_code, 0) << version.err;
  EXPECT_FALSE(loads_openimageio(version)) << "prism --version loaded OpenImageIO";
  EXPECT_NE(version.err.find("file=libOpenColorIO.so"), std::string::npos)
      << "the check no longer sees what the loader loads: " << version.err.substr(0, 2000);

  TestDirs dirs("image_io");
  const std::string scene = dirs.scene("tiny.dae", kTinyCollada);
  const ProgramResult render = run_with_loaded_libraries(
      {"render", scene, "-r", "16", "12", "-s", "1", "-q", "-f", (dirs.out / "x.exr").string()});
  ASSERT_EQ(render.exit_code, 0) << render.err.substr(
      render.err.size() > 2000 ? render.err.size() - 2000 : 0);
  EXPECT_TRUE(loads_openimageio(render)) << "the render wrote its EXR without OpenImageIO?";
  EXPECT_TRUE(std::filesystem::exists(dirs.out / "x.exr"));
}

TEST(ColorImageIo, MissingModuleIsOneLineBeforeTheRender) {
  TestDirs dirs("image_io_missing");
  // A copy of the program in a folder without the module beside it.
  const std::filesystem::path program = dirs.root / "prism";
  std::filesystem::copy_file(PRISM_BINARY, program);
  const std::string scene = dirs.scene("tiny.dae", kTinyCollada);
  ProcessLimits limits;
  limits.program = program.string();
  const TimedProgramResult timed = run_prism_limited(
      {"render", scene, "-r", "16", "12", "-s", "1", "-f", (dirs.out / "x.exr").string()}, limits);
  const ProgramResult& r = timed.result;
  expect_one_line_error(r, 1, {(dirs.root / "libprism_image_io.so").string(), "no such file"});
  EXPECT_EQ(dir_entries(dirs.out), std::vector<std::string>{}) << "files left behind";

  // Commands that read or write no image do not need it.
  ProcessLimits same = limits;
  const ProgramResult info = run_prism_limited({"info", scene}, same).result;
  EXPECT_EQ(info.exit_code, 0) << info.err;
}

TEST(ColorImageIo, ModuleThatDoesNotLoadIsOneLineAndNoImage) {
  TestDirs dirs("image_io_broken");
  // A copy of the program beside a "module" that is no shared library: it is there, so the
  // render starts, and it fails to load in the background (two threads) or at the write (one).
  const std::filesystem::path program = dirs.root / "prism";
  std::filesystem::copy_file(PRISM_BINARY, program);
  write_text(dirs.root / "libprism_image_io.so", "not a shared library\n");
  const std::string scene = dirs.scene("tiny.dae", kTinyCollada);
  for (const char* threads : {"1", "2"}) {
    SCOPED_TRACE(std::string("-t ") + threads);
    ProcessLimits limits;
    limits.program = program.string();
    const TimedProgramResult timed =
        run_prism_limited({"render", scene, "-r", "16", "12", "-s", "4", "-t", threads, "-q", "-f",
                           (dirs.out / "x.exr").string()},
                          limits);
    expect_one_line_error(
        timed.result, 1,
        {"cannot load prism's image module", (dirs.root / "libprism_image_io.so").string()});
    EXPECT_EQ(dir_entries(dirs.out), std::vector<std::string>{}) << "files left behind";
  }
}

}  // namespace
}  // namespace prism::test
