#include "integrators/sampling/bilinear.h"

#include <algorithm>
#include <cmath>

namespace prism {

float sample_linear(float u, float a, float b) {
  if (u == 0.0f && a == 0.0f) return 0.0f;
  // The inverse of the CDF (a x + (b - a) x^2 / 2) / ((a + b) / 2), in the form that stays
  // accurate when a and b are close (no cancellation in the root's difference).
  const float x = u * (a + b) / (a + std::sqrt((1.0f - u) * a * a + u * b * b));
  return std::min(x, 0x1.fffffep-1f);
}

Vec2 sample_bilinear(Vec2 u, const BilinearCorners& w) {
  // x from the marginal (the sums of the corners on each side), then y given x.
  const float x = sample_linear(u.x, w[0] + w[2], w[1] + w[3]);
  const float y = sample_linear(u.y, (1.0f - x) * w[0] + x * w[1], (1.0f - x) * w[2] + x * w[3]);
  return {x, y};
}

float bilinear_pdf(Vec2 p, const BilinearCorners& w) {
  const float sum = w[0] + w[1] + w[2] + w[3];
  if (!(sum > 0.0f)) return 0.0f;
  const float value = (1.0f - p.x) * (1.0f - p.y) * w[0] + p.x * (1.0f - p.y) * w[1] +
                      (1.0f - p.x) * p.y * w[2] + p.x * p.y * w[3];
  return 4.0f * value / sum;
}

}  // namespace prism
