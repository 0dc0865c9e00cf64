#include "core/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <condition_variable>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <vector>

#include "core/error.h"

namespace prism {
namespace fs = std::filesystem;
namespace {

/// Writes in flight (alive AtomicFiles and writability probes, by temporary path), and whether
/// new ones may start. stop_file_writes() closes it and waits for it to empty: with no write able
/// to create a file afterwards, the process can end without leaving one, whichever thread is
/// writing.
struct WriteGate {
  std::mutex mutex;
  std::condition_variable emptied;
  std::vector<fs::path> in_flight;
  bool closed = false;
};
WriteGate write_gate;

/// Counts a write of `temp` in flight; blocks for good once the gate is closed (the process is
/// about to exit).
void start_write(const fs::path& temp) {
  std::unique_lock lock(write_gate.mutex);
  write_gate.emptied.wait(lock, [] { return !write_gate.closed; });
  write_gate.in_flight.push_back(temp);
}

void finish_write(const fs::path& temp) {
  const std::lock_guard lock(write_gate.mutex);
  auto& paths = write_gate.in_flight;
  paths.erase(std::find(paths.begin(), paths.end(), temp));
  if (paths.empty()) write_gate.emptied.notify_all();
}

/// A write of `temp` in flight for as long as it lives (the writability probe's).
class ProbeInFlight {
 public:
  explicit ProbeInFlight(const fs::path& temp) : temp_(temp) { start_write(temp_); }
  ~ProbeInFlight() { finish_write(temp_); }
  ProbeInFlight(const ProbeInFlight&) = delete;
  ProbeInFlight& operator=(const ProbeInFlight&) = delete;

 private:
  fs::path temp_;
};

fs::path folder_of(const fs::path& path) {
  return path.has_parent_path() ? path.parent_path() : fs::path(".");
}

fs::path temp_path_for(const fs::path& target) {
  static std::atomic<unsigned> counter{0};
  std::string name = ".";
  name += target.filename().string();
  name += ".prism-tmp-" + std::to_string(getpid()) + "-" + std::to_string(counter++);
  return folder_of(target) / name;
}

/// Removes the temporary files of `target` that processes no longer running left behind (a
/// process killed with SIGKILL cannot remove its own).
void remove_stale_temp_files(const fs::path& target) {
  const std::string prefix = "." + target.filename().string() + ".prism-tmp-";
  std::error_code ec;
  for (fs::directory_iterator it(folder_of(target), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string rest = name.substr(prefix.size());
    const size_t dash = rest.find('-');
    if (dash == 0 || dash == std::string::npos || rest.find_first_not_of("0123456789") != dash) {
      continue;
    }
    const long pid = std::strtol(rest.substr(0, dash).c_str(), nullptr, 10);
    if (pid <= 0 || pid == long(getpid())) continue;
    if (::kill(pid_t(pid), 0) == -1 && errno == ESRCH) {
      std::error_code ignored;
      fs::remove(it->path(), ignored);
    }
  }
}

Error output_error(const fs::path& path, const std::string& message) {
  return Error(ErrorKind::kOutput, message, ErrorLocation{path.string(), 0, {}});
}

}  // namespace

AtomicFile::AtomicFile(const fs::path& target) : target_(target), temp_(temp_path_for(target)) {
  remove_stale_temp_files(target);
  // Counted last: nothing after it can throw, so the destructor always uncounts it.
  start_write(temp_);
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temp_, ec);
  }
  finish_write(temp_);
}

void AtomicFile::commit() {
  const int fd = ::open(temp_.c_str(), O_RDONLY);
  if (fd < 0 || ::fsync(fd) != 0) {
    const std::string reason = std::strerror(errno);
    if (fd >= 0) ::close(fd);
    throw output_error(target_, "cannot flush the written file to disk: " + reason);
  }
  ::close(fd);
  std::error_code ec;
  fs::rename(temp_, target_, ec);
  if (ec) throw output_error(target_, "cannot replace the file: " + ec.message());
  committed_ = true;
  // Make the rename itself durable; a failure here loses nothing already written.
  if (const int dir = ::open(folder_of(target_).c_str(), O_RDONLY | O_DIRECTORY); dir >= 0) {
    ::fsync(dir);
    ::close(dir);
  }
}

void check_output_writable(const fs::path& path) {
  const fs::path folder = folder_of(path);
  std::error_code ec;
  if (path.filename().empty()) throw output_error(path, "the output path names no file");
  if (!fs::exists(folder, ec)) {
    throw output_error(path, "the output folder '" + folder.string() + "' does not exist");
  }
  if (!fs::is_directory(folder, ec)) {
    throw output_error(path, "'" + folder.string() + "' is not a folder");
  }
  if (fs::is_directory(path, ec)) throw output_error(path, "the output path is a folder");
  // Creating a file is the only reliable test (permissions, read-only mounts, ACLs, quotas).
  const fs::path probe = temp_path_for(path);
  const ProbeInFlight probing(probe);
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) {
    throw output_error(path, "cannot create files in the output folder '" + folder.string() +
                                 "': " + std::strerror(errno));
  }
  ::close(fd);
  ::unlink(probe.c_str());
  // A run that ends without writing `path` (a resumed render that finishes before its next
  // checkpoint) must not leave the temporary files of runs killed while writing it.
  remove_stale_temp_files(path);
}

bool stop_file_writes(std::chrono::milliseconds timeout) {
  std::unique_lock lock(write_gate.mutex);
  write_gate.closed = true;
  if (write_gate.emptied.wait_for(lock, timeout, [] { return write_gate.in_flight.empty(); })) {
    return true;
  }
  for (const fs::path& temp : write_gate.in_flight) ::unlink(temp.c_str());
  return false;
}

}  // namespace prism
