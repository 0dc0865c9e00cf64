// `mpirun -np 3 prism render ...` end to end (core/app/mpi_*.cpp): the frame split across ranks
// is the one-process frame bit for bit, checkpoints cross between the two, a rank that fails
// fails the run with one line naming it. Skipped where mpirun is not installed.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "color/image_output.h"
#include "core/film.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {

namespace fs = std::filesystem;
using test::ProgramResult;

const std::string kScene = std::string(PRISM_SOURCE_DIR) + "/scenes/data/cornell_spheres.json";

std::optional<fs::path> find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream folders(path ? path : "");
  for (std::string folder; std::getline(folders, folder, ':');) {
    const fs::path candidate = fs::path(folder) / name;
    if (!folder.empty() && access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return std::nullopt;
}

#define PRISM_REQUIRE_MPIRUN(var)                                                      \
  const auto var##_opt = find_on_path("mpirun");                                       \
  if (!var##_opt) GTEST_SKIP() << "mpirun is not on PATH (scripts/setup installs it)"; \
  const fs::path var = *var##_opt

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// A program started with its output going to files, waited for with a time limit.
class Launch {
 public:
  Launch(const fs::path& program, const std::vector<std::string>& args, const fs::path& dir)
      : out_(dir / "launch.out"), err_(dir / "launch.err") {
    pid_ = fork();
    if (pid_ < 0) throw std::runtime_error("fork failed");
    if (pid_ == 0) {
      freopen("/dev/null", "r", stdin);
      freopen(out_.c_str(), "w", stdout);
      freopen(err_.c_str(), "w", stderr);
      std::vector<std::string> copy = args;
      std::string name = program.string();
      std::vector<char*> argv{name.data()};
      for (auto& a : copy) argv.push_back(a.data());
      argv.push_back(nullptr);
      execv(name.c_str(), argv.data());
      _exit(127);
    }
  }

  pid_t pid() const { return pid_; }

  /// Waits for the end (killing the program after `timeout_seconds`: exit code -9).
  ProgramResult wait(int timeout_seconds = 120) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeout_seconds);
    int status = 0;
    ProgramResult result;
    while (waitpid(pid_, &status, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() > deadline) {
        kill(pid_, SIGKILL);
        waitpid(pid_, &status, 0);
        result.exit_code = -9;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (result.exit_code != -9) {
      result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
    }
    result.out = read_text(out_);
    result.err = read_text(err_);
    return result;
  }

 private:
  pid_t pid_;
  fs::path out_, err_;
};

/// Whether LeakSanitizer checks the ranks (ASan builds only; other builds ignore it).
enum class RankLeakCheck {
  /// No leak check in the ranks: ASan's other checks only, with its fast unwinder.
  kOff,
  /// Leak check with every allocation's whole stack: the suppressions of Open MPI's own memory
  /// (tests/support/lsan.supp) match its library frames, which the fast unwinder loses. That
  /// makes a run about ten times slower (25 s against 2 s for the smallest one), so two tests
  /// ask for it: a whole render across ranks and a run that one rank fails
  /// (docs/RELIABILITY.md, "Options").
  kWholeStacks,
};

/// mpirun's arguments for 3 ranks of `program` (prism by default) with `args`.
std::vector<std::string> mpirun_args(const std::vector<std::string>& args,
                                     RankLeakCheck leak_check = RankLeakCheck::kOff,
                                     const std::string& program = PRISM_BINARY) {
  std::vector<std::string> all = {"--allow-run-as-root", "--oversubscribe", "-np", "3"};
  if (const char* asan = std::getenv("ASAN_OPTIONS")) {
    const char* rank_options =
        leak_check == RankLeakCheck::kWholeStacks ? ":fast_unwind_on_malloc=0" : ":detect_leaks=0";
    all.insert(all.end(), {"-x", std::string("ASAN_OPTIONS=") + asan + rank_options});
  }
  all.push_back(program);
  all.insert(all.end(), args.begin(), args.end());
  return all;
}

ProgramResult run_mpi(const fs::path& mpirun, const std::vector<std::string>& args,
                      const fs::path& dir, RankLeakCheck leak_check = RankLeakCheck::kOff) {
  return Launch(mpirun, mpirun_args(args, leak_check), dir).wait();
}

/// The ranks started by the mpirun process `mpirun` (its children), by rank.
std::map<int, pid_t> rank_pids(pid_t mpirun) {
  std::map<int, pid_t> ranks;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::istringstream stat(read_text(entry.path() / "stat"));
    std::string pid, command, state;
    pid_t parent = 0;
    // The command is in parentheses and has no spaces here (prism, mpirun, a shell).
    stat >> pid >> command >> state >> parent;
    if (parent != mpirun) continue;
    std::stringstream environment(read_text(entry.path() / "environ"));
    for (std::string variable; std::getline(environment, variable, '\0');) {
      if (variable.rfind("OMPI_COMM_WORLD_RANK=", 0) == 0) {
        ranks[std::stoi(variable.substr(21))] = pid_t(std::stoi(name));
      }
    }
  }
  return ranks;
}

void wait_for_file(const fs::path& path, int timeout_seconds = 60) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeout_seconds);
  while (!fs::exists(path) && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(fs::exists(path)) << path;
}

