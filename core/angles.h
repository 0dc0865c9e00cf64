#pragma once

// Angles from coordinates without libm's general functions, where rendering computes them at
// every vertex or hit: a polynomial for single precision instead of atan2f.

namespace prism {

/// atan2(y, x) for y >= 0, in [0, pi], within 2.5e-7 of std::atan2 (a polynomial on [0, 1]
/// fitted for single precision, then the octant folded back), for the solid angles light
/// sampling computes at every vertex (71 instructions per camera sample fewer than with libm's
/// on CBspheres_lambertian, docs/PERFORMANCE.md, fifth round) and the u, v of sphere hits. NaN
/// when an input is NaN.
float atan2_nonnegative_y(float y, float x);

}  // namespace prism
