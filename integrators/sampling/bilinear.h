#pragma once

#include <array>

#include "core/math.h"

namespace prism {

/// Sampling in proportion to a bilinear function on the unit square (Hart, Pharr, Müller,
/// Lopes, McGuire and Shirley, "Practical Product Sampling by Fitting and Composing Warps",
/// EGSR 2020): the function's values at the corners (0,0), (1,0), (0,1), (1,1), each >= 0 and
/// not all 0. Cheap (two square roots and two divisions per sample), it follows a smooth density
/// such as an emitter's cos / distance^2 over its area (MeshLight).
using BilinearCorners = std::array<float, 4>;

/// x in [0, 1) with density proportional to (1 - x) a + x b (a, b >= 0, not both 0), from u in
/// [0, 1).
float sample_linear(float u, float a, float b);

/// A point of the unit square with density bilinear_pdf(), from u in [0, 1)^2.
Vec2 sample_bilinear(Vec2 u, const BilinearCorners& w);

/// The density on the unit square of sample_bilinear() at p (in [0, 1]^2).
float bilinear_pdf(Vec2 p, const BilinearCorners& w);

}  // namespace prism
