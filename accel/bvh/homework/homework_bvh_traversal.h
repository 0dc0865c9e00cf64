#pragma once

#include <optional>

#include "accel/bvh/homework/homework_bvh.h"
#include "core/hit.h"
#include "core/ray.h"
#include "core/scene_geometry.h"

namespace prism {

/// Deepest tree the traversals accept (their stack is fixed-size); builders must stay below.
inline constexpr size_t kHomeworkBvhMaxDepth = 63;

/// The closest hit of `ray` (already through prepare_query()) among the primitives of `bvh`,
/// built over `geometry`. Visits the nearer child first. Gives bit for bit the hit brute force
/// gives: same primitive test, same comes_before() order, and box tests widened so that no box
/// is culled that holds a primitive whose computed t is still in range.
std::optional<Hit> homework_bvh_intersect(const HomeworkBvh& bvh, const SceneGeometry& geometry,
                                          const Ray& ray);

/// Whether any primitive of `bvh` is hit in [ray.tmin, ray.tmax]; stops at the first hit.
/// Agrees with homework_bvh_intersect().has_value().
bool homework_bvh_occluded(const HomeworkBvh& bvh, const SceneGeometry& geometry, const Ray& ray);

}  // namespace prism
