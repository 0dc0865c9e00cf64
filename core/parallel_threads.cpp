// The std::thread implementation of core/parallel.h and core/parallel_reduce.h
// (-DPRISM_PARALLEL=threads): what ThreadSanitizer builds use, since TSan sees the
// synchronisation of std::thread and std::atomic but not that of an uninstrumented oneTBB.
//
// There is no pool. A loop runs on the calling thread and on helper threads started for it,
// as many as its budget allows, and joins them before it returns. A budget is the thread limit
// (ThreadLimit, or a ThreadArena's size) less the helpers already running; nested loops and
// parallel_invoke draw on the budget of the thread they run on and run inline when it is spent.
// So prism's loops never run on more threads than the limit, however deep the recursion,
// besides threads that callers started themselves. Each thread of a loop takes a first chunk of
// its own, then the next untaken chunk from a shared counter; which thread runs which chunk does
// not change any result (core/parallel.h).
#include <sched.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <set>
#include <system_error>
#include <thread>
#include <vector>

#include "core/parallel.h"
#include "core/parallel_reduce.h"

#ifndef PRISM_PARALLEL_THREADS
#error "core/parallel_threads.cpp is the std::thread implementation: build core/parallel_tbb.cpp"
#endif

namespace prism {
namespace {

// Chunks per thread of a loop whose grain allows it: enough to even out uneven chunks.
constexpr size_t kChunksPerThread = 8;

int hardware_threads() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

/// Threads for the loops of one context: `threads` in all, the threads that started loops
/// included, so at most threads - 1 helpers at a time.
class Budget {
 public:
  explicit Budget(int threads) : threads_(threads) {}

  int threads() const { return threads_.load(std::memory_order_relaxed); }
  void set_threads(int threads) { threads_.store(threads, std::memory_order_relaxed); }

  /// Takes a helper's place if one is free. The counter orders nothing: helpers are
  /// synchronised with their starter by std::thread's start and join.
  bool try_acquire() {
    int helpers = helpers_.load(std::memory_order_relaxed);
    while (helpers + 1 < threads()) {
      if (helpers_.compare_exchange_weak(helpers, helpers + 1, std::memory_order_relaxed)) {
        return true;
      }
    }
    return false;
  }
  void release() { helpers_.fetch_sub(1, std::memory_order_relaxed); }

