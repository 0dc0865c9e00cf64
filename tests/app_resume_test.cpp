// Checkpoints and --resume end to end (`prism render`): a render stopped by --time-limit, by a
// first SIGINT or SIGTERM, or killed with SIGKILL at random moments over and over, and resumed
// from its checkpoint until it finishes, gives the uninterrupted render's image bit for bit; a
// second signal ends the render at once with no output and no temporary file; a resume refuses
// a changed scene, a changed mesh file, damaged or foreign files and contradicting options,
// writing nothing; a checkpoint of a crop resumes into the crop.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "color/image_output.h"
#include "tests/support/app_test_helpers.h"
#include "tests/support/child_process.h"
#include "tests/support/image_compare.h"
#include "tests/support/test_support.h"

namespace prism::test {
namespace {

namespace fs = std::filesystem;

const fs::path kSpheres = fs::path(PRISM_SOURCE_DIR) / "scenes" / "data" / "cornell_spheres.json";

/// `prism render` with `args` after the options every run here shares: quiet, float EXR (every
/// bit of the film's means).
std::vector<std::string> render_args(const std::vector<std::string>& args) {
  std::vector<std::string> all = {"render", "-q", "--exr-type", "float"};
  all.insert(all.end(), args.begin(), args.end());
  return all;
}

/// `prism render --resume checkpoint` with `args` added.
std::vector<std::string> resume_args(const fs::path& checkpoint,
                                     const std::vector<std::string>& args = {}) {
  std::vector<std::string> all = {"render", "-q", "--resume", checkpoint.string()};
  all.insert(all.end(), args.begin(), args.end());
  return all;
}

std::vector<std::string> plus(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

/// Runs prism with `args` and expects exit 0.
void run_ok(const std::vector<std::string>& args) {
  const ProgramResult r = run_prism(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
}

/// "k of N" of prism:passes: {k, N}, or {-1, -1}.
std::pair<int, int> passes_of(const ImageFileContents& file) {
  int k = -1, n = -1;
  if (std::sscanf(file.attribute("prism:passes").c_str(), "%d of %d", &k, &n) != 2) return {-1, -1};
  return {k, n};
}

/// Every file of `dir` with its bytes, to check that a refused run wrote nothing.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    std::ifstream in(e.path(), std::ios::binary);
    files[e.path().filename().string()] = std::string(std::istreambuf_iterator<char>(in), {});
  }
  return files;
}

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

// --- Time limit and resume --------------------------------------------------------------------

/// 64 x 48 at `spp` samples (a multiple of 64), in 64 passes (the default makes fewer below
/// 256 spp) or in passes of `pass_samples`. Runs stopped by a time limit add -t 1: still far
/// from done at the limit on a fast machine (a resume may use any number of threads: it changes
/// no bit).
std::vector<std::string> spheres(int spp, const fs::path& scene = kSpheres, int pass_samples = 0) {
  const std::vector<std::string> args = {scene.string(), "-r", "64",
                                         "48",           "-s", std::to_string(spp)};
  return plus(args, {"--pass-samples", std::to_string(pass_samples > 0 ? pass_samples : spp / 64)});
}

TEST(AppResume, TimeLimitThenResumeGivesTheUninterruptedBits) {
  TestDirs dirs("resume_once");
  const fs::path ref = dirs.out / "ref.exr", out = dirs.out / "out.exr", ck = dirs.out / "ck.exr";
  run_ok(render_args(plus(spheres(128), {"-f", ref.string()})));
  run_ok(render_args(plus(spheres(128), {"-t", "1", "--time-limit", "0.05", "--checkpoint",
                                         ck.string(), "-f", out.string()})));
  const ImageFileContents stopped = read_image_file(out);
  ASSERT_EQ(stopped.attribute("prism:stoppedBy"), "time limit");
  ASSERT_LT(passes_of(stopped).first, 64);
  ASSERT_TRUE(fs::exists(ck));
  EXPECT_FALSE(same_bits(stopped.image, read_exr_image(ref))) << "stopped early: not the image";

  // The checkpoint's options: the same output file, without the scene on the command line.
  const ProgramResult r = run_prism(resume_args(ck));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(out.string()), std::string::npos) << r.out;
  const ImageFileContents resumed = read_image_file(out);
  EXPECT_EQ(resumed.attribute("prism:stoppedBy"), "-");
  EXPECT_EQ(resumed.attribute("prism:passes"), "64 of 64");
  EXPECT_TRUE(same_bits(resumed.image, read_exr_image(ref)));
  EXPECT_EQ(temp_files_in(dirs.out), std::vector<std::string>{});
}

TEST(AppResume, ResumedTwiceGivesTheUninterruptedBits) {
  TestDirs dirs("resume_twice");
  const fs::path ref = dirs.out / "ref.exr", out = dirs.out / "out.exr", ck = dirs.out / "ck.exr";
  run_ok(render_args(plus(spheres(128), {"-f", ref.string()})));
  run_ok(render_args(plus(spheres(128), {"-t", "1", "--time-limit", "0.05", "--checkpoint",
                                         ck.string(), "-f", out.string()})));
  const int first = passes_of(read_image_file(out)).first;
  ASSERT_GE(first, 1);
  ASSERT_LT(first, 64);

  // The second run stops by its own time limit, further on, and checkpoints again.
  run_ok(resume_args(ck, {"-t", "1", "--time-limit", "0.05"}));
  const ImageFileContents second = read_image_file(out);
  ASSERT_EQ(second.attribute("prism:stoppedBy"), "time limit");
  const int next = passes_of(second).first;
  EXPECT_GT(next, first);
  ASSERT_LT(next, 64);

  run_ok(resume_args(ck));
  const ImageFileContents resumed = read_image_file(out);
  EXPECT_EQ(resumed.attribute("prism:passes"), "64 of 64");
  EXPECT_TRUE(same_bits(resumed.image, read_exr_image(ref)));
}

TEST(AppResume, AdaptiveSamplingResumesToTheUninterruptedBits) {
  // Passes of 3 against batches of 4: the stop falls inside a batch, and the resumed run must
  // carry on each pixel's convergence test from the checkpoint's sums.
  TestDirs dirs("resume_adaptive");
  const fs::path ref = dirs.out / "ref.exr", out = dirs.out / "out.exr", ck = dirs.out / "ck.exr";
  const std::vector<std::string> adaptive = {"-a", "4", "0.05"};
  run_ok(render_args(plus(plus(spheres(128), adaptive), {"-f", ref.string()})));
  run_ok(render_args(
      plus(plus(spheres(128, kSpheres, 3), adaptive),
           {"-t", "1", "--time-limit", "0.05", "--checkpoint", ck.string(), "-f", out.string()})));
  ASSERT_EQ(read_image_file(out).attribute("prism:stoppedBy"), "time limit");
  run_ok(resume_args(ck));
  const ImageFileContents resumed = read_image_file(out);
  EXPECT_EQ(resumed.attribute("prism:passes"), "43 of 43");
  EXPECT_TRUE(same_bits(resumed.image, read_exr_image(ref)));
  // Adaptive sampling did stop pixels early.
  const std::vector<float> counts = channel_values(resumed.image, "sampleCount.Y");
  EXPECT_LT(*std::min_element(counts.begin(), counts.end()), 128.0f);
}

// --- Signals ----------------------------------------------------------------------------------

/// 32 x 24 at 512 samples in 16 passes of 32.
std::vector<std::string> signal_scene() {
  return {kSpheres.string(), "-r", "32", "24", "-s", "512", "--pass-samples", "32"};
}

/// signal_scene() with a checkpoint after every pass: the checkpoint's appearance says that the
/// render loop runs (signal handlers installed), with most passes to go.
std::vector<std::string> signal_render(const fs::path& ck, const fs::path& out) {
  return plus(signal_scene(),
              {"--checkpoint", ck.string(), "--checkpoint-interval", "0.001", "-f", out.string()});
}

void expect_first_signal_stops_and_resumes(int signal, const std::string& name) {
  TestDirs dirs("resume_signal");
  const fs::path ref = dirs.out / "ref.exr", out = dirs.out / "out.exr", ck = dirs.out / "ck.exr";
  const fs::path log = dirs.root / "log.txt";
  run_ok(render_args(plus(signal_scene(), {"-f", ref.string()})));

  // One thread, so that the signal mostly comes while some of the pass's 4 tiles are done and
  // others not yet started: the render then stops inside a pass, and the resume must take the
  // rest of that pass tile by tile. A signal that comes between passes stops at a whole pass;
  // then try again (a few times at most).
  std::optional<ImageFileContents> stopped;
  bool inside_a_pass = false;
  for (int attempt = 0; attempt < 10 && !inside_a_pass; ++attempt) {
    fs::remove(out);
    fs::remove(ck);
    PrismProcess render(render_args(plus(signal_render(ck, out), {"-t", "1"})), log);
    ASSERT_TRUE(wait_for_file(ck, render)) << read_bytes(log);
    // Past the checkpoint's last steps (fsync), into the next pass's first tile.
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    render.send(signal);
    ASSERT_EQ(render.wait(), 128 + signal) << read_bytes(log);

    // The image of what was taken, saying why it stopped, and a checkpoint to continue from.
    ASSERT_TRUE(fs::exists(out));
    ASSERT_TRUE(fs::exists(ck));
    EXPECT_EQ(temp_files_in(dirs.out), std::vector<std::string>{});
    stopped = read_image_file(out);
    EXPECT_EQ(stopped->attribute("prism:stoppedBy"), name);
    const auto [k, n] = passes_of(*stopped);
    EXPECT_EQ(n, 16);
    ASSERT_GE(k, 1);
    ASSERT_LT(k, 16);
    // Every pixel has the samples of the k whole passes, or of one pass more (its tile was done).
    size_t ahead = 0;
    const std::vector<float> counts = channel_values(stopped->image, "sampleCount.Y");
    ASSERT_EQ(counts.size(), size_t(32 * 24));
    for (float count : counts) {
      ASSERT_TRUE(count == float(32 * k) || count == float(32 * (k + 1))) << count;
      ahead += count == float(32 * (k + 1));
    }
    inside_a_pass = ahead > 0;
  }
  ASSERT_TRUE(inside_a_pass) << "every signal came between passes";

  run_ok(resume_args(ck));
  const ImageFileContents resumed = read_image_file(out);
  EXPECT_EQ(resumed.attribute("prism:stoppedBy"), "-");
  EXPECT_EQ(resumed.attribute("prism:passes"), "16 of 16");
  EXPECT_TRUE(same_bits(resumed.image, read_exr_image(ref)));
}

TEST(AppResume, FirstSigintWritesImageAndCheckpointThatResume) {
  expect_first_signal_stops_and_resumes(SIGINT, "SIGINT");
}

TEST(AppResume, FirstSigtermWritesImageAndCheckpointThatResume) {
  expect_first_signal_stops_and_resumes(SIGTERM, "SIGTERM");
}

/// ThreadSanitizer builds: the `prism` runs started while this lives do not report threads that
/// finished without being joined. A second signal ends the process by _exit on purpose (nothing
/// is joined, flushed or destroyed), abandoning render workers that may have just finished their
/// share; TSan's exit-time check would call each a leak. Every race is still reported. Other
/// builds: does nothing.
class ThreadsAbandonedByExitAllowed {
 public:
  ThreadsAbandonedByExitAllowed() {
#if defined(__SANITIZE_THREAD__)
    const char* options = std::getenv("TSAN_OPTIONS");
    if (options != nullptr) saved_ = options;
    const std::string allowed = (saved_ ? *saved_ + ":" : std::string()) + "report_thread_leaks=0";
    setenv("TSAN_OPTIONS", allowed.c_str(), 1);
#endif
  }
  ~ThreadsAbandonedByExitAllowed() {
#if defined(__SANITIZE_THREAD__)
    if (saved_) {
      setenv("TSAN_OPTIONS", saved_->c_str(), 1);
    } else {
      unsetenv("TSAN_OPTIONS");
    }
#endif
  }
  ThreadsAbandonedByExitAllowed(const ThreadsAbandonedByExitAllowed&) = delete;
  ThreadsAbandonedByExitAllowed& operator=(const ThreadsAbandonedByExitAllowed&) = delete;

