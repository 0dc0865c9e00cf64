#pragma once

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/math.h"

namespace prism {

inline constexpr float kInvPi = 1.0f / kPi;
inline constexpr float kInv2Pi = 0.5f / kPi;
inline constexpr float kInv4Pi = 0.25f / kPi;

/// Luminance of a linear RGB value (Rec. 709 primaries).
inline float luminance(const Rgb& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

inline float safe_sqrt(float x) { return std::sqrt(std::max(0.0f, x)); }

/// Point on the unit disk from u in [0,1)^2, uniform in area (Shirley-Chiu concentric map).
Vec2 square_to_uniform_disk(Vec2 u);

/// Direction on the upper (z >= 0) hemisphere, density cos(theta) / pi.
Vec3 square_to_cosine_hemisphere(Vec2 u);
inline float cosine_hemisphere_pdf(float cos_theta) {
  return cos_theta > 0.0f ? cos_theta * kInvPi : 0.0f;
}

/// Direction on the upper (z >= 0) hemisphere, density 1 / (2 pi).
Vec3 square_to_uniform_hemisphere(Vec2 u);
inline float uniform_hemisphere_pdf() { return kInv2Pi; }

/// Direction on the unit sphere, density 1 / (4 pi).
Vec3 square_to_uniform_sphere(Vec2 u);
inline float uniform_sphere_pdf() { return kInv4Pi; }

/// Barycentric coordinates (b1, b2) of a point uniform in area on a triangle:
/// p = (1 - b1 - b2) p0 + b1 p1 + b2 p2.
Vec2 square_to_uniform_triangle(Vec2 u);

/// Solid angle that the triangle (a, b, c), given relative to the viewpoint, subtends there
/// (Van Oosterom and Strackee 1983): in [0, 2 pi), 0 for a degenerate triangle or one seen
/// edge-on. The vertices need not be unit vectors.
float triangle_solid_angle(const Vec3& a, const Vec3& b, const Vec3& c);

/// A unit direction uniform in solid angle over the spherical triangle with unit vertices
/// (a, b, c) and solid angle `solid_angle` (triangle_solid_angle(a, b, c), > 0), from u in
/// [0,1)^2 (Arvo, "Stratified Sampling of Spherical Triangles", 1995): density
/// 1 / solid_angle. Accurate in single precision for solid angles of about 1e-4 and more
/// (smaller ones are better sampled in area). Nothing when the triangle is degenerate.
std::optional<Vec3> sample_spherical_triangle(const Vec3& a, const Vec3& b, const Vec3& c,
                                              float solid_angle, Vec2 u);

/// Veach's power heuristic (beta = 2) for `nf` samples of density `f_pdf` against `ng` samples
/// of density `g_pdf`. Infinite f_pdf (a delta strategy) gives 1.
float power_heuristic(float nf, float f_pdf, float ng, float g_pdf);

}  // namespace prism
