#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "core/image.h"
#include "core/math.h"

namespace prism {

/// Arbitrary output values of one camera sample, taken at the camera ray's first hit (zero
/// where the ray escapes).
struct AovSample {
  Rgb albedo{0.0f};    ///< surface colour in [0,1]^3
  Vec3 normal{0.0f};   ///< world-space unit shading normal
  float depth = 0.0f;  ///< distance from the ray origin to the hit
};

/// Accumulates radiance samples per pixel, with their running variance and the AOVs.
/// add_sample() for different pixels may run concurrently; one pixel is written by one thread
/// at a time (the tile loop guarantees it). Non-finite samples count as zero radiance and are
/// counted, so no NaN or Inf reaches an image.
class Film {
 public:
  Film(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  void add_sample(glm::ivec2 pixel, const Rgb& radiance);
  void add_sample(glm::ivec2 pixel, const Rgb& radiance, const AovSample& aovs);
  /// Samples whose radiance was NaN or infinite.
  uint64_t non_finite_samples() const { return non_finite_.load(); }
  /// Samples taken in `pixel` so far.
  uint32_t sample_count(glm::ivec2 pixel) const { return count_[index(pixel)]; }

  /// The per-pixel means as an image with channels, in this order: R, G, B (radiance);
  /// albedo.R/G/B; N.X/Y/Z (mean shading normal, not renormalised); Z (mean depth, 0 where
  /// rays escape); sampleCount.Y (samples taken); variance.R/G/B (estimated variance of the
  /// pixel mean: sample variance / n, 0 for fewer than two samples).
  Image resolve() const;
  /// Number of channels resolve() produces, and the index of the first of each group.
  static constexpr int kChannels = 14;
  static constexpr int kAlbedoChannel = 3;
  static constexpr int kNormalChannel = 6;
  static constexpr int kDepthChannel = 9;
  static constexpr int kSampleCountChannel = 10;
  static constexpr int kVarianceChannel = 11;

 private:
  size_t index(glm::ivec2 pixel) const { return size_t(pixel.y) * width_ + pixel.x; }

  /// Welford's running mean and sum of squared deviations: stable in float.
  struct PixelStats {
    Rgb mean{0.0f};
    Rgb m2{0.0f};
    Rgb albedo_sum{0.0f};
    Vec3 normal_sum{0.0f};
    float depth_sum = 0.0f;
  };

  int width_, height_;
  std::vector<PixelStats> stats_;
  std::vector<uint32_t> count_;
  std::atomic<uint64_t> non_finite_{0};
};

}  // namespace prism