 private:
  [[maybe_unused]] std::optional<std::string> saved_;
};

TEST(AppResume, SecondSignalEndsAtOnceWithoutOutputOrTemporaryFiles) {
  TestDirs dirs("resume_second_signal");
  const fs::path ref = dirs.out / "ref.exr";
  run_ok(render_args(plus(signal_scene(), {"-f", ref.string()})));
  // Two different signals back to back: both are delivered (two of the same signal sent before
  // the first is handled would merge into one). Either may be handled first.
  for (const auto& [first, second] : {std::pair{SIGINT, SIGTERM}, std::pair{SIGTERM, SIGINT}}) {
    SCOPED_TRACE(std::string(first == SIGINT ? "SIGINT" : "SIGTERM") + " then " +
                 (second == SIGINT ? "SIGINT" : "SIGTERM"));
    const fs::path folder = dirs.out / std::to_string(first);
    fs::create_directories(folder);
    const fs::path out = folder / "out.exr", ck = folder / "ck.exr";
    int code = 0;
    {
      const ThreadsAbandonedByExitAllowed abandoned_threads_allowed;
      PrismProcess render(render_args(signal_render(ck, out)), dirs.root / "log.txt");
      ASSERT_TRUE(wait_for_file(ck, render)) << read_bytes(dirs.root / "log.txt");
      render.send(first);
      render.send(second);
      code = render.wait();
    }
    EXPECT_TRUE(code == 130 || code == 143) << "exit " << code;
    EXPECT_FALSE(fs::exists(out)) << "the render went on to write its image";
    EXPECT_EQ(temp_files_in(folder), std::vector<std::string>{});
    // The checkpoint left is a whole one: it still resumes to the uninterrupted image.
    run_ok(resume_args(ck));
    EXPECT_TRUE(same_bits(read_exr_image(out), read_exr_image(ref)));
  }
}

// --- SIGKILL at random moments ----------------------------------------------------------------

TEST(AppResume, KilledAtRandomMomentsAndResumedUntilDoneGivesTheUninterruptedBits) {
  TestDirs dirs("resume_kill9");
  const fs::path ref = dirs.out / "ref.exr", out = dirs.out / "out.exr", ck = dirs.out / "ck.exr";
  const fs::path log = dirs.root / "log.txt";
  const auto start = std::chrono::steady_clock::now();
  // 64 passes of 4 samples, of 1 under a sanitizer (a quarter of the work, still seconds).
  const int spp = sanitizer_share(256);
  run_ok(render_args(plus(spheres(spp), {"-f", ref.string()})));
  // The uninterrupted run's wall time, start-up included: kills come after 10% to 50% of it (or
  // from the first checkpoint on, when that comes later), so that no run from the start, nor the
  // first resume, can finish (several kills), while most runs get through a few checkpoints
  // (0.05 s apart) before they die.
  const double run_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // When a run with checkpoints writes its first: the image module that writes it loads beside
  // the first samples (color/image_io.h), which under a sanitizer is most of a short run, and a
  // run killed before it leaves nothing to resume. Kills come after it.
  double first_checkpoint_seconds = 0.0;
  {
    const fs::path probe = dirs.root / "probe_ck.exr";
    const auto probe_start = std::chrono::steady_clock::now();
    PrismProcess probe_run(
        render_args(plus(spheres(spp), {"--checkpoint", probe.string(), "--checkpoint-interval",
                                        "0.05", "-f", (dirs.root / "probe.exr").string()})),
        log);
    ASSERT_TRUE(wait_for_file(probe, probe_run)) << read_bytes(log);
    first_checkpoint_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - probe_start).count();
    ASSERT_EQ(probe_run.wait(), 0) << read_bytes(log);
  }
  const double earliest = std::max(0.1 * run_seconds, first_checkpoint_seconds);
  std::mt19937 random(184);
  std::uniform_real_distribution<double> delay(
      earliest, std::max(0.5 * run_seconds, earliest + 0.4 * (run_seconds - earliest)));