/// Every channel of every pixel, and the windows, are equal.
void expect_same_pixels(const fs::path& a, const fs::path& b) {
  const Image x = read_image_file(a).image;
  const Image y = read_image_file(b).image;
  ASSERT_EQ(x.channel_names, y.channel_names);
  ASSERT_EQ(x.width, y.width);
  ASSERT_EQ(x.height, y.height);
  EXPECT_EQ(x.x, y.x);
  EXPECT_EQ(x.y, y.y);
  ASSERT_EQ(x.pixels.size(), y.pixels.size());
  size_t different = 0;
  for (size_t i = 0; i < x.pixels.size(); ++i) different += x.pixels[i] != y.pixels[i] ? 1 : 0;
  EXPECT_EQ(different, 0u) << a << " and " << b << " differ";
}

size_t count_of(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

/// Renders `args` with -f <dir>/one.exr in one process and with -f <dir>/mpi.exr on 3 ranks and
/// expects the same pixels; returns the MPI run.
ProgramResult expect_same_render(const fs::path& mpirun, const fs::path& dir,
                                 std::vector<std::string> args,
                                 RankLeakCheck leak_check = RankLeakCheck::kOff) {
  std::vector<std::string> one = args;
  one.insert(one.end(), {"-f", (dir / "one.exr").string()});
  const ProgramResult single = test::run_prism(one);
  EXPECT_EQ(single.exit_code, 0) << single.err;
  args.insert(args.end(), {"-f", (dir / "mpi.exr").string()});
  const ProgramResult result = run_mpi(mpirun, args, dir, leak_check);
  EXPECT_EQ(result.exit_code, 0) << result.err;
  if (single.exit_code == 0 && result.exit_code == 0) {
    expect_same_pixels(dir / "one.exr", dir / "mpi.exr");
  }
  return result;
}

TEST(AppMpi, ThreeRanksRenderTheOneProcessFrameAndReportOnce) {
  PRISM_REQUIRE_MPIRUN(mpirun);
  const fs::path dir = test::make_temp_dir("mpi_frame");
  const ProgramResult result = expect_same_render(
      mpirun, dir, {"-r", "64", "48", "-s", "8", kScene}, RankLeakCheck::kWholeStacks);
  // Rank 0 alone prints the summary, and the progress (its final line: stderr is no terminal).
  EXPECT_EQ(count_of(result.out, "cornell_spheres.json:"), 1u) << result.out;
  EXPECT_NE(result.out.find("on 3 MPI ranks"), std::string::npos) << result.out;
  EXPECT_EQ(count_of(result.err, "rendering: 100%"), 1u) << result.err;
  const ImageFileContents exr = read_image_file(dir / "mpi.exr");
  EXPECT_EQ(exr.attribute("prism:mpiRanks"), "3");
  // A pixel's state crosses the network once at most (rank 0 renders some tiles itself).
  const long long bytes = std::stoll(exr.attribute("prism:mpiBytes"));
  EXPECT_GT(bytes, 0);
  EXPECT_LT(bytes, 64 * 48 * (long long)sizeof(FilmPixel) + 16 * 1024);
  fs::remove_all(dir);
}

TEST(AppMpi, AdaptiveSamplingAndCropsAreTheOneProcessFrame) {
  PRISM_REQUIRE_MPIRUN(mpirun);
  const fs::path dir = test::make_temp_dir("mpi_adaptive");
  expect_same_render(mpirun, dir,
                     {"-q", "-r", "64", "48", "-s", "16", "-a", "4", "0.05", "--crop", "5", "3",
                      "61", "40", kScene});
  fs::remove_all(dir);
}

TEST(AppMpi, Cs184SceneIsTheOneProcessFrame) {
  PRISM_REQUIRE_MPIRUN(mpirun);
  PRISM_REQUIRE_CS184(scene, "CBspheres_lambertian.dae");
  const fs::path dir = test::make_temp_dir("mpi_cs184");
  expect_same_render(mpirun, dir, {"-q", "-r", "64", "48", "-s", "8", scene.string()});
  fs::remove_all(dir);
}

// The render of the checkpoint tests: under a second of work in 24 tiles, adaptive (a quarter
// of the samples under a sanitizer: still seconds there).
const std::vector<std::string> kLongerRender = {
    "-q", "-r", "96",   "64",  "-s", std::to_string(test::sanitizer_share(128)),
    "-a", "16", "0.02", kScene};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.begin(), more.begin(), more.end());
  return args;
}

