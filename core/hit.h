#pragma once

#include <cstdint>

namespace prism {

/// The result of a closest-hit query, identical in meaning for every accelerator.
/// - t: ray parameter of the hit, in [ray.tmin, ray.tmax].
/// - u, v: Embree's barycentric convention for triangles, p = (1-u-v) p0 + u p1 + v p2;
///   for spheres, u = phi / 2pi and v = theta / pi of the hit point around the centre.
/// - geom_id: index of the triangle mesh in SceneGeometry::meshes, or
///   SceneGeometry::sphere_geom_id() for the spheres.
/// - prim_id: triangle index within that mesh, or sphere index.
/// - vertex_lanes: optional (null from most accelerators): the hit triangle's vertex positions
///   in the accelerator's own memory, coordinate a of vertex k at vertex_lanes[4 * (3 * k + a)],
///   the same floats as the mesh's positions of its triangle's corners. Lets
///   Scene::surface_at() read them where the traversal just did instead of through the mesh's
///   index and position arrays. Valid while the accelerator lives.
struct Hit {
  float t = 0.0f;
  float u = 0.0f;
  float v = 0.0f;
  uint32_t geom_id = 0;
  uint32_t prim_id = 0;
  const float* vertex_lanes = nullptr;
};

}  // namespace prism
