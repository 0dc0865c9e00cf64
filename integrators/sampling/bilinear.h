#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "core/math.h"

namespace prism {

/// Sampling in proportion to a bilinear function on the unit square (Hart, Pharr, Müller,
/// Lopes, McGuire and Shirley, "Practical Product Sampling by Fitting and Composing Warps",
/// EGSR 2020): the function's values at the corners (0,0), (1,0), (0,1), (1,1), each >= 0 and
/// not all 0. Cheap (two square roots and two divisions per sample), it follows a smooth density
/// such as an emitter's cos / distance^2 over its area (MeshLight).
using BilinearCorners = std::array<float, 4>;

// Inline: they run once per light sample, in a chain of dependent square roots and divisions
// that the caller's own work can then overlap.

/// x in [0, 1) with density proportional to (1 - x) a + x b (a, b >= 0, not both 0), from u in
/// [0, 1).
inline float sample_linear(float u, float a, float b) {
  if (u == 0.0f && a == 0.0f) return 0.0f;
  // The inverse of the CDF (a x + (b - a) x^2 / 2) / ((a + b) / 2), in the form that stays
  // accurate when a and b are close (no cancellation in the root's difference).
  const float x = u * (a + b) / (a + std::sqrt((1.0f - u) * a * a + u * b * b));
  return std::min(x, 0x1.fffffep-1f);
}

/// A point of the unit square with density bilinear_pdf(), from u in [0, 1)^2.
inline Vec2 sample_bilinear(Vec2 u, const BilinearCorners& w) {
  // x from the marginal (the sums of the corners on each side), then y given x.
  const float x = sample_linear(u.x, w[0] + w[2], w[1] + w[3]);
  const float y = sample_linear(u.y, (1.0f - x) * w[0] + x * w[1], (1.0f - x) * w[2] + x * w[3]);
  return {x, y};
}

/// The density on the unit square of sample_bilinear() at p (in [0, 1]^2).
inline float bilinear_pdf(Vec2 p, const BilinearCorners& w) {
  const float sum = w[0] + w[1] + w[2] + w[3];
  if (!(sum > 0.0f)) return 0.0f;
  const float value = (1.0f - p.x) * (1.0f - p.y) * w[0] + p.x * (1.0f - p.y) * w[1] +
                      (1.0f - p.x) * p.y * w[2] + p.x * p.y * w[3];
  return 4.0f * value / sum;
}

}  // namespace prism
