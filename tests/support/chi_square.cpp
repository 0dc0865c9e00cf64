#include "tests/support/chi_square.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/sampler.h"

namespace prism::test {
namespace {

constexpr double kGaussNodes[6] = {-0.9324695142031521, -0.6612093864662645, -0.2386191860831969,
                                   0.2386191860831969,  0.6612093864662645,  0.9324695142031521};
constexpr double kGaussWeights[6] = {0.1713244923791704, 0.3607615730481386, 0.4679139345726910,
                                     0.4679139345726910, 0.3607615730481386, 0.1713244923791704};
constexpr double kTwoPi = 6.283185307179586;

Vec3 direction_of(double cos_theta, double phi) {
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  return Vec3(float(sin_theta * std::cos(phi)), float(sin_theta * std::sin(phi)), float(cos_theta));
}

/// Midpoint rule with n x n points over the cell [z0, z0 + dz] x [phi0, phi0 + dphi].
double midpoint_integral(const DirectionPdf& pdf, double z0, double dz, double phi0, double dphi,
                         int n) {
  double sum = 0.0;
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      sum += pdf(direction_of(z0 + (a + 0.5) / n * dz, phi0 + (b + 0.5) / n * dphi));
    }
  }
  return sum * dz * dphi / (double(n) * n);
}

/// Integral of the density over the cell [z0, z0 + dz] x [phi0, phi0 + dphi] (in cos theta
/// and phi, so the measure is solid angle). Gauss-Legendre where the density is smooth; where
/// it vanishes on part of the cell (the edge of a light, the horizon) a fine midpoint rule,
/// since a polynomial rule cannot see a discontinuity.
double cell_integral(const DirectionPdf& pdf, double z0, double dz, double phi0, double dphi) {
  constexpr int kProbe = 8;
  int zeros = 0;
  for (int a = 0; a < kProbe; ++a) {
    for (int b = 0; b < kProbe; ++b) {
      const double p =
          pdf(direction_of(z0 + (a + 0.5) / kProbe * dz, phi0 + (b + 0.5) / kProbe * dphi));
      zeros += p > 0.0 ? 0 : 1;
    }
  }
  if (zeros == 0) {
    double sum = 0.0;
    for (int a = 0; a < 6; ++a) {
      const double z = z0 + 0.5 * (kGaussNodes[a] + 1.0) * dz;
      for (int b = 0; b < 6; ++b) {
        const double phi = phi0 + 0.5 * (kGaussNodes[b] + 1.0) * dphi;
        sum += kGaussWeights[a] * kGaussWeights[b] * pdf(direction_of(z, phi));
      }
    }
    return sum * 0.25 * dz * dphi;
  }
  // A cell that looked empty is still searched for slivers of support, more coarsely.
  return midpoint_integral(pdf, z0, dz, phi0, dphi, zeros == kProbe * kProbe ? 24 : 64);
}

}  // namespace

ChiSquareResult directional_chi_square(const DirectionSampler& sample, const DirectionPdf& pdf,
                                       const DirectionalChiSquareOptions& options) {
  const int nt = options.theta_bins, np = options.phi_bins;
  const size_t cells = size_t(nt) * np;
  std::vector<double> observed(cells + 1, 0.0), expected(cells + 1, 0.0);

  IndependentSampler rng(options.seed);
  for (size_t i = 0; i < options.samples; ++i) {
    rng.start_pixel_sample({int(i & 0xffff), int(i >> 16)}, 0);
    const float u1 = rng.get_1d();
    const Vec2 u2 = rng.get_2d();
    const std::optional<Vec3> w = sample(u1, u2);
    if (!w || !is_finite(*w)) {
      observed[cells] += 1.0;
      continue;
    }
    const Vec3 d = glm::normalize(*w);
    const double z = std::clamp(double(d.z), -1.0, 1.0);
    double phi = std::atan2(double(d.y), double(d.x));
    if (phi < 0.0) phi += kTwoPi;
    const int it = std::clamp(int((z + 1.0) * 0.5 * nt), 0, nt - 1);
    const int ip = std::clamp(int(phi / kTwoPi * np), 0, np - 1);
    observed[size_t(it) * np + ip] += 1.0;
  }

  double total = 0.0;
  const double dz = 2.0 / nt, dphi = kTwoPi / np;
  for (int it = 0; it < nt; ++it) {
    for (int ip = 0; ip < np; ++ip) {
      const double z0 = -1.0 + it * dz, phi0 = ip * dphi;
      double integral = cell_integral(pdf, z0, dz, phi0, dphi);
      // Samples where the density seemed to vanish: look much closer before calling them
      // impossible (a thin sliver of support along the cell's edge).
      if (integral == 0.0 && observed[size_t(it) * np + ip] > 0.0) {
        integral = midpoint_integral(pdf, z0, dz, phi0, dphi, 256);
      }
      expected[size_t(it) * np + ip] = integral * double(options.samples);
      total += integral;
    }
  }
  expected[cells] = std::max(0.0, 1.0 - total) * double(options.samples);
  return chi_square_test(observed, expected);
}

}  // namespace prism::test
