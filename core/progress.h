#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace prism {

/// Reports progress of long work on stderr: a redrawn bar with percentage and ETA when stderr is
/// a terminal, otherwise one plain line at most every `interval_seconds`. update() is
/// thread-safe and cheap (an atomic add; printing is rate-limited). Quiet reporters print
/// nothing.
class ProgressReporter {
 public:
  ProgressReporter(std::string label, uint64_t total_work, bool quiet,
                   double interval_seconds = 10.0);
  ~ProgressReporter();
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;

  void update(uint64_t work_done = 1);
  /// Prints the final state (100%, elapsed time) once.
  void done();
  double elapsed_seconds() const;

 private:
  void print(uint64_t done_work, bool final);

  std::string label_;
  uint64_t total_;
  bool quiet_;
  bool terminal_;
  double interval_;
  std::atomic<uint64_t> done_{0};
  std::atomic<bool> finished_{false};
  std::chrono::steady_clock::time_point start_;
  std::mutex print_mutex_;
  double last_print_ = -1.0;
};

/// "1h02m", "3m05s", "4.2s".
std::string format_duration(double seconds);

}  // namespace prism
