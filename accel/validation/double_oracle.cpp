#include "accel/validation/double_oracle.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "accel/ray_query.h"
#include "core/error.h"

namespace prism {
namespace {

constexpr double kFloatEpsilon = 0x1p-24;  // unit roundoff of float
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

double max_abs(const DVec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

/// Where the line o + t d meets triangle (p0, p1, p2) in double, and whether inside.
struct TriangleCrossing {
  bool inside = false;
  double t = kNaN;
};

TriangleCrossing cross_triangle(const DVec3& o, const DVec3& d, const DVec3& p0, const DVec3& p1,
                                const DVec3& p2) {
  // Moeller-Trumbore: in double its rounding is far below anything a float test resolves.
  const DVec3 e1 = p1 - p0, e2 = p2 - p0;
  const DVec3 pvec = glm::cross(d, e2);
  const double det = glm::dot(e1, pvec);
  if (det == 0.0 || !std::isfinite(det)) return {};
  const DVec3 tvec = o - p0;
  const double u = glm::dot(tvec, pvec) / det;
  const DVec3 qvec = glm::cross(tvec, e1);
  const double v = glm::dot(d, qvec) / det;
  return {u >= 0.0 && v >= 0.0 && u + v <= 1.0, glm::dot(e2, qvec) / det};
}

/// Roots of |o + t d - c| = r in double, the nearer first; nothing when the line misses.
struct SphereRoots {
  bool real = false;
  double t0 = kNaN, t1 = kNaN;
  double closest_t = kNaN;      // parameter of the point of closest approach
  double line_distance = kNaN;  // distance from the centre to the line
};

SphereRoots sphere_roots(const DVec3& o, const DVec3& d, const DVec3& c, double r) {
  SphereRoots s;
  const DVec3 f = o - c;
  const double a = glm::dot(d, d);
  const double half_b = glm::dot(f, d);
  s.closest_t = -half_b / a;
  const DVec3 l = f - (half_b / a) * d;
  s.line_distance = glm::length(l);
  const double disc = a * (r * r - glm::dot(l, l));
  if (!(disc >= 0.0)) return s;
  s.real = true;
  const double q = -half_b - std::copysign(std::sqrt(disc), half_b);
  if (q == 0.0) {
    s.t0 = s.t1 = s.closest_t;
    return s;
  }
  s.t0 = (glm::dot(f, f) - r * r) / q;
  s.t1 = q / a;
  if (s.t0 > s.t1) std::swap(s.t0, s.t1);
  return s;
}

/// Distance between the line through o along unit direction `axis` and segment [a, b], with
/// the length of the segment projected onto the plane normal to the line.
double line_segment_distance(const DVec3& o, const DVec3& axis, const DVec3& a, const DVec3& b) {
  const auto perp = [&](const DVec3& x) { return x - glm::dot(x, axis) * axis; };
  const DVec3 w = perp(a - o);
  const DVec3 e = perp(b - a);
  const double ee = glm::dot(e, e);
  const double s = ee > 0.0 ? std::clamp(-glm::dot(w, e) / ee, 0.0, 1.0) : 0.0;
  return glm::length(w + s * e);
}

bool in_interval(double t, const Ray& ray) { return t >= ray.tmin && t <= ray.tmax; }

PrimitiveProbe probe_triangle(const Ray& ray, const DVec3& p0, const DVec3& p1, const DVec3& p2) {
  const DVec3 o(ray.origin), d(ray.direction);
  const double d_len = glm::length(d);
  const DVec3 axis = d / d_len;
  PrimitiveProbe p;
  const TriangleCrossing crossing = cross_triangle(o, d, p0, p1, p2);
  p.t = crossing.t;
  p.hit = crossing.inside && in_interval(crossing.t, ray);
  p.boundary_distance =
      std::min({line_segment_distance(o, axis, p0, p1), line_segment_distance(o, axis, p1, p2),
                line_segment_distance(o, axis, p2, p0)});
  // Float tests work on vertices relative to the origin: their rounding is about epsilon times
  // the distance to the origin plus the size of the coordinates themselves.
  const double reach = std::max({glm::length(p0 - o), glm::length(p1 - o), glm::length(p2 - o)});
  const double scale = reach + std::max({max_abs(o), max_abs(p0), max_abs(p1), max_abs(p2)});
  const double allowance = DoubleOracle::kRoundingFactor * kFloatEpsilon * scale;
  p.boundary_tolerance = allowance;
  const DVec3 normal = glm::cross(p1 - p0, p2 - p0);
  const double normal_len = glm::length(normal);
  const double incidence = normal_len > 0.0 ? std::abs(glm::dot(normal, axis)) / normal_len : 0.0;
  // A rounding error in the 2D hit decision moves t by that much over the sine of the angle
  // between the ray and the plane.
  p.t_tolerance = incidence > 0.0 ? allowance / (incidence * d_len) : kInf;
  return p;
}

PrimitiveProbe probe_sphere(const Ray& ray, const Sphere& sphere) {
  const DVec3 o(ray.origin), d(ray.direction), c(sphere.center);
  const double r = sphere.radius;
  const double d_len = glm::length(d);
  PrimitiveProbe p;
  const SphereRoots roots = sphere_roots(o, d, c, r);
  if (!roots.real) {
    p.t = roots.closest_t;
  } else if (in_interval(roots.t0, ray)) {
    p.t = roots.t0;
    p.hit = true;
  } else if (in_interval(roots.t1, ray)) {
    p.t = roots.t1;
    p.hit = true;
  } else {
    const auto gap = [&](double t) { return t < ray.tmin ? ray.tmin - t : t - ray.tmax; };
    p.t = gap(roots.t0) <= gap(roots.t1) ? roots.t0 : roots.t1;
  }
  p.boundary_distance = std::abs(roots.line_distance - r);
  const double scale = glm::length(o - c) + std::max(max_abs(o), max_abs(c)) + r;
  const double allowance = DoubleOracle::kRoundingFactor * kFloatEpsilon * scale;
  p.boundary_tolerance = allowance;
  // Near tangency t = closest_t +- half_chord / |d| and the half chord is a square root of a
  // difference: its rounding grows as the chord shrinks, up to about sqrt(epsilon * scale * r).
  const double half_chord =
      roots.real ? std::sqrt(std::max(0.0, r * r - roots.line_distance * roots.line_distance))
                 : 0.0;
  const double floor = std::sqrt(allowance * r);
  p.t_tolerance = (allowance + allowance * r / std::max(half_chord, floor)) / d_len;
  return p;
}

}  // namespace

bool PrimitiveProbe::near_interval_end(const Ray& ray) const {
  const std::optional<Ray> q = prepare_query(ray);
  if (!q || std::isnan(t)) return false;
  const double slack = t_tolerance + DoubleOracle::kRoundingFactor * kFloatEpsilon * std::abs(t);
  return std::abs(t - double(q->tmin)) <= slack ||
         (std::isfinite(q->tmax) && std::abs(t - double(q->tmax)) <= slack);
}

std::optional<OracleHit> DoubleOracle::closest(const Ray& ray) const {
  const std::optional<Ray> q = prepare_query(ray);
  if (!q) return std::nullopt;
  const DVec3 o(q->origin), d(q->direction);
  std::optional<OracleHit> best;
  const auto consider = [&](double t, uint32_t geom_id, uint32_t prim_id) {
    // Candidates come in (geom_id, prim_id) order, so keeping the first at equal t is the
    // tie rule.
    if (!best || t < best->t) best = OracleHit{t, geom_id, prim_id};
  };
  for (uint32_t g = 0; g < geometry_.meshes.size(); ++g) {
    const TriangleMesh& mesh = geometry_.meshes[g];
    for (uint32_t i = 0; i < mesh.triangles.size(); ++i) {
      const glm::uvec3& tri = mesh.triangles[i];
      const TriangleCrossing c =
          cross_triangle(o, d, DVec3(mesh.positions[tri.x]), DVec3(mesh.positions[tri.y]),
                         DVec3(mesh.positions[tri.z]));
      if (c.inside && in_interval(c.t, *q)) consider(c.t, g, i);
    }
  }
  for (uint32_t i = 0; i < geometry_.spheres.size(); ++i) {
    const Sphere& s = geometry_.spheres[i];
    const SphereRoots roots = sphere_roots(o, d, DVec3(s.center), s.radius);
    if (!roots.real) continue;
    if (in_interval(roots.t0, *q)) {
      consider(roots.t0, geometry_.sphere_geom_id(), i);
    } else if (in_interval(roots.t1, *q)) {
      consider(roots.t1, geometry_.sphere_geom_id(), i);
    }
  }
  return best;
}

PrimitiveProbe DoubleOracle::probe(const Ray& ray, uint32_t geom_id, uint32_t prim_id) const {
  const bool sphere = geom_id == geometry_.sphere_geom_id();
  const bool known = sphere ? prim_id < geometry_.spheres.size()
                            : geom_id < geometry_.meshes.size() &&
                                  prim_id < geometry_.meshes[geom_id].triangles.size();
  if (!known) {
    throw Error(ErrorKind::kInternal, "oracle probe of unknown primitive (geom " +
                                          std::to_string(geom_id) + ", prim " +
                                          std::to_string(prim_id) + ")");
  }
  const std::optional<Ray> q = prepare_query(ray);
  if (!q) {
    PrimitiveProbe none;
    none.t = kNaN;
    none.boundary_distance = kInf;
    return none;
  }
  if (sphere) return probe_sphere(*q, geometry_.spheres[prim_id]);
  const TriangleMesh& mesh = geometry_.meshes[geom_id];
  const glm::uvec3& tri = mesh.triangles[prim_id];
  return probe_triangle(*q, DVec3(mesh.positions[tri.x]), DVec3(mesh.positions[tri.y]),
                        DVec3(mesh.positions[tri.z]));
}

}  // namespace prism
