#include "integrators/sampling/spherical_rectangle.h"

#include <algorithm>
#include <cmath>

#include "core/angles.h"
#include "integrators/sampling/warp.h"

namespace prism {

std::optional<Rectangle> rectangle_from_corner(const Vec3& corner, const Vec3& p1, const Vec3& p2) {
  const Vec3 ex = p1 - corner, ey = p2 - corner;
  const float lx = glm::length(ex), ly = glm::length(ey);
  if (!(lx > 0.0f) || !(ly > 0.0f) || !std::isfinite(lx * ly)) return std::nullopt;
  if (!(std::abs(glm::dot(ex, ey)) <= kRectangleTolerance * lx * ly)) return std::nullopt;
  Rectangle r;
  r.corner = corner;
  r.unit_x = ex / lx;
  r.unit_y = ey / ly;
  r.normal = glm::normalize(glm::cross(r.unit_x, r.unit_y));
  r.length_x = lx;
  r.length_y = ly;
  return r;
}

Vec2 Rectangle::extent_of(const Vec3& q) const {
  const Vec3 o = q - corner;
  return {std::clamp(glm::dot(o, unit_x) / length_x, 0.0f, 1.0f),
          std::clamp(glm::dot(o, unit_y) / length_y, 0.0f, 1.0f)};
}

SphericalRectangle::SphericalRectangle(const Rectangle& rectangle, const Vec3& reference)
    : reference_(reference),
      unit_x_(rectangle.unit_x),
      unit_y_(rectangle.unit_y),
      unit_z_(rectangle.normal) {
  // The rectangle in the frame (unit_x, unit_y, unit_z) at the reference point: it spans
  // [x0, x1] x [y0, y1] on the plane z = z_signed; the construction takes z0 <= 0.
  const Vec3 d = rectangle.corner - reference;
  x0_ = glm::dot(d, unit_x_);
  y0_ = glm::dot(d, unit_y_);
  z_signed_ = glm::dot(d, unit_z_);
  z0_ = -std::abs(z_signed_);
  x1_ = x0_ + rectangle.length_x;
  y1_ = y0_ + rectangle.length_y;
  if (!(z0_ < 0.0f)) return;  // in the plane: nothing subtended
  // The planes through the reference point and each edge have normals with two non-zero
  // components each: (0, z0, -y0) / l0 for the edge y = y0, (-z0, 0, x1) / l1 for x = x1,
  // (0, -z0, y1) / l2 for y = y1 and (z0, 0, -x0) / l3 for x = x0. The spherical rectangle's
  // interior angles g0..g3 lie between neighbouring ones, and its solid angle is their sum less
  // 2 pi. Each angle as atan2(sine, cosine), both scaled by the two normals' lengths: the sine
  // is then |z0| times the distance to the corner they share; acos of the cosine would lose
  // most of its digits where the angle nears pi (points close to the rectangle's plane).
  const float z2 = z0_ * z0_;
  const float depth = -z0_;
  const auto corner_distance = [z2](float x, float y) { return std::sqrt(x * x + y * y + z2); };
  const float g0 = atan2_nonnegative_y(depth * corner_distance(x1_, y0_), x1_ * y0_);
  const float g1 = atan2_nonnegative_y(depth * corner_distance(x1_, y1_), -x1_ * y1_);
  const float g2 = atan2_nonnegative_y(depth * corner_distance(x0_, y1_), x0_ * y1_);
  const float g3 = atan2_nonnegative_y(depth * corner_distance(x0_, y0_), -x0_ * y0_);
  const float l0 = std::sqrt(z2 + y0_ * y0_);
  const float l2 = std::sqrt(z2 + y1_ * y1_);
  b0_ = -y0_ / l0;
  b1_ = y1_ / l2;
  k_ = 2.0f * kPi - g2 - g3;
  const float omega = g0 + g1 - k_;
  solid_angle_ = std::isfinite(omega) ? std::clamp(omega, 0.0f, 2.0f * kPi) : 0.0f;
}

std::optional<Vec3> SphericalRectangle::sample(Vec2 u) const {
  if (!(solid_angle_ > 0.0f)) return std::nullopt;
  // x: the sub-rectangle [x0, xu] subtends u.x of the solid angle.
  const float au = u.x * solid_angle_ + k_;
  const float fu = (std::cos(au) * b0_ - b1_) / std::sin(au);
  const float cu =
      std::clamp(std::copysign(1.0f, fu) / std::sqrt(fu * fu + b0_ * b0_), -1.0f, 1.0f);
  float xu = -(cu * z0_) / safe_sqrt(1.0f - cu * cu);
  if (std::isnan(xu)) return std::nullopt;
  xu = std::clamp(xu, x0_, x1_);
  // y: uniform in the sine of the elevation along the segment x = xu.
  const float dd = std::sqrt(xu * xu + z0_ * z0_);
  const float h0 = y0_ / std::sqrt(dd * dd + y0_ * y0_);
  const float h1 = y1_ / std::sqrt(dd * dd + y1_ * y1_);
  const float hv = h0 + u.y * (h1 - h0);
  const float hv2 = hv * hv;
  const float yv = hv2 < 1.0f - 1e-6f ? std::clamp(hv * dd / std::sqrt(1.0f - hv2), y0_, y1_)
                                      : (hv > 0.0f ? y1_ : y0_);
  const Vec3 q = reference_ + xu * unit_x_ + yv * unit_y_ + z_signed_ * unit_z_;
  if (!std::isfinite(q.x + q.y + q.z)) return std::nullopt;
  return q;
}

}  // namespace prism
