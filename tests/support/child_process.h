#pragma once

#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace prism::test {

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
