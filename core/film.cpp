#include "core/film.h"

#include <cmath>

#include "core/error.h"

namespace prism {

size_t Image::count_non_finite() const {
  size_t n = 0;
  for (float v : pixels) n += std::isfinite(v) ? 0 : 1;
  return n;
}

Film::Film(int width, int height)
    : width_(width),
      height_(height),
      sum_(size_t(width) * height, Rgb(0.0f)),
      count_(size_t(width) * height, 0) {
  PRISM_CHECK(width > 0 && height > 0);
}

void Film::add_sample(glm::ivec2 pixel, const Rgb& radiance) {
  const size_t i = size_t(pixel.y) * width_ + pixel.x;
  ++count_[i];
  if (!is_finite(radiance)) {
    non_finite_.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  sum_[i] += radiance;
}

Image Film::resolve() const {
  Image image;
  image.width = width_;
  image.height = height_;
  image.channel_names = {"R", "G", "B"};
  image.pixels.resize(size_t(width_) * height_ * 3);
  for (size_t i = 0; i < sum_.size(); ++i) {
    const Rgb mean = count_[i] > 0 ? sum_[i] / float(count_[i]) : Rgb(0.0f);
    image.pixels[3 * i + 0] = mean.r;
    image.pixels[3 * i + 1] = mean.g;
    image.pixels[3 * i + 2] = mean.b;
  }
  return image;
}

}  // namespace prism
