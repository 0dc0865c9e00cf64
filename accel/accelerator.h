#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "core/hit.h"
#include "core/param_set.h"
#include "core/ray.h"
#include "core/registry.h"
#include "core/scene_geometry.h"

namespace prism {

/// Build statistics of an accelerator; fields that do not apply are 0.
struct AccelStats {
  size_t nodes = 0;
  size_t leaves = 0;
  size_t max_depth = 0;
  size_t bytes = 0;       ///< memory owned by the acceleration structure (not the scene)
  double sah_cost = 0.0;  ///< SAH cost with traversal cost 1 and intersection cost 1
  double build_ms = 0.0;  ///< wall time of the last build()
};

/// Ray queries against a scene's triangles and spheres.
/// Contract for every backend:
/// - build() must be called once before any query; it keeps a reference to `geometry`, which
///   must outlive the accelerator and not change. Throws Error on failure.
/// - After build() all queries are thread-safe.
/// - A ray hits a primitive at t only if ray.tmin <= t <= ray.tmax (closed interval); both faces
///   of triangles count; the direction need not be normalized.
class Accelerator {
 public:
  virtual ~Accelerator() = default;
  virtual std::string_view name() const = 0;
  virtual void build(const SceneGeometry& geometry) = 0;
  /// The closest hit in [tmin, tmax], or nothing.
  virtual std::optional<Hit> intersect(const Ray& ray) const = 0;
  /// Whether any hit exists in [tmin, tmax]; agrees with intersect().has_value().
  virtual bool occluded(const Ray& ray) const = 0;
  /// intersect() for each ray; hits.size() must equal rays.size().
  virtual void intersect(std::span<const Ray> rays, std::span<std::optional<Hit>> hits) const;
  virtual AccelStats stats() const = 0;
};

/// The table of accelerators: brute, bvh, embree. Parameters are read from `params` with the
/// backend's name as prefix ("bvh.max_leaf_size").
const Registry<Accelerator>& accelerator_registry();

}  // namespace prism
