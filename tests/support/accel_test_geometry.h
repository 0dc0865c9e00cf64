#pragma once

// Rays and tiny hand-made scenes for the accelerator tests (tests/accel_*_test.cpp), whose hits
// are known exactly.

#include <utility>
#include <vector>

#include "core/math.h"
#include "core/ray.h"
#include "core/scene_geometry.h"

namespace prism::test {

/// The ray origin + t * direction over [tmin, tmax].
inline Ray ray(Vec3 origin, Vec3 direction, float tmin = 0.0f, float tmax = kInfinity) {
  Ray r;
  r.origin = origin;
  r.direction = direction;
  r.tmin = tmin;
  r.tmax = tmax;
  return r;
}

/// A mesh of the given triangles, finalized as loaders leave it.
inline TriangleMesh mesh_of(std::vector<Vec3> positions, std::vector<glm::uvec3> triangles) {
  TriangleMesh m;
  m.name = "test";
  m.positions = std::move(positions);
  m.triangles = std::move(triangles);
  m.finalize();
  return m;
}

/// The triangle (-1,-1,2), (1,-1,2), (-1,1,2): a ray from the origin towards (x, y, 2) hits it
/// at t = 1 with u = (x+1)/2, v = (y+1)/2 when the direction is (x/2, y/2, 1)*2.
inline SceneGeometry one_triangle() {
  SceneGeometry g;
  g.meshes.push_back(mesh_of({{-1, -1, 2}, {1, -1, 2}, {-1, 1, 2}}, {{0, 1, 2}}));
  return g;
}

/// Two triangles sharing the edge x = y in the plane z = 2 (a unit quad), a copy of the first
/// in a second mesh (coplanar duplicate), and a sphere of radius 1 at (5, 0, 2).
inline SceneGeometry quad_scene() {
  SceneGeometry g;
  TriangleMesh quad;
  quad.positions = {{0, 0, 2}, {1, 0, 2}, {1, 1, 2}, {0, 1, 2}};
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};
  quad.finalize();
  g.meshes.push_back(quad);
  TriangleMesh copy;
  copy.positions = {{0, 0, 2}, {1, 0, 2}, {1, 1, 2}};
  copy.triangles = {{0, 1, 2}};
  copy.finalize();
  g.meshes.push_back(copy);
  g.spheres.push_back({Vec3(5, 0, 2), 1.0f, 0});
  return g;
}

}  // namespace prism::test
