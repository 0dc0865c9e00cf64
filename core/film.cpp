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
      stats_(size_t(std::max(width, 0)) * size_t(std::max(height, 0))),
      count_(size_t(std::max(width, 0)) * size_t(std::max(height, 0)), 0) {
  PRISM_CHECK(width > 0 && height > 0);
}

void Film::add_sample(glm::ivec2 pixel, const Rgb& radiance) {
  add_sample(pixel, radiance, AovSample{});
}

void Film::add_sample(glm::ivec2 pixel, const Rgb& radiance, const AovSample& aovs) {
  const size_t i = index(pixel);
  PixelStats& s = stats_[i];
  const uint32_t n = ++count_[i];
  Rgb value = radiance;
  if (!is_finite(value)) {
    non_finite_.fetch_add(1, std::memory_order_relaxed);
    value = Rgb(0.0f);
  }
  const Rgb delta = value - s.mean;
  s.mean += delta / float(n);
  s.m2 += delta * (value - s.mean);
  // AOVs are bounded by construction but a degenerate hit could still produce garbage.
  if (is_finite(aovs.albedo)) s.albedo_sum += aovs.albedo;
  if (is_finite(aovs.normal)) s.normal_sum += aovs.normal;
  if (std::isfinite(aovs.depth)) s.depth_sum += aovs.depth;
}

Image Film::resolve() const {
  Image image;
  image.width = width_;
  image.height = height_;
  image.channel_names = {
      "R",   "G",   "B", "albedo.R",      "albedo.G",   "albedo.B",   "N.X",
      "N.Y", "N.Z", "Z", "sampleCount.Y", "variance.R", "variance.G", "variance.B"};
  const int c = kChannels;
  image.pixels.assign(stats_.size() * c, 0.0f);
  for (size_t i = 0; i < stats_.size(); ++i) {
    const PixelStats& s = stats_[i];
    const uint32_t n = count_[i];
    float* out = &image.pixels[i * c];
    if (n == 0) continue;
    const float inv_n = 1.0f / float(n);
    const Rgb albedo = s.albedo_sum * inv_n;
    const Vec3 normal = s.normal_sum * inv_n;
    const Rgb variance = n > 1 ? glm::max(s.m2, Rgb(0.0f)) / (float(n - 1) * float(n)) : Rgb(0.0f);
    const float values[kChannels] = {
        s.mean.r, s.mean.g,   s.mean.b,   albedo.r,  albedo.g,
        albedo.b, normal.x,   normal.y,   normal.z,  s.depth_sum * inv_n,
        float(n), variance.r, variance.g, variance.b};
    for (int k = 0; k < c; ++k) out[k] = std::isfinite(values[k]) ? values[k] : 0.0f;
  }
  return image;
}

}  // namespace prism
