#include "core/film.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace prism {
namespace {

/// v x 2^shift as an integer, truncated toward zero; |v| must be below 2^(127 - shift). The
/// scaling by a power of two is exact, so the only rounding is the truncation, the same for a
/// value wherever it is added.
Int128 to_fixed(double v, double scale) {
  const double scaled = v * scale;
  // Most values fit in 64 bits: one instruction instead of a library call.
  if (std::abs(scaled) < 0x1p62) return Int128(int64_t(scaled));
  return Int128(scaled);
}

double clamp_value(float v, double limit) { return std::clamp(double(v), -limit, limit); }

constexpr double kValueScale = 0x1p50;
constexpr double kSquareScale = 0x1p40;
constexpr double kUnitScale = 0x1p40;
static_assert(kValueScale == double(Int128(1) << FilmPixel::kValueShift));
static_assert(kSquareScale == double(Int128(1) << FilmPixel::kSquareShift));
static_assert(kUnitScale == double(Int128(1) << FilmPixel::kUnitShift));

int64_t unit_to_fixed(float v) { return int64_t(std::clamp(double(v), -1.0, 1.0) * kUnitScale); }

double from_fixed(Int128 v, double scale) { return double(v) / scale; }

}  // namespace

size_t Image::count_non_finite() const {
  size_t n = 0;
  for (float v : pixels) n += std::isfinite(v) ? 0 : 1;
  return n;
}

Film::Film(int width, int height) : Film(width, height, PixelRect{{0, 0}, {width, height}}) {}

Film::Film(int width, int height, const PixelRect& window)
    : width_(width), height_(height), window_(window) {
  PRISM_CHECK(width > 0 && height > 0);
  PRISM_CHECK((!window.empty() && PixelRect{{0, 0}, {width, height}}.contains(window)));
  pixels_.resize(window.pixel_count());
}

Film::Film(Film&& other) noexcept
    : width_(other.width_),
      height_(other.height_),
      window_(other.window_),
      pixels_(std::move(other.pixels_)),
      non_finite_(other.non_finite_.load()) {}

Film& Film::operator=(Film&& other) noexcept {
  width_ = other.width_;
  height_ = other.height_;
  window_ = other.window_;
  pixels_ = std::move(other.pixels_);
  non_finite_.store(other.non_finite_.load());
  return *this;
}

void Film::add_sample(glm::ivec2 p, const Rgb& radiance, const AovSample& aovs) {
  FilmPixel& s = pixel(p);
  ++s.samples;
  // A sample that brings nothing (a camera ray that left the scene): every sum stays as it is,
  // as it would adding zeros, without the conversions.
  if (radiance == Rgb(0.0f) && aovs.albedo == Rgb(0.0f) && aovs.normal == Vec3(0.0f) &&
      aovs.depth == 0.0f) {
    return;
  }
  if (!is_finite(radiance)) {
    non_finite_.fetch_add(1, std::memory_order_relaxed);
  } else {
    for (int c = 0; c < 3; ++c) {
      const double v = clamp_value(radiance[c], FilmPixel::kValueLimit);
      s.radiance[c] += to_fixed(v, kValueScale);
      s.radiance_squared[c] += to_fixed(std::min(v * v, FilmPixel::kSquareLimit), kSquareScale);
    }
  }
  // AOVs are bounded by construction but a degenerate hit could still produce garbage: a
  // non-finite one is left out (as a zero).
  if (is_finite(aovs.albedo)) {
    for (int c = 0; c < 3; ++c) s.albedo[c] += unit_to_fixed(aovs.albedo[c]);
  }
  if (is_finite(aovs.normal)) {
    for (int c = 0; c < 3; ++c) s.normal[c] += unit_to_fixed(aovs.normal[c]);
  }
  if (std::isfinite(aovs.depth)) {
    s.depth += to_fixed(clamp_value(aovs.depth, FilmPixel::kValueLimit), kValueScale);
  }
}

void Film::accumulate(const Film& part) {
  PRISM_CHECK(part.width_ == width_ && part.height_ == height_);
  PRISM_CHECK(window_.contains(part.window_));
  const PixelRect& w = part.window_;
  for (int y = w.begin.y; y < w.end.y; ++y) {
    for (int x = w.begin.x; x < w.end.x; ++x) {
      const FilmPixel& from = part.pixel({x, y});
      FilmPixel& to = pixel({x, y});
      for (int c = 0; c < 3; ++c) {
        to.radiance[c] += from.radiance[c];
        to.radiance_squared[c] += from.radiance_squared[c];
        to.albedo[c] += from.albedo[c];
        to.normal[c] += from.normal[c];
      }
      to.depth += from.depth;
      to.samples += from.samples;
      to.progress = std::max(to.progress, from.progress);
    }
  }
  non_finite_.fetch_add(part.non_finite_samples());
}

Image Film::resolve(ImagePixels buffer) const {
  Image image;
  image.width = window_.width();
  image.height = window_.height();
  image.x = window_.begin.x;
  image.y = window_.begin.y;
  image.full_width = width_;
  image.full_height = height_;
  image.channel_names = {
      "R",   "G",   "B", "albedo.R",      "albedo.G",   "albedo.B",   "N.X",
      "N.Y", "N.Z", "Z", "sampleCount.Y", "variance.R", "variance.G", "variance.B"};
  const int c = kChannels;
  if (buffer.size() == pixels_.size() * c) {
    image.pixels = std::move(buffer);  // zeros, as below
  } else {
    image.pixels.assign(pixels_.size() * c, 0.0f);
  }
  for (size_t i = 0; i < pixels_.size(); ++i) {
    const FilmPixel& s = pixels_[i];
    const uint32_t n = s.samples;
    if (n == 0) continue;
    const double inv_n = 1.0 / double(n);
    float values[kChannels];
    for (int k = 0; k < 3; ++k) {
      const double sum = from_fixed(s.radiance[k], kValueScale);
      const double mean = sum * inv_n;
      values[k] = float(mean);
      values[kAlbedoChannel + k] = float(from_fixed(s.albedo[k], kUnitScale) * inv_n);
      values[kNormalChannel + k] = float(from_fixed(s.normal[k], kUnitScale) * inv_n);
      // Sample variance / n from the sums: (sum of squares - n mean^2) / (n - 1) / n.
      double variance = 0.0;
      if (n > 1) {
        const double squares = from_fixed(s.radiance_squared[k], kSquareScale);
        variance = std::max(0.0, (squares - sum * mean) / (double(n - 1) * double(n)));
      }
      values[kVarianceChannel + k] = float(variance);
    }
    values[kDepthChannel] = float(from_fixed(s.depth, kValueScale) * inv_n);
    values[kSampleCountChannel] = float(n);
    float* out = &image.pixels[i * c];
    for (int k = 0; k < c; ++k) out[k] = std::isfinite(values[k]) ? values[k] : 0.0f;
  }
  return image;
}

}  // namespace prism
