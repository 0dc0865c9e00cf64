// The hostile-input corpus (tests/hostile/cases.json): every case is a file or a command line
// that prism must refuse with its documented exit code (2: bad command line or input, 3: output
// or memory), one line on stderr naming the file (and line or element), no output file and no
// temporary file left behind, no signal, in well under 2 s of CPU time. One test per case:
// Corpus/AppHostileInputs.Case/<id>.

#include <gtest/gtest.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <ostream>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "tests/support/app_test_helpers.h"
#include "tests/support/child_process.h"
#include "tests/support/test_support.h"

namespace prism::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// Every run of prism must end within this much CPU time (the issue's bound). Wall time is
/// measured and bounded more loosely (kMaxWallSeconds), since other jobs share the machine.
constexpr double kMaxCpuSeconds = 2.0;
constexpr double kMaxWallSeconds = 10.0;
/// The kill timeout: a case that hangs fails here.
constexpr int kTimeoutSeconds = 30;

/// The CPU time a case may take: kMaxCpuSeconds, and in a sanitizer build also what starting
/// the instrumented prism costs by itself (`prism --version`, measured once per process, half
/// as much again for the noise of one measurement), so that the bound stays on prism's own work:
/// ASan's start-up and exit scan alone take ~0.7 s on a quiet machine. One run, not the most of
/// three: every ctest group of these tests pays it, 18 groups under ASan. The normal build keeps
/// the plain bound, start-up included.
double max_cpu_seconds() {
  if constexpr (kSanitizedBuild) {
    static const double start_up = [] {
      const TimedProgramResult version = run_prism_limited({"--version"}, {}, kTimeoutSeconds);
      EXPECT_EQ(version.result.exit_code, 0) << version.result.err;
      return version.cpu_seconds;
    }();
    return kMaxCpuSeconds + 1.5 * start_up;
  }
  return kMaxCpuSeconds;
}

const fs::path kCorpus = fs::path(PRISM_SOURCE_DIR) / "tests" / "hostile";

/// One row of cases.json.
struct HostileCase {
  std::string id;
  json row;
};

/// How GoogleTest prints a case (its id, not its bytes).
void PrintTo(const HostileCase& c, std::ostream* os) { *os << c.id; }

std::vector<HostileCase> load_cases() {
  std::ifstream in(kCorpus / "cases.json");
  const json table = json::parse(in);
  std::vector<HostileCase> cases;
  for (const json& row : table.at("cases")) cases.push_back({row.at("id").get<std::string>(), row});
  return cases;
}

/// `text` with the placeholders of cases.json replaced: {hostile}, {in}, {out}, {nonutf8},
/// {rep:N:TEXT}.
std::string expand(std::string text, const TestDirs& dirs) {
  static const std::regex rep(R"(\{rep:(\d+):([^}]*)\})");
  std::smatch m;
  while (std::regex_search(text, m, rep)) {
    std::string repeated;
    for (int i = 0; i < std::stoi(m[1].str()); ++i) repeated += m[2].str();
    text.replace(size_t(m.position(0)), size_t(m.length(0)), repeated);
  }
  const std::pair<std::string, std::string> fixed[] = {{"{hostile}", kCorpus.string()},
                                                       {"{in}", dirs.in.string()},
                                                       {"{out}", dirs.out.string()},
                                                       {"{nonutf8}", "\xff\xfe"}};
  for (const auto& [from, to] : fixed) {
    for (size_t at = text.find(from); at != std::string::npos;
         at = text.find(from, at + to.size())) {
      text.replace(at, from.size(), to);
    }
  }
  return text;
}

