#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/bounds.h"
#include "core/ray.h"
#include "core/scene_geometry.h"

namespace prism {

/// `count` random rays around `bounds` (an empty box counts as [-1, 1]^3), a pure function of
/// (bounds, count, seed) on every platform. Origins are inside the box or in a margin around
/// it; directions are uniform on the sphere or aimed at a point of the box, some scaled away
/// from unit length; most rays cover [0, inf], the rest have a finite tmin, tmax or both.
std::vector<Ray> random_rays(const Bounds3& bounds, size_t count, uint64_t seed);

/// `count` rays aimed exactly at features where rounding decides: triangle vertices, edge
/// midpoints and random edge points (direction = target - origin, so t = 1 at the target;
/// some rays end or start exactly there), and points near sphere silhouettes. Empty when the
/// geometry has no primitives. Deterministic in the seed.
std::vector<Ray> feature_rays(const SceneGeometry& geometry, size_t count, uint64_t seed);

/// The ray as hex floats ("origin=(0x1p+0, ...) direction=(...) tmin=0x0p+0 tmax=inf"), exact
/// so that a failing ray can be replayed with parse_ray().
std::string format_ray(const Ray& ray);

/// Reads format_ray()'s output back; nothing if `text` is not in that form.
std::optional<Ray> parse_ray(const std::string& text);

}  // namespace prism
