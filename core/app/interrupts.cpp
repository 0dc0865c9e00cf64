#include "core/app/interrupts.h"

#include <fcntl.h>
#include <pthread.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <thread>

#include "core/atomic_file.h"
#include "core/error.h"

namespace prism {
namespace {

std::atomic<int> received_signal{0};
struct sigaction previous_int, previous_term;

/// The handler's only job: pass the signal to the thread that acts on it, through a pipe (write()
/// is async-signal-safe; whatever the interrupted thread held stays untouched).
int signal_pipe[2] = {-1, -1};
constexpr unsigned char kQuit = 0;  // not a signal number: asks the acting thread to end

/// How long a second signal waits for files being written to be finished or removed. Writes are
/// one image each (milliseconds); the limit only matters for a stalled disk.
constexpr std::chrono::milliseconds kWritesInFlightTimeout{2000};

void on_signal(int signal) {
  const int saved_errno = errno;
  const unsigned char byte = static_cast<unsigned char>(signal);
  [[maybe_unused]] const ssize_t written = ::write(signal_pipe[1], &byte, 1);
  errno = saved_errno;
}

/// Runs on its own thread, which holds no lock when a signal comes: the first signal is stored for
/// the render to see; the second lets the files being written finish (or removes them after
/// kWritesInFlightTimeout), keeps any other write from starting, and ends the process.
void act_on_signals() {
  for (;;) {
    unsigned char byte = kQuit;
    const ssize_t got = ::read(signal_pipe[0], &byte, 1);
    if (got < 0 && errno == EINTR) continue;
    if (got != 1 || byte == kQuit) return;
    const int signal = byte;
    int expected = 0;
    if (received_signal.compare_exchange_strong(expected, signal)) continue;
    stop_file_writes(kWritesInFlightTimeout);
    _exit(interrupted_exit_code(signal));
  }
}

std::thread signal_thread;

}  // namespace

InterruptHandlers::InterruptHandlers() {
  PRISM_CHECK(!signal_thread.joinable());  // one alive at a time
  received_signal.store(0);
  if (::pipe2(signal_pipe, O_CLOEXEC) != 0) {
    std::perror("prism: cannot set up the SIGINT/SIGTERM handling (pipe)");
    return;  // the signals keep their default effect: ending the process
  }
  // The acting thread never receives SIGINT or SIGTERM itself (it starts with them blocked):
  // a handler that interrupts it while it waits for the pipe would wait for itself where the
  // handler is deferred to the next safe point, as ThreadSanitizer's are.
  sigset_t interrupt_signals, previous_mask;
  sigemptyset(&interrupt_signals);
  sigaddset(&interrupt_signals, SIGINT);
  sigaddset(&interrupt_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &interrupt_signals, &previous_mask);
  signal_thread = std::thread(act_on_signals);
  pthread_sigmask(SIG_SETMASK, &previous_mask, nullptr);
  struct sigaction action {};
  action.sa_handler = &on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, &previous_int);
  sigaction(SIGTERM, &action, &previous_term);
}

InterruptHandlers::~InterruptHandlers() {
  if (!signal_thread.joinable()) return;
  sigaction(SIGINT, &previous_int, nullptr);
  sigaction(SIGTERM, &previous_term, nullptr);
  // A signal that came before the handlers went back is still in the pipe, ahead of kQuit.
  [[maybe_unused]] const ssize_t written = ::write(signal_pipe[1], &kQuit, 1);
  signal_thread.join();
  ::close(signal_pipe[0]);
  ::close(signal_pipe[1]);
  signal_pipe[0] = signal_pipe[1] = -1;
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
