#pragma once

#include "core/math.h"

namespace prism {

/// Unpolarised Fresnel reflectance of a smooth dielectric boundary. `cos_i` is the cosine of
/// the incident direction with the normal on the side with index 1 (negative: incidence from
/// the other side); `eta` = index of the far side / index of the near side for cos_i > 0.
/// Returns 1 under total internal reflection.
float fresnel_dielectric(float cos_i, float eta);

/// Unpolarised Fresnel reflectance of a conductor with complex index eta + i k relative to the
/// outside medium, per channel; `cos_i` in [0, 1].
Rgb fresnel_conductor(float cos_i, const Rgb& eta, const Rgb& k);

}  // namespace prism
