#pragma once

#include <string>
#include <string_view>

#include "core/math.h"

namespace prism {

enum class LightType {
  kPoint,        ///< intensity `color` at `position`, attenuated 1 / (c + l d + q d^2)
  kSpot,         ///< a point light limited to a cone about `direction`
  kDirectional,  ///< radiance `color` travelling along `direction`
  kAmbient,      ///< uniform radiance `color` from the upper hemisphere about `up`
  kArea,         ///< one-sided parallelogram emitter, radiance `color`, emitting along `direction`
};

/// Plain light description in world space.
struct Light {
  std::string name;
  LightType type = LightType::kPoint;
  Rgb color{1.0f};
  Vec3 position{0.0f};       ///< point/spot position; area-light centre
  Vec3 direction{0, 0, -1};  ///< unit: where light travels (the light node's -Z)
  Vec3 up{0, 0, 1};          ///< ambient: the hemisphere's pole (the scene's up axis)
  float constant_attenuation = 1.0f;
  float linear_attenuation = 0.0f;
  float quadratic_attenuation = 0.0f;
  float falloff_angle_deg = 180.0f;  ///< spot: full cone angle in degrees, as COLLADA defines it
  float falloff_exponent = 0.0f;
  Vec3 edge_u{0.0f};  ///< area: full edge vectors; corner = position - (edge_u + edge_v) / 2
  Vec3 edge_v{0.0f};
  /// Area light whose emission is already present as an emissive mesh at the same place: it
  /// serves only as a sampling proxy and must not add energy on its own (see ARCHITECTURE.md).
  bool duplicates_emissive_mesh = false;
};

std::string_view to_string(LightType type);

}  // namespace prism