  const std::vector<std::string> fresh =
      render_args(plus(spheres(spp), {"--checkpoint", ck.string(), "--checkpoint-interval", "0.05",
                                      "-f", out.string()}));
  int kills = 0, resumes = 0;
  bool finished = false;
  // On a loaded machine every run may take longer than the first: after kKilledAttempts kills
  // the runs are left to finish, so the loop ends whatever the load (a resume is still tested).
  // Under a sanitizer, where most of a killed run is start-up, 10.
  constexpr int kKilledAttempts = sanitizer_share(40);
  for (int attempt = 0; attempt < kKilledAttempts + 20 && !finished; ++attempt) {
    const bool resume = fs::exists(ck);
    resumes += resume;
    PrismProcess render(resume ? resume_args(ck, {"--checkpoint-interval", "0.05"}) : fresh, log);
    const double seconds = attempt < kKilledAttempts ? delay(random) : 3600.0;
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::duration<double>(seconds));
    while (!render.poll() && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    if (const auto code = render.poll()) {
      ASSERT_EQ(*code, 0) << "attempt " << attempt << ": " << read_bytes(log);
      finished = true;
    } else if (const int code = render.kill_now(); code == 0) {
      finished = true;  // it finished between the last poll and the kill
    } else {
      EXPECT_EQ(code, -SIGKILL) << "attempt " << attempt << ": " << read_bytes(log);
      ++kills;
    }
  }
  ASSERT_TRUE(finished) << kills << " kills, no run finished";
  EXPECT_GE(kills, 2) << "the render was not interrupted enough to show anything";
  EXPECT_GE(resumes, 1);
  const ImageFileContents done = read_image_file(out);
  EXPECT_EQ(done.attribute("prism:passes"), "64 of 64");
  EXPECT_TRUE(same_bits(done.image, read_exr_image(ref)))
      << kills << " kills, " << resumes << " resumes";
  EXPECT_EQ(temp_files_in(dirs.out), std::vector<std::string>{}) << kills << " kills";
}

