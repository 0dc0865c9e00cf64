#pragma once

#include "core/light.h"
#include "integrators/lights/light_source.h"

namespace prism {

/// A point light of intensity `color` with COLLADA's attenuation 1 / (c + l d + q d^2) (no
/// inverse-square law of its own: q = 1, c = l = 0 gives the physical one), optionally limited
/// to a spot cone: full cone angle `falloff_angle_deg` about `direction`, within which the
/// intensity falls off as cos(angle)^falloff_exponent.
class PointLight final : public LightSource {
 public:
  explicit PointLight(const Light& light);
  LightKind kind() const override { return LightKind::kDelta; }
  std::optional<LightLiSample> sample_li(const Vec3& p, Vec2 u) const override;
  Rgb power() const override;

 private:
  float cone_factor(const Vec3& w_from_light) const;

  Rgb intensity_;
  Vec3 position_;
  Vec3 direction_;
  float c_, l_, q_;
  bool spot_;
  float cos_cutoff_;
  float exponent_;
};

/// Radiance `color` arriving from -direction everywhere (the sun): a delta in direction.
class DirectionalLight final : public LightSource {
 public:
  /// `scene_radius` bounds the scene, for power().
  DirectionalLight(const Light& light, float scene_radius);
  LightKind kind() const override { return LightKind::kDelta; }
  std::optional<LightLiSample> sample_li(const Vec3& p, Vec2 u) const override;
  Rgb power() const override;

 private:
  Rgb radiance_;
  Vec3 direction_;
  float scene_radius_;
};

/// Uniform radiance `color` from the hemisphere of directions about `up` (an ambient
/// "sky"). Sampled uniformly over that hemisphere. `visible`: rays that escape upward see it
/// (kInfinite); else it is kHiddenInfinite: it lights surfaces through sample_li() only and
/// escaping rays find black, as in the CS184 homework.
class AmbientLight final : public LightSource {
 public:
  AmbientLight(const Light& light, float scene_radius, bool visible);
  LightKind kind() const override {
    return visible_ ? LightKind::kInfinite : LightKind::kHiddenInfinite;
  }
  std::optional<LightLiSample> sample_li(const Vec3& p, Vec2 u) const override;
  float pdf_li_escaped(const Vec3& w) const override;
  Rgb le_escaped(const Vec3& w) const override;
  Rgb power() const override;

 private:
  Rgb radiance_;
  Vec3 up_;
  float scene_radius_;
  bool visible_;
};

}  // namespace prism
