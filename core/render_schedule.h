#pragma once

#include <cstddef>
#include <cstdint>

#include "core/film.h"
#include "core/parallel.h"

namespace prism {

/// Sample indices [first, last) of every pixel.
struct SampleRange {
  uint32_t first = 0;
  uint32_t last = 0;

  uint32_t count() const { return last > first ? last - first : 0; }
  bool operator==(const SampleRange&) const = default;
};

/// How one render is cut into units of work, the same on every machine: the pixels of `window`
/// in square tiles of `tile_size` (tile rows top to bottom, left to right in a row), the
/// sample range in passes of `pass_samples` samples (the last pass may be shorter). Unit u is
/// tile u % tile_count() of pass u / tile_count(): pass-major, so that the image after any
/// whole number of passes is the image of a render with that many samples. Every sample of
/// every pixel belongs to exactly one unit.
class RenderSchedule {
 public:
  static constexpr int kTileSize = 16;

  RenderSchedule(const PixelRect& window, SampleRange samples, uint32_t pass_samples,
                 int tile_size = kTileSize);

  const PixelRect& window() const { return window_; }
  SampleRange samples() const { return samples_; }
  uint32_t pass_samples() const { return pass_samples_; }
  int tile_count() const { return tiles_x_ * tiles_y_; }
  int pass_count() const { return passes_; }
  size_t unit_count() const { return size_t(tile_count()) * size_t(passes_); }

  /// Tile `index` in [0, tile_count()).
  Tile tile(int index) const;
  /// Samples of pass `index` in [0, pass_count()).
  SampleRange pass(int index) const;
  /// The pass whose range holds sample `sample` (pass_count() for samples().last and beyond).
  int pass_of_sample(uint32_t sample) const;

 private:
  PixelRect window_;
  SampleRange samples_;
  uint32_t pass_samples_;
  int tile_size_;
  int tiles_x_ = 0, tiles_y_ = 0;
  int passes_ = 0;
};

}  // namespace prism