TEST(AppResume, TemporaryFilesOfKilledRunsAreRemoved) {
  // A run killed while writing its checkpoint or image leaves .<file>.prism-tmp-<pid>-<n>; the
  // next run removes those of processes that no longer run (not those of running ones), even
  // when it finishes without writing a checkpoint.
  TestDirs dirs("resume_stale");
  const fs::path out = dirs.out / "out.exr", ck = dirs.out / "ck.exr";
  run_ok(render_args(plus(spheres(64), {"-t", "1", "--time-limit", "0.02", "--checkpoint",
                                        ck.string(), "-f", out.string()})));
  ASSERT_TRUE(fs::exists(ck));
  const std::string dead = std::to_string(dead_pid());
  const std::string alive = std::to_string(getpid());
  for (const std::string& name :
       {".ck.exr.prism-tmp-" + dead + "-0", ".out.exr.prism-tmp-" + dead + "-3",
        ".ck.exr.prism-tmp-" + alive + "-1"}) {
    write_text(dirs.out / name, "partial");
  }
  run_ok(resume_args(ck));
  EXPECT_EQ(read_image_file(out).attribute("prism:passes"), "64 of 64");
  EXPECT_EQ(temp_files_in(dirs.out), std::vector<std::string>{".ck.exr.prism-tmp-" + alive + "-1"});
}

