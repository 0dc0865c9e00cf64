#pragma once

// Query conventions shared by every backend and by the double-precision oracle, so that they
// differ only in traversal and arithmetic, never in what counts as a valid ray or a closer hit.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

#include "core/hit.h"
#include "core/math.h"
#include "core/ray.h"

namespace prism {

/// Whether a backend traces `ray` at all. A ray with a non-finite origin or direction, a zero
/// direction, a NaN bound or max(tmin, 0) > tmax hits nothing (occluded() is false).
inline bool is_traceable(const Ray& ray) {
  return is_finite(ray.origin) && is_finite(ray.direction) && ray.direction != Vec3(0.0f) &&
         !std::isnan(ray.tmin) && !std::isnan(ray.tmax) && std::max(ray.tmin, 0.0f) <= ray.tmax;
}

/// The ray a backend actually traces for `ray`, or nothing when it is not traceable
/// (is_traceable()). Rays start at their origin: a negative tmin counts as 0 (Embree cannot
/// search behind the origin consistently, so no backend does).
inline std::optional<Ray> prepare_query(const Ray& ray) {
  if (!is_traceable(ray)) return std::nullopt;
  Ray out = ray;
  out.tmin = ray.tmin > 0.0f ? ray.tmin : 0.0f;  // -0 becomes +0 too
  return out;
}

/// Whether prepare_query(ray) would return `ray` itself unchanged (traceable, tmin +0 or more,
/// as every ray the integrators make): then the ray is traced as it is, without the copy, whose
/// 4-byte tmin store and 16-byte reload stall the store forwarding.
inline bool is_prepared_query(const Ray& ray) {
  return !std::signbit(ray.tmin) && is_traceable(ray);
}

/// The closest-hit order: smaller t first; at exactly equal t the lower (geom_id, prim_id)
/// wins. Every backend that does its own traversal applies it, so brute and bvh agree even on
/// exact ties. Returns whether the candidate comes before `best`.
inline bool comes_before(float t, uint32_t geom_id, uint32_t prim_id, const Hit& best) {
  if (t != best.t) return t < best.t;
  if (geom_id != best.geom_id) return geom_id < best.geom_id;
  return prim_id < best.prim_id;
}

}  // namespace prism
