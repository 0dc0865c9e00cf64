// core/atomic_file.h: the temporary file beside the target, the commit, and stop_file_writes(),
// which the second SIGINT/SIGTERM uses to end the process without leaving a file behind.
// stop_file_writes() closes a process-wide gate for good, so its tests run in a child process
// (death tests) and end it with _exit (a thread stays blocked at the closed gate).

#include "core/atomic_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/child_process.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

using test::finish_child;
using test::read_bytes;
using test::temp_files_in;
using test::write_text;

void wait_until(const std::atomic<bool>& flag) {
  while (!flag.load()) std::this_thread::sleep_for(milliseconds(1));
}

TEST(CoreAtomicFile, CommitReplacesTheTargetAndLeavesNoTemporaryFile) {
  const fs::path dir = test::make_temp_dir("atomic_file_commit");
  const fs::path target = dir / "out.txt";
  write_text(target, "old");
  {
    AtomicFile file(target);
    EXPECT_EQ(file.temp_path().parent_path(), dir);
    write_text(file.temp_path(), "new");
    EXPECT_EQ(read_bytes(target), "old");  // untouched until the commit
    file.commit();
  }
  EXPECT_EQ(read_bytes(target), "new");
  EXPECT_EQ(temp_files_in(dir), std::vector<std::string>{});
  {
    AtomicFile abandoned(target);
    write_text(abandoned.temp_path(), "partial");
  }
  EXPECT_EQ(read_bytes(target), "new");
  EXPECT_EQ(temp_files_in(dir), std::vector<std::string>{});
  fs::remove_all(dir);
}

TEST(CoreAtomicFileDeathTest, StoppingWritesWaitsForTheWriteInFlightAndStartsNoOther) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const fs::path dir = test::make_temp_dir("atomic_file_stop");
  const auto scenario = [&] {
    const fs::path target = dir / "in_flight.txt", late_target = dir / "late.txt";
    std::atomic<bool> created{false}, late_started{false};
    // A write in flight: its temporary file exists, the commit comes 300 ms later.
    std::thread writer([&] {
      AtomicFile file(target);
      write_text(file.temp_path(), "whole");
      created = true;
      std::this_thread::sleep_for(milliseconds(300));
      file.commit();
    });
    wait_until(created);
    const auto start = Clock::now();
    const bool drained = stop_file_writes(milliseconds(10000));
    const auto waited = Clock::now() - start;
    // A write that starts after the stop never gets to create anything.
    std::thread late([&] {
      AtomicFile file(late_target);
      late_started = true;
      write_text(file.temp_path(), "late");
    });
    late.detach();
    std::this_thread::sleep_for(milliseconds(200));
    writer.join();
    if (!drained) finish_child(false, "stop_file_writes gave up on a write that commits");
    if (waited < milliseconds(200)) finish_child(false, "stop_file_writes did not wait");
    if (read_bytes(target) != "whole") finish_child(false, "the write in flight was not committed");
    if (late_started) finish_child(false, "a write started after stop_file_writes");
    if (!temp_files_in(dir).empty()) finish_child(false, "a temporary file was left");
    finish_child(!fs::exists(late_target), "the late write created its target");
  };
  EXPECT_EXIT(scenario(), ::testing::ExitedWithCode(0), "");
  fs::remove_all(dir);
}

TEST(CoreAtomicFileDeathTest, StoppingWritesGivesUpOnAStalledWriteAndRemovesItsFile) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const fs::path dir = test::make_temp_dir("atomic_file_stalled");
  const auto scenario = [&] {
    std::atomic<bool> created{false}, release{false};
    std::thread stalled([&] {
      AtomicFile file(dir / "stalled.txt");
      write_text(file.temp_path(), "partial");
      created = true;
      wait_until(release);  // a write on a disk that stopped answering
    });
    stalled.detach();
    wait_until(created);
    if (temp_files_in(dir).size() != 1) finish_child(false, "the stalled write's file is missing");
    const auto start = Clock::now();
    const bool drained = stop_file_writes(milliseconds(100));
    const auto waited = Clock::now() - start;
    if (drained) finish_child(false, "stop_file_writes claimed a stalled write had finished");
    if (waited < milliseconds(100) || waited > milliseconds(5000)) {
      finish_child(false, "stop_file_writes did not wait for its timeout, and only that");
    }
    finish_child(temp_files_in(dir).empty(), "stop_file_writes left the stalled write's file");
  };
  EXPECT_EXIT(scenario(), ::testing::ExitedWithCode(0), "");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace prism