// --- Refusals and allowed options -------------------------------------------------------------

/// A JSON scene that names a mesh file: the bundled spheres plus a small triangle from an OBJ.
struct SceneWithMesh {
  std::string json, obj;
};
SceneWithMesh scene_with_mesh() {
  std::string json = read_bytes(kSpheres);
  json = replaced(json, "\"meshes\": [",
                  R"("meshes": [{"name": "extra", "material": "white", "file": "extra.obj"},)");
  return {json, "v -0.3 0.01 0.5\nv 0.3 0.01 0.5\nv 0 0.01 0.1\nf 1 2 3\n"};
}

TEST(AppResume, RefusesChangedInputsDamagedFilesAndContradictingOptions) {
  TestDirs dirs("resume_refusals");
  const SceneWithMesh original = scene_with_mesh();
  const std::string scene = dirs.scene("scene.json", original.json);
  dirs.scene("extra.obj", original.obj);
  const fs::path ref = dirs.root / "ref.exr", out = dirs.out / "out.exr", ck = dirs.out / "ck.exr";
  run_ok(render_args(plus(spheres(64, scene), {"-f", ref.string()})));
  run_ok(render_args(plus(spheres(64, scene), {"-t", "1", "--time-limit", "0.02", "--checkpoint",
                                               ck.string(), "-f", out.string()})));
  ASSERT_TRUE(fs::exists(ck));
  ASSERT_EQ(read_image_file(out).attribute("prism:stoppedBy"), "time limit");

  // Damaged and foreign files beside the checkpoint.
  const std::string bytes = read_bytes(ck);
  write_bytes(dirs.out / "truncated.exr", bytes.substr(0, bytes.size() / 2));
  std::string flipped = bytes;
  for (size_t i = 0; i < 8; ++i) flipped[bytes.size() / 2 + i] ^= char(0x5a);
  write_bytes(dirs.out / "flipped.exr", flipped);

  const auto expect_refused = [&](const std::vector<std::string>& args,
                                  const std::vector<std::string>& mentions) {
    const auto before = snapshot(dirs.out);
    expect_one_line_error(run_prism(args), 2, mentions);
    EXPECT_TRUE(snapshot(dirs.out) == before) << "a refused resume changed the output folder";
  };
  {
    SCOPED_TRACE("scene file changed");
    dirs.scene("scene.json", replaced(original.json, "[0.6, 0.2, 0.2]", "[0.6, 0.2, 0.25]"));
    expect_refused(resume_args(ck), {"ck.exr", "scene", "changed"});
    dirs.scene("scene.json", original.json);
  }
  {
    SCOPED_TRACE("mesh file changed");
    dirs.scene("extra.obj", replaced(original.obj, "v 0 0.01 0.1", "v 0 0.01 0.2"));
    expect_refused(resume_args(ck), {"ck.exr", "scene", "changed"});
    dirs.scene("extra.obj", original.obj);
  }
  {
    SCOPED_TRACE("truncated checkpoint");
    expect_refused(resume_args(dirs.out / "truncated.exr"), {"truncated.exr"});
  }
  {
    SCOPED_TRACE("flipped bytes in the middle");
    expect_refused(resume_args(dirs.out / "flipped.exr"), {"flipped.exr"});
  }
  {
    SCOPED_TRACE("an image that is not a checkpoint");
    expect_refused(resume_args(out), {"out.exr", "render state"});
  }
  {
    SCOPED_TRACE("missing file");
    expect_refused(resume_args(dirs.out / "missing.exr"), {"missing.exr"});
  }
  {
    SCOPED_TRACE("contradicting options");
    expect_refused(resume_args(ck, {"-s", "16"}), {"ck.exr", "spp", "16", "64"});
    expect_refused(resume_args(ck, {"-r", "32", "24"}), {"ck.exr", "resolution"});
    expect_refused(resume_args(ck, {"--seed", "7"}), {"ck.exr", "seed"});
  }

  // The inputs as they were, and only run controls given (-q too: resume_args gives it): it
  // resumes, to the same bits.
  run_ok(resume_args(ck, {"-t", "1", "--time-limit", "1000"}));
  const ImageFileContents resumed = read_image_file(out);
  EXPECT_EQ(resumed.attribute("prism:passes"), "64 of 64");
  EXPECT_TRUE(same_bits(resumed.image, read_exr_image(ref)));
}

