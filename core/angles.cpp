#include "core/angles.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/math.h"

namespace prism {

float atan2_nonnegative_y(float y, float x) {
  if (std::isnan(x) || std::isnan(y)) return std::numeric_limits<float>::quiet_NaN();
  const float ax = std::abs(x);
  const float low = std::min(ax, y), high = std::max(ax, y);
  if (!(high > 0.0f)) return 0.0f;
  // atan(a) = a P(a^2) on [0, 1]: degree 8 in a^2, fitted by iterated weighted least squares to
  // the minimax error, 1e-7 evaluated in float.
  const float a = low / high;
  const float z = a * a;
  const float p =
      0.99999988f +
      z * (-0.33332598f +
           z * (0.19985907f +
                z * (-0.14161229f +
                     z * (0.10498944f +
                          z * (-0.07234853f +
                               z * (0.03978117f + z * (-0.01440132f + z * 0.00245672f)))))));
  float r = a * p;
  if (y > ax) r = 0.5f * kPi - r;
  if (x < 0.0f) r = kPi - r;
  return r;
}

}  // namespace prism
