#pragma once

#include <cmath>
#include <optional>

#include "core/lanes3.h"
#include "core/math.h"
#include "integrators/sampling/bilinear.h"

namespace prism {

/// A rectangle in space, by a corner and two orthogonal edges as unit vectors and lengths:
/// the form an emitter quad is sampled in (MeshLight). `normal` is cross(unit_x, unit_y).
struct Rectangle {
  Vec3 corner;
  Vec3 unit_x, unit_y, normal;
  float length_x = 0.0f, length_y = 0.0f;

  float area() const { return length_x * length_y; }
  /// The point at (u.x, u.y) of the rectangle's extent, uniform in area for u in [0,1)^2.
  Vec3 point_at(Vec2 u) const {
    return corner + (u.x * length_x) * unit_x + (u.y * length_y) * unit_y;
  }
  /// The (u.x, u.y) of point_at() nearest to `q`, clamped to [0, 1]^2.
  Vec2 extent_of(const Vec3& q) const;
};

/// For sample_bilinear() on the rectangle's extent (point_at()): the density uniform in solid
/// angle seen from `p`, cos / distance^2, at its four corners, up to one factor (1 /
/// distance^3: the cosine's distance to the plane is the same for all). Equal weights when
/// they are not finite (p at a corner, or distances beyond float's range). Inline, as
/// sample_bilinear() is.
inline BilinearCorners solid_angle_corners(const Rectangle& rectangle, const Vec3& p) {
  // The four corners' squared distances in the four lanes of one register (Lanes3, all of its
  // lanes): one square root and one division for all of them (this runs once per light sample).
  const Vec3 d = rectangle.corner - p;
  const float x0 = glm::dot(d, rectangle.unit_x), y0 = glm::dot(d, rectangle.unit_y);
  const float z = glm::dot(d, rectangle.normal);
  const float x1 = x0 + rectangle.length_x, y1 = y0 + rectangle.length_y;
  const Lanes3 x = {x0, x1, x0, x1}, y = {y0, y0, y1, y1};
  const Lanes3 r2 = x * x + y * y + z * z;
  const Lanes3 w = 1.0f / (r2 * square_roots(r2));
  const float sum = (w[0] + w[1]) + (w[2] + w[3]);
  if (!std::isfinite(sum) || !(sum > 0.0f)) return {1.0f, 1.0f, 1.0f, 1.0f};
  return {w[0], w[1], w[2], w[3]};
}

/// Relative tolerance of the rectangle tests: of the cosine between two edges, and of a fourth
/// corner's distance from where the rectangle puts it (MeshLight).
inline constexpr float kRectangleTolerance = 1e-5f;

/// The rectangle (corner, edges p1 - corner and p2 - corner) when those edges are orthogonal
/// and neither is degenerate, to kRectangleTolerance of the cosine of their angle; nothing
/// otherwise.
std::optional<Rectangle> rectangle_from_corner(const Vec3& corner, const Vec3& p1, const Vec3& p2);

/// A rectangle as seen from a reference point: the spherical rectangle it subtends there
/// (Urena, Fajardo and King, "An Area-Preserving Parametrization for Spherical Rectangles",
/// EGSR 2013). Directions drawn with sample() are uniform in its solid angle, density
/// 1 / solid_angle(). Float throughout: the solid angle, a sum of four angles less 2 pi, is within
/// about 6.4e-7 of the exact value, so small ones (MeshLight: below 1e-3) are better sampled in
/// area.
class SphericalRectangle {
 public:
  /// `rectangle` seen from `reference` (anywhere off its plane; on it the solid angle is 0).
  SphericalRectangle(const Rectangle& rectangle, const Vec3& reference);

  /// In [0, 2 pi]; 0 from the rectangle's plane.
  float solid_angle() const { return solid_angle_; }

  /// The point of the rectangle whose direction from the reference point is uniform in solid
  /// angle for u in [0,1)^2 (u.x sweeps the rectangle's x edge, u.y its y edge); nothing when
  /// the solid angle is 0 or rounding defeats the inversion.
  std::optional<Vec3> sample(Vec2 u) const;

 private:
  Vec3 reference_, unit_x_, unit_y_, unit_z_;
  float x0_ = 0.0f, x1_ = 0.0f, y0_ = 0.0f, y1_ = 0.0f;
  float z0_ = 0.0f;        ///< -|distance to the plane|
  float z_signed_ = 0.0f;  ///< the reference point's offset to the plane along `normal`
  float b0_ = 0.0f, b1_ = 0.0f, k_ = 0.0f;
  float solid_angle_ = 0.0f;
};

}  // namespace prism
