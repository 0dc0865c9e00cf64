#pragma once

// An image's pixel buffer made ahead of need, beside the work that will fill it.

#include <cstddef>
#include <memory>

#include "core/image.h"

namespace prism {

/// A buffer of zeros made (and its pages touched) by a task beside the caller (run_beside()),
/// for a result that is only known at the end of the caller's work: the render's image. Fresh
/// memory costs a page fault per page on first touch, ~2 ms per MiB on the virtual machines
/// prism is measured on; made at the end, the 10 MB of a 480 x 360 film's image would cost
/// that on the command's single thread, made beside the render it costs half of it (the other
/// threads render on). Thread-safe between the task and the owner.
class ImageBufferAhead {
 public:
  /// Starts making `count` zeros beside the caller when `threads` >= 2 (with one thread the
  /// task would wait for the caller's work, or add a thread); makes nothing otherwise.
  ImageBufferAhead(size_t count, int threads);
  /// Waits for the task if it is making the buffer; cancels it if it has not started.
  ~ImageBufferAhead();
  ImageBufferAhead(const ImageBufferAhead&) = delete;
  ImageBufferAhead& operator=(const ImageBufferAhead&) = delete;

  /// The buffer of `count` zeros if it has been made (waiting while it is being made); an empty
  /// one if it has not (the task had not started: it never will), or after a first take().
  ImagePixels take();
  /// Whether the buffer is made and not taken yet (take() would return it at once).
  bool made() const;

 private:
  struct State;
  std::shared_ptr<State> state_;
};

}  // namespace prism
