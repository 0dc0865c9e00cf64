#pragma once

#include <optional>
#include <span>
#include <string_view>

#include "accel/ray_query.h"
#include "core/error.h"
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
  double build_ms = 0.0;  ///< wall time of the last build(), validation included
};

/// Ray queries against a scene's triangles and spheres.
///
/// The contract every backend shares is enforced here, once:
/// - build() validates the geometry (Error(kInput) naming the element), times the build and
///   keeps a reference to `geometry`, which must outlive the accelerator and not change; only
///   then does it call the backend's build_structure(). It must run before any query.
/// - Queries follow accel/ray_query.h: a ray that cannot hit anything (non-finite, zero
///   direction, NaN or inverted bounds) misses without reaching the backend, and a negative
///   tmin counts as 0. A ray hits a primitive at t only if tmin <= t <= tmax (closed interval);
///   both faces of triangles count; the direction need not be normalised.
/// - After build() all queries are thread-safe.
/// Backends implement only what differs: the structure, the prepared queries, their statistics.
class Accelerator {
 public:
  virtual ~Accelerator() = default;
  /// The registry name ("brute", "bvh", "embree").
  virtual std::string_view name() const = 0;

  /// Validates `geometry`, builds the structure over it and keeps a reference to it. Throws
  /// Error on invalid geometry or when the backend fails (kResource when out of memory); the
  /// accelerator then answers no query until a later build() succeeds.
  void build(const SceneGeometry& geometry);

  /// The closest hit in [tmin, tmax] (exact ties: comes_before()), or nothing.
  std::optional<Hit> intersect(const Ray& ray) const {
    PRISM_CHECK(geometry_ != nullptr);
    if (is_prepared_query(ray)) return intersect_prepared(ray);
    const std::optional<Ray> prepared = prepare_query(ray);
    if (!prepared) return std::nullopt;
    return intersect_prepared(*prepared);
  }
  /// Whether any hit exists in [tmin, tmax]; agrees with intersect().has_value().
  bool occluded(const Ray& ray) const {
    PRISM_CHECK(geometry_ != nullptr);
    if (is_prepared_query(ray)) return occluded_prepared(ray);
    const std::optional<Ray> prepared = prepare_query(ray);
    if (!prepared) return false;
    return occluded_prepared(*prepared);
  }
  /// intersect() for each ray; hits.size() must equal rays.size().
  void intersect(std::span<const Ray> rays, std::span<std::optional<Hit>> hits) const;

  /// The backend's statistics of the last build, with its wall time.
  AccelStats stats() const;

 protected:
  /// Builds the backend's structure over `geometry`, already validated; build() keeps the
  /// reference. Throws Error on failure.
  virtual void build_structure(const SceneGeometry& geometry) = 0;
  /// The closest hit of a ray already through prepare_query(); see intersect().
  virtual std::optional<Hit> intersect_prepared(const Ray& ray) const = 0;
  /// Whether a ray already through prepare_query() hits anything; see occluded().
  virtual bool occluded_prepared(const Ray& ray) const = 0;
  /// nodes, leaves, depth, bytes and SAH cost of the structure (build_ms is filled by stats()).
  virtual AccelStats structure_stats() const = 0;

  /// The geometry of the last successful build().
  const SceneGeometry& geometry() const {
    PRISM_CHECK(geometry_ != nullptr);
    return *geometry_;
  }

 private:
  const SceneGeometry* geometry_ = nullptr;
  double build_ms_ = 0.0;
};

/// The table of accelerators: brute, bvh, embree. Parameters are read from `params` with the
/// backend's name as prefix ("bvh.max_leaf_size").
const Registry<Accelerator>& accelerator_registry();

}  // namespace prism
