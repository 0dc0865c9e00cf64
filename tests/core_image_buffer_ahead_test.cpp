// core/image_buffer_ahead.h: the buffer is made beside the caller and handed over once; with
// one thread nothing is made; an owner gone before the task starts leaves it nothing to do.

#include "core/image_buffer_ahead.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>

#include "core/parallel.h"

namespace prism {
namespace {

/// Waits until a task queued by run_beside() now has run, at most 10 s (the tasks queued
/// before it have been taken by then, under oneTBB's roughly first-in first-out queue; the
/// std::thread implementation runs them at once).
void wait_for_tasks_beside() {
  struct Flag {
    bool ran = false;
    std::mutex mutex;
    std::condition_variable done;
  };
  // Shared with the task, which may still come after a wait that timed out.
  const auto flag = std::make_shared<Flag>();
  run_beside([flag] {
    std::lock_guard lock(flag->mutex);
    flag->ran = true;
    flag->done.notify_all();
  });
  std::unique_lock lock(flag->mutex);
  flag->done.wait_for(lock, std::chrono::seconds(10), [&] { return flag->ran; });
}

TEST(CoreImageBufferAhead, MakesTheBufferOfZerosBesideTheCallerAndHandsItOverOnce) {
  const ThreadLimit limit(2);
  ImageBufferAhead ahead(12345, 2);
  // Made by a worker when it is free: at once here, within 10 s however loaded the machine.
  for (int i = 0; i < 1000 && !ahead.made(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(ahead.made());
  const ImagePixels buffer = ahead.take();
  ASSERT_EQ(buffer.size(), 12345u);
  EXPECT_TRUE(std::all_of(buffer.begin(), buffer.end(), [](float v) { return v == 0.0f; }));
  EXPECT_TRUE(ahead.take().empty()) << "handed over twice";
}

TEST(CoreImageBufferAhead, MakesNothingWithOneThread) {
  ImageBufferAhead ahead(100, 1);
  wait_for_tasks_beside();
  EXPECT_FALSE(ahead.made());
  EXPECT_TRUE(ahead.take().empty());
}

TEST(CoreImageBufferAhead, AnOwnerGoneFirstLeavesTheTaskNothingToDo) {
  // Owners taken or destroyed at once, whether their tasks have started or not: no hang, no
  // use of a freed owner (the sanitizer builds run this too), and whatever take() returns is
  // either the whole buffer or nothing.
  const ThreadLimit limit(2);
  for (int i = 0; i < 50; ++i) {
    ImageBufferAhead taken(4096, 2);
    const ImagePixels buffer = taken.take();
    EXPECT_TRUE(buffer.empty() || buffer.size() == 4096u);
    const ImageBufferAhead destroyed(4096, 2);
  }
  wait_for_tasks_beside();
}

}  // namespace
}  // namespace prism
