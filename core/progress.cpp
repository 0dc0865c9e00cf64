#include "core/progress.h"

#include <unistd.h>

#include <cstdio>

namespace prism {

std::string format_duration(double seconds) {
  char buf[32];
  if (seconds < 60.0) {
    std::snprintf(buf, sizeof buf, "%.1fs", seconds);
  } else if (seconds < 3600.0) {
    std::snprintf(buf, sizeof buf, "%dm%02ds", int(seconds) / 60, int(seconds) % 60);
  } else {
    std::snprintf(buf, sizeof buf, "%dh%02dm", int(seconds) / 3600, (int(seconds) / 60) % 60);
  }
  return buf;
}

ProgressReporter::ProgressReporter(std::string label, uint64_t total_work, bool quiet,
                                   double interval_seconds)
    : label_(std::move(label)),
      total_(total_work > 0 ? total_work : 1),
      quiet_(quiet),
      terminal_(isatty(STDERR_FILENO) != 0),
      interval_(terminal_ ? 0.1 : interval_seconds),
      start_(std::chrono::steady_clock::now()) {}

ProgressReporter::~ProgressReporter() {
  if (terminal_ && !quiet_ && !finished_.load() && last_print_ >= 0.0) std::fputc('\n', stderr);
}

double ProgressReporter::elapsed_seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void ProgressReporter::update(uint64_t work_done) {
  const uint64_t now_done = done_.fetch_add(work_done, std::memory_order_relaxed) + work_done;
  if (quiet_) return;
  const double t = elapsed_seconds();
  if (t - last_print_ < interval_) return;  // racy read is fine: only rate-limits printing
  std::unique_lock lock(print_mutex_, std::try_to_lock);
  if (!lock.owns_lock() || t - last_print_ < interval_ || finished_.load()) return;
  last_print_ = t;
  print(now_done, false);
}

void ProgressReporter::done() {
  if (finished_.exchange(true)) return;
  if (quiet_) return;
  std::lock_guard lock(print_mutex_);
  print(total_, true);
}

void ProgressReporter::print(uint64_t done_work, bool final) {
  const double fraction = std::min(1.0, double(done_work) / double(total_));
  const double t = elapsed_seconds();
  const double eta = fraction > 0.0 ? t * (1.0 - fraction) / fraction : 0.0;
  if (terminal_) {
    constexpr int kWidth = 30;
    const int filled = int(fraction * kWidth);
    std::string bar(filled, '#');
    bar.append(kWidth - filled, '-');
    if (final) {
      std::fprintf(stderr, "\r%s [%s] 100%% %s        \n", label_.c_str(), bar.c_str(),
                   format_duration(t).c_str());
    } else {
      std::fprintf(stderr, "\r%s [%s] %3d%% %s, ETA %s   ", label_.c_str(), bar.c_str(),
                   int(fraction * 100.0), format_duration(t).c_str(), format_duration(eta).c_str());
    }
  } else if (final) {
    std::fprintf(stderr, "%s: 100%% done in %s\n", label_.c_str(), format_duration(t).c_str());
  } else if (t >= interval_) {
    std::fprintf(stderr, "%s: %d%% after %s, ETA %s\n", label_.c_str(), int(fraction * 100.0),
                 format_duration(t).c_str(), format_duration(eta).c_str());
  }
  std::fflush(stderr);
}

}  // namespace prism
