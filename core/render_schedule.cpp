#include "core/render_schedule.h"

#include <algorithm>

#include "core/error.h"

namespace prism {

RenderSchedule::RenderSchedule(const PixelRect& window, SampleRange samples, uint32_t pass_samples,
                               int tile_size)
    : window_(window), samples_(samples), pass_samples_(pass_samples), tile_size_(tile_size) {
  PRISM_CHECK(!window.empty() && tile_size > 0 && pass_samples > 0);
  PRISM_CHECK(samples.last >= samples.first);
  tiles_x_ = (window.width() + tile_size - 1) / tile_size;
  tiles_y_ = (window.height() + tile_size - 1) / tile_size;
  passes_ = int((samples.count() + pass_samples - 1) / pass_samples);
}

Tile RenderSchedule::tile(int index) const {
  PRISM_CHECK(index >= 0 && index < tile_count());
  const glm::ivec2 begin =
      window_.begin + glm::ivec2(index % tiles_x_, index / tiles_x_) * tile_size_;
  return Tile{begin, glm::min(begin + glm::ivec2(tile_size_), window_.end)};
}

SampleRange RenderSchedule::pass(int index) const {
  PRISM_CHECK(index >= 0 && index < passes_);
  const uint32_t first = samples_.first + uint32_t(index) * pass_samples_;
  return SampleRange{first, std::min(samples_.last, first + pass_samples_)};
}

int RenderSchedule::pass_of_sample(uint32_t sample) const {
  if (sample < samples_.first) return 0;
  if (sample >= samples_.last) return passes_;
  return int((sample - samples_.first) / pass_samples_);
}

}  // namespace prism
