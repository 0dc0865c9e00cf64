#include "accel/bvh/build_reference.h"

#include "core/parallel.h"
#include "core/primitive_intersection.h"

namespace prism {

std::vector<PrimRef> make_prim_refs(const SceneGeometry& geometry) {
  std::vector<PrimRef> refs(geometry.primitive_count());
  // Degenerate triangles are never hit (triangle_hit_parameters()), so the tree leaves them out
  // and the kernels need not test for them on every hit.
  std::vector<uint8_t> degenerate(refs.size(), 0);
  size_t offset = 0;
  for (size_t m = 0; m < geometry.meshes.size(); ++m) {
    const TriangleMesh& mesh = geometry.meshes[m];
    const auto geom_id = static_cast<uint32_t>(m);
    PrimRef* out = refs.data() + offset;
    parallel_for_range(
        mesh.triangles.size(),
        [&](size_t begin, size_t end) {
          for (size_t i = begin; i < end; ++i) {
            const glm::uvec3 t = mesh.triangles[i];
            const Vec3& p0 = mesh.positions[t.x];
            const Vec3& p1 = mesh.positions[t.y];
            const Vec3& p2 = mesh.positions[t.z];
            degenerate[offset + i] = is_degenerate_triangle(p0, p1, p2) ? 1 : 0;
            Bounds3 b;
            b.extend(p0);
            b.extend(p1);
            b.extend(p2);
            PrimRef& r = out[i];
            for (int a = 0; a < 3; ++a) {
              r.lower[a] = b.lower[a];
              r.upper[a] = b.upper[a];
            }
            r.geom_id = geom_id;
            r.prim_id = static_cast<uint32_t>(i);
          }
        },
        16 * 1024);
    offset += mesh.triangles.size();
  }
  for (size_t i = 0; i < geometry.spheres.size(); ++i) {
    const Bounds3 b = geometry.spheres[i].bounds();
    PrimRef& r = refs[offset + i];
    for (int a = 0; a < 3; ++a) {
      r.lower[a] = b.lower[a];
      r.upper[a] = b.upper[a];
    }
    r.geom_id = geometry.sphere_geom_id();
    r.prim_id = static_cast<uint32_t>(i);
  }
  size_t kept = 0;
  for (size_t i = 0; i < refs.size(); ++i) {
    if (!degenerate[i]) refs[kept++] = refs[i];
  }
  refs.resize(kept);
  return refs;
}

}  // namespace prism
