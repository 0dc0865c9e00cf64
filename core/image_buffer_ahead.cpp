#include "core/image_buffer_ahead.h"

#include <condition_variable>
#include <mutex>
#include <new>

#include "core/parallel.h"

namespace prism {

/// Where the task stands; shared with it, since it may start after its owner is gone.
struct ImageBufferAhead::State {
  enum class Step { kQueued, kMaking, kDone, kCancelled };
  std::mutex mutex;
  std::condition_variable done;
  Step step = Step::kQueued;
  ImagePixels buffer;  ///< under mutex once kDone
};

ImageBufferAhead::ImageBufferAhead(size_t count, int threads) {
  if (threads < 2 || count == 0) return;
  state_ = std::make_shared<State>();
  run_beside([state = state_, count] {
    using Step = State::Step;
    {
      std::lock_guard lock(state->mutex);
      if (state->step != Step::kQueued) return;
      state->step = Step::kMaking;
    }
    ImagePixels buffer;
    try {
      buffer.assign(count, 0.0f);  // every page written once: faulted in here
    } catch (const std::bad_alloc&) {
      buffer = ImagePixels();  // the owner makes its own, and reports if that fails too
    }
    std::lock_guard lock(state->mutex);
    state->buffer = std::move(buffer);
    state->step = Step::kDone;
    state->done.notify_all();
  });
}

ImageBufferAhead::~ImageBufferAhead() { take(); }

ImagePixels ImageBufferAhead::take() {
  if (!state_) return {};
  using Step = State::Step;
  std::unique_lock lock(state_->mutex);
  if (state_->step == Step::kQueued) state_->step = Step::kCancelled;
  state_->done.wait(lock, [&] { return state_->step != Step::kMaking; });
  return std::move(state_->buffer);
}

bool ImageBufferAhead::made() const {
  if (!state_) return false;
  std::lock_guard lock(state_->mutex);
  return state_->step == State::Step::kDone && !state_->buffer.empty();
}

}  // namespace prism
