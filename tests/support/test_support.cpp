#include "tests/support/test_support.h"

#include "tests/support/child_process.h"

#include <fcntl.h>
#include <grp.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iterator>
#include <random>
#include <stdexcept>

namespace prism::test {

std::optional<std::filesystem::path> cs184_scene_dir() {
  const std::filesystem::path dir = std::filesystem::path(PRISM_SHARED_DIR) / "scenes" / "cs184";
  if (std::filesystem::is_directory(dir)) return dir;
  return std::nullopt;
}

std::optional<std::filesystem::path> cs184_scene(const std::string& file_name) {
  const auto dir = cs184_scene_dir();
  if (!dir || !std::filesystem::exists(*dir / file_name)) return std::nullopt;
  return *dir / file_name;
}

std::vector<std::string> cs184_scene_names() {
  std::vector<std::string> names;
  if (const auto dir = cs184_scene_dir()) {
    for (const auto& e : std::filesystem::directory_iterator(*dir)) {
      if (e.path().extension() == ".dae") names.push_back(e.path().filename().string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::filesystem::path make_temp_dir(const std::string& tag) {
  std::random_device rd;
  const auto dir =
      std::filesystem::temp_directory_path() /
      ("prism_test_" + tag + "_" + std::to_string(getpid()) + "_" + std::to_string(rd()));
  std::filesystem::create_directories(dir);
  return dir;
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

ProgramResult run_prism(const std::vector<std::string>& args, int timeout_seconds) {
  return run_prism_limited(args, ProcessLimits{}, timeout_seconds).result;
}

TimedProgramResult run_prism_limited(const std::vector<std::string>& args,
                                     const ProcessLimits& limits, int timeout_seconds) {
  int out_pipe[2], err_pipe[2];
  if (pipe(out_pipe) != 0 || pipe(err_pipe) != 0) throw std::runtime_error("pipe failed");
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    dup2(out_pipe[1], STDOUT_FILENO);
    dup2(err_pipe[1], STDERR_FILENO);
    close(out_pipe[0]);
    close(err_pipe[0]);
    if (limits.drop_root && geteuid() == 0) {
      if (setgroups(0, nullptr) != 0 || setgid(65534) != 0 || setuid(65534) != 0) _exit(126);
    }
    if (limits.file_size_bytes > 0) {
      signal(SIGXFSZ, SIG_IGN);  // kept across exec: writes fail with EFBIG instead
      const rlimit r{limits.file_size_bytes, limits.file_size_bytes};
      if (setrlimit(RLIMIT_FSIZE, &r) != 0) _exit(126);
    }
    if (limits.address_space_bytes > 0) {
      const rlimit r{limits.address_space_bytes, limits.address_space_bytes};
      if (setrlimit(RLIMIT_AS, &r) != 0) _exit(126);
    }
    std::vector<char*> argv;
    std::string program = limits.program.empty() ? std::string(PRISM_BINARY) : limits.program;
    argv.push_back(program.data());
    std::vector<std::string> copy = args;
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(program.c_str(), argv.data());
    _exit(127);
  }
  close(out_pipe[1]);
  close(err_pipe[1]);
  TimedProgramResult timed;
  ProgramResult& result = timed.result;
  pollfd fds[2] = {{out_pipe[0], POLLIN, 0}, {err_pipe[0], POLLIN, 0}};
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeout_seconds);
  int open_fds = 2;
  bool killed = false;
  char buf[4096];
  while (open_fds > 0) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                          deadline - std::chrono::steady_clock::now())
                          .count();
    if (left <= 0) {
      kill(pid, SIGKILL);
      killed = true;
      break;
    }
    if (poll(fds, 2, static_cast<int>(std::min<long long>(left, 1000))) < 0) break;
    for (int i = 0; i < 2; ++i) {
      if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP))) continue;
      const ssize_t n = read(fds[i].fd, buf, sizeof buf);
      if (n <= 0) {
        close(fds[i].fd);
        fds[i].fd = -1;
        --open_fds;
      } else {
        (i == 0 ? result.out : result.err).append(buf, size_t(n));
      }
    }
  }
  for (auto& f : fds) {
    if (f.fd >= 0) close(f.fd);
  }
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  timed.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  timed.cpu_seconds = double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                      1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  if (killed) {
    result.exit_code = -9;
  } else if (WIFEXITED(status)) {
    result.exit_code = WEXITSTATUS(status);
  } else {
    result.exit_code = -WTERMSIG(status);
  }
  // In sanitizer builds the program is instrumented too (docs/RELIABILITY.md): its reports fail
  // the test, whatever exit code the test expected.
  for (const char* marker :
       {"ERROR: AddressSanitizer", "ERROR: LeakSanitizer", "WARNING: ThreadSanitizer",
        "ThreadSanitizer: ", "runtime error: ", "SUMMARY: UndefinedBehaviorSanitizer"}) {
    if (result.err.find(marker) != std::string::npos) {
      std::string command = "prism";
      for (const std::string& a : args) command += " " + a;
      ADD_FAILURE() << "sanitizer report from `" << command << "`:\n" << result.err;
      break;
    }
  }
  return timed;
}

}  // namespace prism::test
