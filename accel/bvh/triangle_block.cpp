#include "accel/bvh/triangle_block.h"

namespace prism {

void fill_triangle_block(const SceneGeometry& geometry, const PrimRef* refs, int count,
                         TriangleBlock& block) {
  for (int lane = 0; lane < 4; ++lane) {
    const PrimRef& r = refs[lane < count ? lane : count - 1];
    const TriangleMesh& mesh = geometry.meshes[r.geom_id];
    const glm::uvec3 tri = mesh.triangles[r.prim_id];
    const Vec3 v[3] = {mesh.positions[tri.x], mesh.positions[tri.y], mesh.positions[tri.z]};
    for (int k = 0; k < 3; ++k) {
      for (int a = 0; a < 3; ++a) block.p[k][a][lane] = v[k][a];
    }
    block.geom_id[lane] = r.geom_id;
    block.prim_id[lane] = r.prim_id;
  }
}

bool intersect_block_lane(const WatertightRay& ray, const TriangleBlock& block, int lane,
                          PrimitiveHit& hit) {
  Vec3 v[3];
  for (int k = 0; k < 3; ++k)
    v[k] = Vec3(block.p[k][0][lane], block.p[k][1][lane], block.p[k][2][lane]);
  const std::optional<PrimitiveHit> h = intersect_triangle(ray, v[0], v[1], v[2]);
  if (!h) return false;
  hit = *h;
  return true;
}

}  // namespace prism
