#include "core/app/interrupts.h"

#include <unistd.h>

#include <csignal>

#include "core/atomic_file.h"

namespace prism {
namespace {

std::atomic<int> received_signal{0};
struct sigaction previous_int, previous_term;

void on_signal(int signal) {
  int expected = 0;
  if (received_signal.compare_exchange_strong(expected, signal)) return;
  // The second signal: stop now, leaving nothing half-written (only async-signal-safe calls).
  remove_pending_temp_files();
  _exit(interrupted_exit_code(signal));
}

}  // namespace

InterruptHandlers::InterruptHandlers() {
  received_signal.store(0);
  struct sigaction action {};
  action.sa_handler = &on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, &previous_int);
  sigaction(SIGTERM, &action, &previous_term);
}

InterruptHandlers::~InterruptHandlers() {
  sigaction(SIGINT, &previous_int, nullptr);
  sigaction(SIGTERM, &previous_term, nullptr);
}

const std::atomic<int>& InterruptHandlers::stop_signal() const { return received_signal; }

const char* signal_name(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    default:
      return "a signal";
  }
}

}  // namespace prism