 private:
  std::atomic<int> threads_;
  std::atomic<int> helpers_{0};
};

/// The process-wide budget, whose size is the smallest live ThreadLimit (all hardware threads
/// when there is none).
struct GlobalLimits {
  std::mutex mutex;
  std::multiset<int> active;
  Budget budget{hardware_threads()};
};

GlobalLimits& global_limits() {
  static GlobalLimits limits;
  return limits;
}

// The budget of the arena the calling thread works in; nullptr: the global one.
thread_local Budget* t_budget = nullptr;

Budget& current_budget() { return t_budget != nullptr ? *t_budget : global_limits().budget; }

/// Runs work(member, members) for every member of a team: the calling thread (member 0) and
/// up to `wanted` helpers that the budget allows (members 1 ...), and returns when every one has
/// returned. work() must not throw.
void run_team(size_t wanted, const std::function<void(size_t, size_t)>& work) {
  Budget& budget = current_budget();
  size_t members = 1;
  while (members <= wanted && budget.try_acquire()) ++members;
  std::vector<std::thread> helpers;
  helpers.reserve(members - 1);
  size_t started = 1;
  for (; started < members; ++started) {
    try {
      helpers.emplace_back([&budget, &work, started, members] {
        t_budget = &budget;
        work(started, members);
        budget.release();
      });
    } catch (const std::system_error&) {  // out of threads: the caller stands in for the rest
      break;
    }
  }
  work(0, members);
  for (size_t member = started; member < members; ++member) {
    budget.release();
    work(member, members);
  }
  for (std::thread& helper : helpers) helper.join();
}

}  // namespace

namespace parallel_detail {

Chunks chunks_of(size_t count, size_t grain) {
  if (count == 0) return {1, 0};
  const size_t target = static_cast<size_t>(current_budget().threads()) * kChunksPerThread;
  const size_t size = std::max({grain, size_t{1}, (count + target - 1) / target});
  return {size, (count + size - 1) / size};
}

void run_chunks(size_t chunks, const std::function<void(size_t)>& body) {
  if (chunks == 0) return;
  if (chunks == 1) {
    body(0);
    return;
  }
  std::atomic<bool> failed{false};
  std::mutex error_mutex;
  std::exception_ptr error;
  // Member m of the team takes chunk m first, then the next untaken one: every thread of the
  // team runs at least one chunk, however late it starts (so ThreadSanitizer always sees the
  // loop on several threads), and the rest balance.
  std::atomic<size_t> taken{0};  // of the chunks after the first `members`
  run_team(chunks - 1, [&](size_t member, size_t members) {
    for (size_t c = member; c < chunks && !failed.load(std::memory_order_relaxed);
         c = members + taken.fetch_add(1, std::memory_order_relaxed)) {
      try {
        body(c);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        failed.store(true, std::memory_order_relaxed);
      }
    }
  });
  if (error) std::rethrow_exception(error);
}

}  // namespace parallel_detail

void parallel_for_tiles(int width, int height, int tile_size,
                        const std::function<void(const Tile&)>& body) {
  const int tiles_x = (width + tile_size - 1) / tile_size;
  const int tiles_y = (height + tile_size - 1) / tile_size;
  parallel_detail::run_chunks(size_t(tiles_x) * size_t(tiles_y), [&](size_t index) {
    const int i = static_cast<int>(index);
    const glm::ivec2 begin{(i % tiles_x) * tile_size, (i / tiles_x) * tile_size};
    const glm::ivec2 end = glm::min(begin + tile_size, glm::ivec2(width, height));
    body(Tile{begin, end});
  });
}

void parallel_for_indices(size_t count, const std::function<void(size_t)>& body) {
  parallel_detail::run_chunks(count, body);
}

void parallel_for_range(size_t count, const std::function<void(size_t, size_t)>& body,
                        size_t grain) {
  const parallel_detail::Chunks cut = parallel_detail::chunks_of(count, grain);
  parallel_detail::run_chunks(
      cut.chunks, [&](size_t c) { body(c * cut.size, std::min(count, (c + 1) * cut.size)); });
}

void parallel_invoke(const std::function<void()>& a, const std::function<void()>& b) {
  Budget& budget = current_budget();
  if (!budget.try_acquire()) {
    a();
    b();
    return;
  }
  std::exception_ptr a_error, b_error;
  std::thread helper;
  try {
    helper = std::thread([&] {
      t_budget = &budget;
      try {
        a();
      } catch (...) {
        a_error = std::current_exception();
      }
      budget.release();
    });
  } catch (const std::system_error&) {  // out of threads: both here
    budget.release();
    a();
    b();
    return;
  }
  try {
    b();
  } catch (...) {
    b_error = std::current_exception();
  }
  helper.join();
  if (a_error) std::rethrow_exception(a_error);
  if (b_error) std::rethrow_exception(b_error);
}

struct ThreadLimit::State {
  explicit State(int threads) : control(tbb::global_control::max_allowed_parallelism, threads) {}
  // oneTBB still runs Embree's builds: it obeys the limit too.
  tbb::global_control control;
  std::multiset<int>::iterator entry;
};

void run_beside(std::function<void()> body) { body(); }

ThreadLimit::ThreadLimit(int threads) {
  threads_ = threads > 0 ? threads : hardware_threads();
  state_ = std::make_unique<State>(threads_);
  GlobalLimits& limits = global_limits();
  const std::lock_guard<std::mutex> lock(limits.mutex);
  state_->entry = limits.active.insert(threads_);
  limits.budget.set_threads(*limits.active.begin());
}

ThreadLimit::~ThreadLimit() {
  GlobalLimits& limits = global_limits();
  const std::lock_guard<std::mutex> lock(limits.mutex);
  limits.active.erase(state_->entry);
  limits.budget.set_threads(limits.active.empty() ? hardware_threads() : *limits.active.begin());
}

struct ThreadArena::State {
  explicit State(int threads) : budget(threads) {}
  Budget budget;
};

ThreadArena::ThreadArena(int threads)
    : state_(std::make_unique<State>(std::max(1, threads))), threads_(threads) {}

ThreadArena::~ThreadArena() = default;

void ThreadArena::execute(const std::function<void()>& body) {
  struct Enter {
    explicit Enter(Budget* budget) : saved(t_budget) { t_budget = budget; }
    ~Enter() { t_budget = saved; }
    Budget* saved;
  } enter(&state_->budget);
  body();
}

}  // namespace prism