TEST(AppResume, ACheckpointOfACropResumesIntoTheCrop) {
  TestDirs dirs("resume_crop");
  const fs::path ref = dirs.out / "ref.exr", out = dirs.out / "crop.exr", ck = dirs.out / "ck.exr";
  run_ok(render_args(plus(spheres(128), {"-f", ref.string()})));
  // Not on the tile grid: 32 x 31 pixels from (13, 7).
  run_ok(
      render_args(plus(spheres(128), {"--crop", "13", "7", "45", "38", "-t", "1", "--time-limit",
                                      "0.02", "--checkpoint", ck.string(), "-f", out.string()})));
  ASSERT_EQ(read_image_file(out).attribute("prism:stoppedBy"), "time limit");
  run_ok(resume_args(ck, {"-t", "1"}));
  const ImageFileContents crop = read_image_file(out);
  EXPECT_EQ(crop.attribute("prism:crop"), "13 7 45 38");
  EXPECT_EQ(crop.attribute("prism:passes"), "64 of 64");
  EXPECT_EQ(crop.image.x, 13);
  EXPECT_EQ(crop.image.y, 7);
  EXPECT_EQ(crop.image.width, 32);
  EXPECT_EQ(crop.image.height, 31);
  EXPECT_EQ(crop.image.full_width, 64);
  EXPECT_EQ(crop.image.full_height, 48);
  EXPECT_TRUE(same_bits_in(crop.image, read_exr_image(ref)));
}

}  // namespace
}  // namespace prism::test
