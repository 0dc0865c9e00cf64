#pragma once

#include <atomic>

namespace prism {

/// SIGINT and SIGTERM during a render, while alive: the first signal stores its number in
/// stop_signal(), so the render stops after the tiles in flight and writes what it has (and its
/// checkpoint); a second signal ends the process with interrupted_exit_code() as soon as the files
/// being written are finished (stop_file_writes(); a write is one image, milliseconds), starting
/// no other, so no partial or temporary file is left. The signals are acted on by a thread of its
/// own, which the handler wakes through a pipe: a signal landing on a thread that is writing or
/// holds a lock changes nothing there. The previous handlers come back when it is destroyed. One
/// alive at a time.
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

/// "SIGINT", "SIGTERM", or "a signal".
const char* signal_name(int signal);

}  // namespace prism
