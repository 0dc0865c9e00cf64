#pragma once

#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tests/support/test_support.h"

namespace prism::test {

/// Limits applied to the prism process (in the child, before exec) by run_prism_limited, and
/// which program that is.
struct ProcessLimits {
  /// RLIMIT_AS in bytes, as `ulimit -v` sets it; 0: unchanged.
  unsigned long long address_space_bytes = 0;
  /// RLIMIT_FSIZE in bytes; 0: unchanged. SIGXFSZ is ignored, so a write past the limit fails
  /// with EFBIG as a write to a full filesystem fails with ENOSPC.
  unsigned long long file_size_bytes = 0;
  /// When the tests run as root, run prism as user and group 65534 (nobody), so that permission
  /// bits (a read-only folder, an unreadable file) apply to it. No effect for other users.
  bool drop_root = false;
  /// The program to run instead of the built prism (a copy of it elsewhere); empty: the built one.
  std::string program = {};
};

/// What run_prism_limited measured besides run_prism's result.
struct TimedProgramResult {
  ProgramResult result;
  double wall_seconds = 0.0;  ///< from fork to the end of the process
  double cpu_seconds = 0.0;   ///< user + system time of the process
};

/// Ends the child process of a death test: exit code 0 when `ok`, else 1 after saying why on
/// stderr (with _exit: a child that forked from a test must not run the test's teardown).
[[noreturn]] void finish_child(bool ok, const std::string& why);

/// run_prism (test_support.h) with `limits` applied to the program, timed. Setting a limit that
/// fails, or dropping root, makes the child exit with 126 before prism runs.
TimedProgramResult run_prism_limited(const std::vector<std::string>& args,
                                     const ProcessLimits& limits, int timeout_seconds = 120);

/// The built prism program running in the background, for tests that signal or kill it while
/// it works (run_prism() waits for the end). Its stdout and stderr go to `log` (appended; none:
/// /dev/null). Destroyed while running, it is killed with SIGKILL and reaped, so a failing test
/// leaves no process behind.
class PrismProcess {
 public:
  explicit PrismProcess(const std::vector<std::string>& args,
                        const std::filesystem::path& log = {});
  ~PrismProcess();
  PrismProcess(const PrismProcess&) = delete;
  PrismProcess& operator=(const PrismProcess&) = delete;

  pid_t pid() const { return pid_; }
  /// Sends `signal` to the process (nothing once it has been reaped).
  void send(int signal) const;
  /// The exit status once the process has ended (reaping it), else nothing; does not wait.
  std::optional<int> poll();
  /// Waits for the end, at most `timeout_seconds` (then kills it with SIGKILL). The exit code,
  /// or minus the signal that ended it (-9 after the timeout), as run_prism() reports them.
  int wait(double timeout_seconds = 120.0);
  /// Kills it with SIGKILL and reaps it; the status as wait() gives it.
  int kill_now();

 private:
  pid_t pid_ = -1;
  std::optional<int> status_;
};

/// Waits until `path` exists or `process` ends or `timeout_seconds` pass, polling every
/// millisecond; whether the file exists.
bool wait_for_file(const std::filesystem::path& path, PrismProcess& process,
                   double timeout_seconds = 60.0);

/// The names of the entries of `dir` whose name contains ".prism-tmp" (the atomic writers'
/// temporary files), sorted.
std::vector<std::string> temp_files_in(const std::filesystem::path& dir);

/// A process id that belongs to no running process: the id of a child that has ended and been
/// reaped (the kernel reuses ids only after the id space wraps around).
pid_t dead_pid();

}  // namespace prism::test
