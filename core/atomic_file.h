#pragma once

#include <chrono>
#include <filesystem>

namespace prism {

/// A file that replaces `target` only once it is complete and on disk. Write to temp_path() (a
/// hidden file beside the target, unique per process and object), then commit(): fsync, rename
/// over the target, fsync of the folder. Destroyed without a commit, it removes the temporary
/// file, so a failure leaves the previous target (or none) and never a partial file. While it
/// exists it counts as a write in flight for stop_file_writes(). Creating one also removes the
/// temporary files of the same target that dead processes left (SIGKILL).
class AtomicFile {
 public:
  explicit AtomicFile(const std::filesystem::path& target);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::filesystem::path& target() const { return target_; }
  const std::filesystem::path& temp_path() const { return temp_; }
  /// Makes the written temporary file the target. Throws Error(kOutput) naming the target.
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temp_;
  bool committed_ = false;
};

/// Throws Error(kOutput) naming `path` when a file cannot be created there: no file name, a
/// missing folder, a folder that is not one, a path that is a folder, or a folder where no file
/// can be created (found by creating and removing a hidden probe file: the only test that
/// covers permissions, read-only mounts, ACLs and quotas). Called before long work. Then removes
/// the temporary files of `path` that dead processes left, as creating an AtomicFile does.
void check_output_writable(const std::filesystem::path& path);

/// For a process about to end with _exit() without leaving partial files (not from a signal
/// handler): from now on no new write starts (creating an AtomicFile, or the probe of
/// check_output_writable(), blocks its thread for good), and the writes in flight are given up to
/// `timeout` to commit or remove their temporary files. Returns true when none is left in flight;
/// otherwise deletes the laggards' temporary files and returns false (a laggard that opens its
/// file again after that would recreate it).
bool stop_file_writes(std::chrono::milliseconds timeout);

}  // namespace prism
