#include "core/app/tile_lanes.h"

#include <algorithm>

namespace prism {

TileLanes::TileLanes(const TileRenderer& renderer, SampleRange samples, int lanes)
    : renderer_(renderer), samples_(samples) {
  for (int i = 0; i < std::max(1, lanes); ++i) threads_.emplace_back([this] { run_lane(); });
}

TileLanes::~TileLanes() {
  {
    const std::lock_guard lock(mutex_);
    halted_ = true;
    queue_.clear();
    closing_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : threads_) t.join();
}

void TileLanes::push(TileJob job) {
  {
    const std::lock_guard lock(mutex_);
    ++load_;
    if (halted_) {
      finished_.push_back(std::move(job));
      return;
    }
    queue_.push_back(std::move(job));
  }
  wake_.notify_one();
}

std::vector<TileJob> TileLanes::take_finished() {
  const std::lock_guard lock(mutex_);
  if (error_) std::rethrow_exception(error_);
  std::vector<TileJob> out = std::move(finished_);
  finished_.clear();
  load_ -= out.size();
  return out;
}

void TileLanes::halt() {
  const std::lock_guard lock(mutex_);
  halted_ = true;
  for (TileJob& job : queue_) finished_.push_back(std::move(job));
  queue_.clear();
}

size_t TileLanes::load() const {
  const std::lock_guard lock(mutex_);
  return load_;
}

void TileLanes::run_lane() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return closing_ || !queue_.empty(); });
    if (queue_.empty()) return;  // closing
    TileJob job = std::move(queue_.front());
    queue_.pop_front();
    lock.unlock();
    std::exception_ptr error;
    try {
      renderer_.render_tile(job.tile, samples_, job.film);
      job.rendered = true;
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    if (error && !error_) error_ = error;
    finished_.push_back(std::move(job));
  }
}

}  // namespace prism