/// Runs the setup steps of a case: files to write, copy, truncate, render, folders to make and
/// permissions to set. A step that fails fails the test.
void run_setup(const json& steps, const TestDirs& dirs) {
  for (const json& step : steps) {
    if (step.contains("write")) {
      std::string text;
      for (const json& part : step.at("parts")) {
        if (part.contains("text")) text += part.at("text").get<std::string>();
        for (int i = 0; i < part.value("count", 0); ++i)
          text += part.at("repeat").get<std::string>();
      }
      write_text(expand(step.at("write"), dirs), text);
    } else if (step.contains("copy")) {
      fs::copy_file(expand(step.at("copy"), dirs), expand(step.at("to"), dirs));
    } else if (step.contains("mkdir")) {
      fs::create_directories(expand(step.at("mkdir"), dirs));
    } else if (step.contains("chmod")) {
      fs::permissions(expand(step.at("chmod"), dirs), fs::perms(step.at("mode").get<int>()));
    } else if (step.contains("truncate")) {
      const fs::path file = expand(step.at("truncate"), dirs);
      fs::resize_file(file, uintmax_t(double(fs::file_size(file)) * step.at("keep").get<double>()));
    } else if (step.contains("render")) {
      std::vector<std::string> args;
      for (const json& a : step.at("render")) args.push_back(expand(a, dirs));
      const ProgramResult r = run_prism(args);
      ASSERT_EQ(r.exit_code, 0) << "setup render failed: " << r.err;
    } else {
      FAIL() << "unknown setup step " << step.dump();
    }
  }
}

/// Every file under `root` (recursively) whose name marks a temporary file of the writers.
std::vector<std::string> temporary_files(const fs::path& root) {
  std::vector<std::string> found;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(root, ec); !ec && it != fs::end(it);
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.find(".prism-tmp") != std::string::npos || name.find(".tmp") != std::string::npos) {
      found.push_back(it->path().string());
    }
  }
  return found;
}

/// The slowest runs, printed once at the end of the suite (and the measurements of the report
/// in docs/RELIABILITY.md).
struct Timings {
  std::mutex mutex;
  std::map<std::string, std::pair<double, double>> by_case;  // id -> wall, cpu seconds
};
Timings& timings() {
  static Timings t;
  return t;
}

class AppHostileInputs : public ::testing::TestWithParam<HostileCase> {
 public:
  static void TearDownTestSuite() {
    auto& t = timings();
    const std::lock_guard lock(t.mutex);
    if (t.by_case.empty()) return;
    double max_wall = 0.0, max_cpu = 0.0;
    std::string slowest;
    for (const auto& [id, seconds] : t.by_case) {
      if (seconds.first > max_wall) slowest = id;
      max_wall = std::max(max_wall, seconds.first);
      max_cpu = std::max(max_cpu, seconds.second);
    }
    std::printf("hostile inputs: %zu cases, slowest wall %.3f s (%s), max CPU %.3f s\n",
                t.by_case.size(), max_wall, slowest.c_str(), max_cpu);
  }
};

