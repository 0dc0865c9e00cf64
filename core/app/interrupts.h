#pragma once

#include <atomic>

namespace prism {

/// SIGINT and SIGTERM during a render, while alive: the first signal stores its number in
/// stop_signal(), so the render stops after the tiles in flight and writes what it has (and its
/// checkpoint); a second signal deletes the temporary files being written
/// (remove_pending_temp_files()) and ends the process at once with interrupted_exit_code(), so
/// no partial file is left. The previous handlers come back when it is destroyed.
class InterruptHandlers {
 public:
  InterruptHandlers();
  ~InterruptHandlers();
  InterruptHandlers(const InterruptHandlers&) = delete;
  InterruptHandlers& operator=(const InterruptHandlers&) = delete;

  /// 0 until the first signal, then its number.
  const std::atomic<int>& stop_signal() const;
};

/// The exit code of a render stopped by `signal`: 128 + signal (130 for SIGINT, 143 for
/// SIGTERM), as shells report a process killed by it.
inline int interrupted_exit_code(int signal) { return 128 + signal; }

/// "SIGINT", "SIGTERM", or "signal N".
const char* signal_name(int signal);

}  // namespace prism
