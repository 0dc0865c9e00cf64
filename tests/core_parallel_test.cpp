// run_beside() (core/parallel.h): its body runs once, and the parallel loops started meanwhile do
// not wait for it.

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <vector>

#include "core/parallel.h"

namespace prism::test {
namespace {

/// What a body beside the test shares with it; the body may outlive the test's scope.
struct BesideState {
  std::mutex mutex;
  std::condition_variable changed;
  int runs = 0;
  bool released = false;
  bool gave_up = false;
};

constexpr auto kPatience = std::chrono::seconds(60);

TEST(CoreParallel, RunBesideRunsTheBodyOnce) {
  const ThreadLimit limit(2);
  auto state = std::make_shared<BesideState>();
  run_beside([state] {
    std::lock_guard lock(state->mutex);
    ++state->runs;
    state->changed.notify_all();
  });
  std::unique_lock lock(state->mutex);
  ASSERT_TRUE(state->changed.wait_for(lock, kPatience, [&] { return state->runs > 0; }))
      << "the body did not run within a minute";
  lock.unlock();
  // Loops after it do not run it again.
  std::vector<int> squares(256);
  parallel_for_indices(squares.size(), [&](size_t i) { squares[i] = int(i * i); });
  lock.lock();
  EXPECT_EQ(state->runs, 1);
}

TEST(CoreParallel, LoopsFinishWhileTheBodyBesideThemRuns) {
#ifdef PRISM_PARALLEL_THREADS
  GTEST_SKIP() << "the std::thread implementation runs the body before run_beside returns";
#endif
  const ThreadLimit limit(2);
  auto state = std::make_shared<BesideState>();
  // The body holds its thread until the loop below has finished: a run_beside that made the
  // loop wait for it (or ran it first on the calling thread) ends its wait after a minute instead
  // of hanging, and says so.
  run_beside([state] {
    std::unique_lock lock(state->mutex);
    state->gave_up = !state->changed.wait_for(lock, kPatience, [&] { return state->released; });
    ++state->runs;
    state->changed.notify_all();
  });
  std::vector<int> squares(10000);
  parallel_for_indices(squares.size(), [&](size_t i) { squares[i] = int(i * i); });
  for (size_t i = 0; i < squares.size(); ++i) ASSERT_EQ(squares[i], int(i * i)) << i;
  std::unique_lock lock(state->mutex);
  state->released = true;
  state->changed.notify_all();
  ASSERT_TRUE(state->changed.wait_for(lock, kPatience, [&] { return state->runs > 0; }))
      << "the body did not run within a minute";
  EXPECT_FALSE(state->gave_up) << "the loop waited for the body beside it";
  EXPECT_EQ(state->runs, 1);
}

}  // namespace
}  // namespace prism::test