TEST_P(AppHostileInputs, Case) {
  const json& row = GetParam().row;
  SCOPED_TRACE(row.dump());
  const TestDirs dirs("hostile_" + GetParam().id);
  ProcessLimits limits;
  limits.drop_root = row.value("drop_root", false);
  if (limits.drop_root && geteuid() == 0) {
    // The folders of the case are the user's that prism runs as (the setup may restrict them).
    fs::permissions(dirs.root, fs::perms::others_read | fs::perms::others_exec,
                    fs::perm_options::add);
    fs::permissions(dirs.in, fs::perms::all);
    fs::permissions(dirs.out, fs::perms::all);
  }
  if (row.contains("setup")) run_setup(row.at("setup"), dirs);
  if (::testing::Test::HasFatalFailure()) return;
  if (row.contains("limits")) {
    const json& l = row.at("limits");
    limits.address_space_bytes = l.value("address_space_mb", 0ull) << 20;
    limits.file_size_bytes = l.value("file_size_bytes", 0ull);
  }
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer reserves terabytes of address space for its shadow memory at start-up, so
  // no `ulimit -v` a scene could exceed lets an instrumented prism start at all.
  if (limits.address_space_bytes != 0) {
    GTEST_SKIP() << "a memory limit (RLIMIT_AS) cannot apply to an AddressSanitizer build";
  }
#endif

  std::vector<std::string> args;
  if (row.contains("scene")) {
    args = {
        "render", expand(row.at("scene"), dirs),    "-r", "32", "24", "-s", "1", "-t", "1", "-q",
        "-f",     (dirs.out / "image.exr").string()};
    for (const json& a : row.value("extra", json::array())) args.push_back(expand(a, dirs));
  } else {
    for (const json& a : row.at("args")) args.push_back(expand(a, dirs));
  }
  std::vector<std::string> mentions;
  for (const json& m : row.at("mentions")) mentions.push_back(expand(m, dirs));
  std::map<fs::path, std::string> unchanged;
  for (const json& f : row.value("unchanged", json::array())) {
    const fs::path path = expand(f, dirs);
    unchanged[path] = read_bytes(path);
  }
  const std::vector<std::string> out_before = dir_entries(dirs.out);
  const std::vector<std::string> in_before = dir_entries(dirs.in);

  const TimedProgramResult timed = run_prism_limited(args, limits, kTimeoutSeconds);
  const ProgramResult& r = timed.result;
  {
    auto& t = timings();
    const std::lock_guard lock(t.mutex);
    t.by_case[GetParam().id] = {timed.wall_seconds, timed.cpu_seconds};
  }
  std::printf("hostile case %s: exit %d, wall %.3f s, CPU %.3f s\n", GetParam().id.c_str(),
              r.exit_code, timed.wall_seconds, timed.cpu_seconds);

  ASSERT_NE(r.exit_code, 126) << "could not apply the limits of the case";
  // Exit code, one line "prism: error: ..." naming the file (and line or element); so also no
  // sanitizer report and no crash (a signal gives a negative exit code).
  expect_one_line_error(r, row.at("exit").get<int>(), mentions);
  EXPECT_EQ(r.err.find("Sanitizer"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "") << "a refused run prints nothing on stdout";
  // Nothing written: the output folder and the input folder hold what they held before, and no
  // temporary file is left anywhere in the case's folders.
  std::error_code ec;
  fs::permissions(dirs.out, fs::perms::owner_all, fs::perm_options::add, ec);
  EXPECT_EQ(dir_entries(dirs.out), out_before) << "files left in the output folder";
  EXPECT_EQ(dir_entries(dirs.in), in_before) << "files left in the input folder";
  EXPECT_EQ(temporary_files(dirs.root), std::vector<std::string>{});
  for (const auto& [path, bytes] : unchanged) {
    EXPECT_TRUE(read_bytes(path) == bytes) << path << " was changed";
  }
  EXPECT_LT(timed.cpu_seconds, max_cpu_seconds()) << "CPU seconds";
  EXPECT_LT(timed.wall_seconds, kMaxWallSeconds) << "wall seconds";
}

std::string case_name(const ::testing::TestParamInfo<HostileCase>& info) { return info.param.id; }

INSTANTIATE_TEST_SUITE_P(Corpus, AppHostileInputs, ::testing::ValuesIn(load_cases()), case_name);

TEST(AppHostileInputs, CorpusCoversEveryCategory) {
  // The issue's list: at least 60 cases, and every category present.
  const std::vector<HostileCase> cases = load_cases();
  EXPECT_GE(cases.size(), 60u);
  std::map<std::string, int> per_category;
  std::set<std::string> ids;
  for (const auto& c : cases) {
    ++per_category[c.row.at("category").get<std::string>()];
    EXPECT_TRUE(ids.insert(c.id).second) << "duplicate case id " << c.id;
    const int code = c.row.at("exit").get<int>();
    EXPECT_TRUE(code == 2 || code == 3) << c.id;
  }
  for (const char* category :
       {"empty and truncated files", "wrong types", "NaN, Inf, 1e39 and denormals",
        "negative or absurd sizes and counts", "deep nesting", "cyclic references",
        "XML entity expansion", "duplicate ids", "missing and dangling references",
        "binary garbage", "non-UTF-8 and very long paths", "unwritable output", "memory limit"}) {
    EXPECT_GT(per_category[category], 0) << category;
  }
}

}  // namespace
}  // namespace prism::test