TEST(AppMpi, CheckpointsCrossBetweenMpiAndOneProcess) {
  PRISM_REQUIRE_MPIRUN(mpirun);
  const fs::path dir = test::make_temp_dir("mpi_checkpoint");
  const fs::path reference = dir / "reference.exr";
  ASSERT_EQ(test::run_prism(with(kLongerRender, {"-f", reference.string()})).exit_code, 0);

  // Stopped under MPI by SIGTERM to every rank (as srun or scancel send it) once rendering:
  // image and checkpoint written, 143; the checkpoint resumes in one process.
  const fs::path stopped = dir / "mpi.exr", checkpoint = dir / "mpi_ck.exr";
  Launch launch(
      mpirun,
      mpirun_args(with(kLongerRender, {"-f", stopped.string(), "--checkpoint", checkpoint.string(),
                                       "--checkpoint-interval", "0.05"})),
      dir);
  wait_for_file(checkpoint);
  for (const auto& [rank, pid] : rank_pids(launch.pid())) kill(pid, SIGTERM);
  const ProgramResult result = launch.wait();
  ASSERT_EQ(result.exit_code, 143) << result.err;
  EXPECT_EQ(read_image_file(stopped).attribute("prism:stoppedBy"), "SIGTERM");
  const ProgramResult resumed = test::run_prism({"-q", "--resume", checkpoint.string()});
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  expect_same_pixels(reference, stopped);

  // A one-process checkpoint (pass-major: every tile part-way) resumes under MPI.
  const fs::path single = dir / "one.exr", single_checkpoint = dir / "one_ck.exr";
  const ProgramResult part =
      test::run_prism(with(kLongerRender, {"-f", single.string(), "--checkpoint",
                                           single_checkpoint.string(), "--time-limit", "0.2"}));
  ASSERT_EQ(part.exit_code, 0) << part.err;
  ASSERT_NE(read_image_file(single).attribute("prism:stoppedBy"), "-");
  const ProgramResult continued =
      run_mpi(mpirun, {"-q", "--resume", single_checkpoint.string()}, dir);
  ASSERT_EQ(continued.exit_code, 0) << continued.err;
  expect_same_pixels(reference, single);
  fs::remove_all(dir);
}

/// A script that runs its arguments with `good` appended, and on rank 1 with `rank1` instead.
fs::path rank1_wrapper(const fs::path& dir, const std::string& good, const std::string& rank1) {
  const fs::path script = dir / "rank1_scene.sh";
  test::write_text(script, "#!/bin/sh\nscene='" + good +
                               "'\n[ \"$OMPI_COMM_WORLD_RANK\" = 1 ] && scene='" + rank1 +
                               "'\nexec \"$@\" \"$scene\"\n");
  fs::permissions(script, fs::perms::owner_all);
  return script;
}

