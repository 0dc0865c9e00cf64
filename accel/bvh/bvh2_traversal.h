#pragma once

#include <optional>

#include "accel/bvh/bvh2.h"
#include "core/hit.h"
#include "core/ray.h"
#include "core/scene_geometry.h"

namespace prism {

/// Deepest tree the traversals accept (their stack is fixed-size); builders must stay below.
inline constexpr size_t kBvh2MaxDepth = 63;

/// The closest hit of `ray` (already through prepare_query()) among the primitives of `bvh`,
/// built over `geometry`. Visits the nearer child first. Gives bit for bit the hit brute force
/// gives: same primitive test, same comes_before() order, and box tests widened so that no box
/// is culled that holds a primitive whose computed t is still in range.
std::optional<Hit> bvh2_intersect(const Bvh2& bvh, const SceneGeometry& geometry, const Ray& ray);

/// Whether any primitive of `bvh` is hit in [ray.tmin, ray.tmax]; stops at the first hit.
/// Agrees with bvh2_intersect().has_value().
bool bvh2_occluded(const Bvh2& bvh, const SceneGeometry& geometry, const Ray& ray);

}  // namespace prism
