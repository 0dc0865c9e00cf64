#pragma once

#include <vector>

#include "core/image.h"
#include "integrators/lights/light_source.h"
#include "integrators/sampling/distribution.h"
#include "integrators/sampling/frame.h"

namespace prism {

/// An environment map in latitude-longitude layout surrounding the scene: radiance arriving
/// from direction w is the map's pixel at u = phi / 2pi (column), v = theta / pi (row), where
/// theta is the angle between w and `up` (row 0 is the pole at `up`) and phi is measured in the
/// plane normal to `up` from Frame::from_z(up).s toward .t. Pixels are piecewise constant.
/// Sampled in proportion to luminance x sin(theta) per pixel; every pixel with any radiance
/// can be sampled. Negative values in the map count as zero.
class EnvironmentLight final : public LightSource {
 public:
  /// `image` must hold channels R, G and B (others are ignored); throws Error(kInput)
  /// otherwise or when it is empty. The pixels are copied.
  EnvironmentLight(const Image& image, const Vec3& up, float scene_radius);
  LightKind kind() const override { return LightKind::kInfinite; }
  std::optional<LightLiSample> sample_li(const Vec3& p, Vec2 u) const override;
  float pdf_li_escaped(const Vec3& w) const override;
  Rgb le_escaped(const Vec3& w) const override;
  Rgb power() const override;

 private:
  /// (column, row) of the pixel seen in direction w, and the sine of its polar angle.
  glm::ivec2 pixel_of(const Vec3& w, float* sin_theta) const;
  const Rgb& texel(int x, int y) const { return pixels_[size_t(y) * width_ + x]; }

  int width_ = 0, height_ = 0;
  std::vector<Rgb> pixels_;
  Frame frame_;
  DiscreteDistribution pixel_distribution_;  ///< over all pixels, row-major
  float scene_radius_;
  Rgb mean_radiance_{0.0f};
};

}  // namespace prism
