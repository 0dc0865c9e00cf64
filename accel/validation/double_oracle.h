#pragma once

#include <cstdint>
#include <optional>

#include "core/ray.h"
#include "core/scene_geometry.h"

namespace prism {

/// A closest hit computed in double precision.
struct OracleHit {
  double t = 0.0;
  uint32_t geom_id = 0;
  uint32_t prim_id = 0;
};

/// How one ray meets one primitive, in double precision, with the slack float arithmetic needs:
/// enough to tell a real disagreement between backends from one decided by rounding.
struct PrimitiveProbe {
  /// The ray meets the primitive (inside the triangle / on the sphere) at t in [tmin, tmax].
  bool hit = false;
  /// Triangle: where the ray's line meets the triangle's plane (NaN when parallel or the
  /// triangle is degenerate). Sphere: the root in [tmin, tmax] intersect_sphere() would pick,
  /// else the root nearest to the interval, else (line misses) the point of closest approach.
  double t = 0.0;
  /// Distance from the ray's line to the primitive's boundary: to the nearest edge segment of a
  /// triangle (so vertices too), or |distance to the centre - radius| for a sphere's silhouette.
  double boundary_distance = 0.0;
  /// boundary_distance at or below this can be decided either way by float rounding: float
  /// tests work on vertex coordinates relative to the ray origin, whose rounding scales with
  /// the distance from the origin and the size of the coordinates.
  double boundary_tolerance = 0.0;
  /// A float t may differ from `t` by this much through rounding alone; it grows without bound
  /// as the ray becomes parallel to the triangle (or tangent to the sphere).
  double t_tolerance = 0.0;

  /// The ray passes so close to an edge, vertex or silhouette that hit or miss is rounding.
  bool grazes() const { return boundary_distance <= boundary_tolerance; }
  /// t lies within rounding of the ray's tmin or tmax, so in or out is rounding.
  bool near_interval_end(const Ray& ray) const;
};

/// Brute force over a scene's geometry in double precision: the judge for disagreements between
/// backends, and the engine of `prism validate`. Queries follow prepare_query() (invalid rays
/// hit nothing; a negative tmin counts as 0). Keeps a reference to `geometry`; thread-safe.
class DoubleOracle {
 public:
  /// Float rounding allowance of the tolerances above, in units of float epsilon times the
  /// problem's scale. Generous on purpose: only a disagreement far beyond it is a bug.
  static constexpr double kRoundingFactor = 64.0;

  explicit DoubleOracle(const SceneGeometry& geometry) : geometry_(geometry) {}

  /// The closest primitive the ray hits in [tmin, tmax] in double precision; exact ties go to
  /// the lower (geom_id, prim_id). O(primitives).
  std::optional<OracleHit> closest(const Ray& ray) const;

  /// How `ray` meets primitive (geom_id, prim_id); throws Error(kInternal) if there is none.
  /// An invalid ray (prepare_query()) gives a probe that neither hits nor grazes.
  PrimitiveProbe probe(const Ray& ray, uint32_t geom_id, uint32_t prim_id) const;

  const SceneGeometry& geometry() const { return geometry_; }

 private:
  const SceneGeometry& geometry_;
};

}  // namespace prism
