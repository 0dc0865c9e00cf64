#pragma once

#include <cstdint>
#include <functional>
#include <optional>

#include "core/math.h"
#include "tests/support/statistics.h"

namespace prism::test {

/// Settings of directional_chi_square().
struct DirectionalChiSquareOptions {
  int theta_bins = 20;  ///< cells in cos(theta) over [-1, 1]: equal solid angle per row
  int phi_bins = 40;    ///< cells in phi over [0, 2 pi)
  size_t samples = 100000;
  uint64_t seed = 1;
};

/// Draws a unit direction from (u_1d, u_2d) in [0,1) x [0,1)^2, or nothing (a failed sample).
using DirectionSampler = std::function<std::optional<Vec3>(float, Vec2)>;
/// Solid-angle density of the sampler at a unit direction (0 where it never samples).
using DirectionPdf = std::function<double(const Vec3&)>;

/// Chi-square goodness of fit of a direction sampler against its claimed density: sampled
/// directions are binned on the sphere and compared with the density integrated over each cell
/// (6 x 6 Gauss-Legendre per cell). Failed samples form one more cell, expected to hold the
/// density's missing mass, so a density that integrates to less than 1 is tested too.
ChiSquareResult directional_chi_square(const DirectionSampler& sample, const DirectionPdf& pdf,
                                       const DirectionalChiSquareOptions& options = {});

}  // namespace prism::test
