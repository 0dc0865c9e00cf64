#include "integrators/lights/point_light.h"

#include <algorithm>
#include <cmath>

#include "integrators/sampling/frame.h"
#include "integrators/sampling/warp.h"

namespace prism {

PointLight::PointLight(const Light& light)
    : intensity_(light.color),
      position_(light.position),
      direction_(glm::normalize(light.direction)),
      c_(light.constant_attenuation),
      l_(light.linear_attenuation),
      q_(light.quadratic_attenuation),
      spot_(light.type == LightType::kSpot),
      cos_cutoff_(std::cos(radians(std::clamp(light.falloff_angle_deg, 0.0f, 360.0f)) * 0.5f)),
      exponent_(std::max(0.0f, light.falloff_exponent)) {}

float PointLight::cone_factor(const Vec3& w_from_light) const {
  if (!spot_) return 1.0f;
  const float cos_angle = glm::dot(w_from_light, direction_);
  if (cos_angle < cos_cutoff_) return 0.0f;
  return exponent_ > 0.0f ? std::pow(std::max(0.0f, cos_angle), exponent_) : 1.0f;
}

std::optional<LightLiSample> PointLight::sample_li(const Vec3& p, Vec2 u) const {
  const Vec3 to_light = position_ - p;
  const float d = glm::length(to_light);
  if (!(d > 0.0f)) return std::nullopt;
  LightLiSample s;
  s.wi = to_light / d;
  s.distance = d;
  s.pdf = 1.0f;
  const float denom = c_ + l_ * d + q_ * d * d;
  // All-zero coefficients mean "no attenuation" rather than a division by zero.
  const float attenuation = denom > 0.0f ? 1.0f / denom : 1.0f;
  const float cone = cone_factor(-s.wi);
  if (cone <= 0.0f) return std::nullopt;
  s.li = intensity_ * (attenuation * cone);
  return s;
}

Rgb PointLight::power() const {
  if (!spot_) return 4.0f * kPi * intensity_;
  // Solid angle of the cone; the falloff exponent is ignored (a selection weight only).
  return 2.0f * kPi * (1.0f - cos_cutoff_) * intensity_;
}

DirectionalLight::DirectionalLight(const Light& light, float scene_radius)
    : radiance_(light.color),
      direction_(glm::normalize(light.direction)),
      scene_radius_(scene_radius) {}

std::optional<LightLiSample> DirectionalLight::sample_li(const Vec3& p, Vec2 u) const {
  LightLiSample s;
  s.wi = -direction_;
  s.pdf = 1.0f;
  s.li = radiance_;
  s.distance = kInfinity;
  return s;
}

Rgb DirectionalLight::power() const { return kPi * scene_radius_ * scene_radius_ * radiance_; }

AmbientLight::AmbientLight(const Light& light, float scene_radius, bool visible)
    : radiance_(light.color),
      up_(glm::normalize(light.up)),
      scene_radius_(scene_radius),
      visible_(visible) {}

std::optional<LightLiSample> AmbientLight::sample_li(const Vec3& p, Vec2 u) const {
  LightLiSample s;
  s.wi = Frame::from_z(up_).to_world(square_to_uniform_hemisphere(u));
  s.pdf = uniform_hemisphere_pdf();
  s.li = radiance_;
  s.distance = kInfinity;
  return s;
}

float AmbientLight::pdf_li_escaped(const Vec3& w) const {
  return glm::dot(w, up_) > 0.0f ? uniform_hemisphere_pdf() : 0.0f;
}

Rgb AmbientLight::le_escaped(const Vec3& w) const {
  return glm::dot(w, up_) > 0.0f ? radiance_ : Rgb(0.0f);
}

Rgb AmbientLight::power() const {
  // Radiance over a hemisphere of directions through a disk of the scene's size.
  return kPi * kPi * scene_radius_ * scene_radius_ * radiance_;
}

}  // namespace prism