/// Runs a 3-rank render whose rank 1 gets `rank1_scene`; expects exit 2, one error line naming
/// rank 1 and containing `expected`, and no output file.
void expect_rank1_failure(const std::string& rank1_scene, const std::string& expected,
                          RankLeakCheck leak_check = RankLeakCheck::kOff) {
  PRISM_REQUIRE_MPIRUN(mpirun);
  const fs::path dir = test::make_temp_dir("mpi_rank1");
  const fs::path out = dir / "out.exr";
  const fs::path wrapper = rank1_wrapper(dir, kScene, rank1_scene);
  const std::vector<std::string> args =
      mpirun_args({PRISM_BINARY, "-q", "-r", "32", "24", "-s", "4", "-f", out.string()}, leak_check,
                  wrapper.string());
  const ProgramResult result = Launch(mpirun, args, dir).wait();
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_EQ(count_of(result.err, "prism: error:"), 1u) << result.err;
  EXPECT_NE(result.err.find("prism: error: rank 1: "), std::string::npos) << result.err;
  EXPECT_NE(result.err.find(expected), std::string::npos) << result.err;
  EXPECT_FALSE(fs::exists(out));
  fs::remove_all(dir);
}

TEST(AppMpi, ARankThatCannotReadTheSceneFailsTheRunNamingIt) {
  expect_rank1_failure("/nonexistent/scene.json", "/nonexistent/scene.json",
                       RankLeakCheck::kWholeStacks);
}

TEST(AppMpi, ARankWithAnotherSceneFailsTheRunNamingIt) {
  expect_rank1_failure(std::string(PRISM_SOURCE_DIR) + "/scenes/data/cornell_empty.json",
                       "differs from rank 0's: 'scene'");
}

TEST(AppMpi, ARankThatDiesLeavesNoOutputFile) {
  PRISM_REQUIRE_MPIRUN(mpirun);
  const fs::path dir = test::make_temp_dir("mpi_killed");
  const fs::path out = dir / "out.exr", checkpoint = dir / "ck.exr";
  Launch launch(
      mpirun,
      mpirun_args(with(kLongerRender, {"-f", out.string(), "--checkpoint", checkpoint.string(),
                                       "--checkpoint-interval", "0.05"})),
      dir);
  wait_for_file(checkpoint);
  const auto ranks = rank_pids(launch.pid());
  ASSERT_EQ(ranks.count(2), 1u);
  kill(ranks.at(2), SIGKILL);
  const ProgramResult result = launch.wait();
  EXPECT_NE(result.exit_code, 0);
  EXPECT_FALSE(fs::exists(out));
  // No image at all, complete or partial: only the checkpoints written before (and, when rank
  // 0 was killed while writing one, its temporary file, removed by the next run).
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(name == "ck.exr" || name.rfind(".ck.exr.prism-tmp", 0) == 0 ||
                name.rfind("launch.", 0) == 0)
        << name;
  }
  fs::remove_all(dir);
}

TEST(AppMpi, TimeLimitIsRefusedUnderMpi) {
  PRISM_REQUIRE_MPIRUN(mpirun);
  const fs::path dir = test::make_temp_dir("mpi_time_limit");
  const ProgramResult result = run_mpi(
      mpirun, {"-q", "-r", "32", "24", "--time-limit", "5", "-f", (dir / "o.exr").string(), kScene},
      dir);
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(count_of(result.err, "prism: error:"), 1u) << result.err;
  EXPECT_NE(result.err.find("--time-limit: cannot be used under MPI"), std::string::npos)
      << result.err;
  EXPECT_FALSE(fs::exists(dir / "o.exr"));
  fs::remove_all(dir);
}

TEST(AppMpi, OtherCommandsRunOnRankZeroAlone) {
  PRISM_REQUIRE_MPIRUN(mpirun);
  const fs::path dir = test::make_temp_dir("mpi_version");
  const ProgramResult version = run_mpi(mpirun, {"--version"}, dir);
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_EQ(count_of(version.out, "prism "), 1u) << version.out;
  const ProgramResult typo = run_mpi(mpirun, {"render", "--no-such-flag"}, dir);
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_EQ(count_of(typo.err, "prism: error:"), 1u) << typo.err;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace prism
