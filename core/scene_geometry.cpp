#include "core/scene_geometry.h"

#include <algorithm>
#include <string>

#include "core/error.h"

namespace prism {

Bounds3 TriangleMesh::bounds() const {
  Bounds3 b;
  for (const auto& t : triangles) {
    b.extend(positions[t.x]);
    b.extend(positions[t.y]);
    b.extend(positions[t.z]);
  }
  return b;
}

void TriangleMesh::finalize() { positions.reserve(positions.size() + 1); }

size_t SceneGeometry::triangle_count() const {
  size_t n = 0;
  for (const auto& m : meshes) n += m.triangle_count();
  return n;
}

Bounds3 SceneGeometry::bounds() const {
  Bounds3 b;
  for (const auto& m : meshes) b.extend(m.bounds());
  for (const auto& s : spheres) b.extend(s.bounds());
  return b;
}

void SceneGeometry::validate() const {
  for (size_t i = 0; i < meshes.size(); ++i) {
    const TriangleMesh& m = meshes[i];
    const ErrorLocation where{{}, 0, "mesh '" + m.name + "'"};
    for (const Vec3& p : m.positions) {
      if (!is_finite(p)) throw Error(ErrorKind::kInput, "vertex position is not finite", where);
    }
    for (const auto& t : m.triangles) {
      if (t.x >= m.positions.size() || t.y >= m.positions.size() || t.z >= m.positions.size()) {
        throw Error(
            ErrorKind::kInput,
            "triangle index out of range (" + std::to_string(m.positions.size()) + " vertices)",
            where);
      }
    }
    if (!m.normals.empty() && m.normals.size() != 3 * m.triangles.size()) {
      throw Error(ErrorKind::kInput, "per-corner normal count does not match triangles", where);
    }
    if (!m.uvs.empty() && m.uvs.size() != 3 * m.triangles.size()) {
      throw Error(ErrorKind::kInput, "per-corner uv count does not match triangles", where);
    }
  }
  for (size_t i = 0; i < spheres.size(); ++i) {
    const Sphere& s = spheres[i];
    if (!is_finite(s.center) || !std::isfinite(s.radius) || s.radius <= 0.0f) {
      throw Error(ErrorKind::kInput, "sphere needs a finite centre and a positive radius",
                  {{}, 0, "sphere " + std::to_string(i)});
    }
  }
}

void SceneGeometry::finalize() {
  for (auto& m : meshes) m.finalize();
}

}  // namespace prism
