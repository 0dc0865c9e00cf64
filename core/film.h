#pragma once

#include <atomic>
#include <cstdint>

#include "core/image.h"
#include "core/math.h"

namespace prism {

/// Accumulates radiance samples per pixel. add_sample() for different pixels may run
/// concurrently; one pixel is written by one thread at a time (the tile loop guarantees it).
/// Non-finite samples are dropped and counted, so no NaN or Inf reaches an image.
class Film {
 public:
  Film(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  void add_sample(glm::ivec2 pixel, const Rgb& radiance);
  /// Samples dropped because they were NaN or infinite.
  uint64_t non_finite_samples() const { return non_finite_.load(); }
  /// The per-pixel mean as an RGB image (channels R, G, B).
  Image resolve() const;

 private:
  int width_, height_;
  std::vector<Rgb> sum_;
  std::vector<uint32_t> count_;
  std::atomic<uint64_t> non_finite_{0};
};

}  // namespace prism
