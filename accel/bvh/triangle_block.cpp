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

namespace {

struct LaneVertices {
  Vec3 v[3];
};

LaneVertices lane_vertices(const TriangleBlock& block, int lane) {
  LaneVertices out;
  for (int k = 0; k < 3; ++k) {
    out.v[k] = Vec3(block.p[k][0][lane], block.p[k][1][lane], block.p[k][2][lane]);
  }
  return out;
}

}  // namespace

bool intersect_block_lane(const WatertightRay& ray, const TriangleBlock& block, int lane,
                          PrimitiveHit& hit) {
  const LaneVertices l = lane_vertices(block, lane);
  const std::optional<PrimitiveHit> h = intersect_triangle(ray, l.v[0], l.v[1], l.v[2]);
  if (!h) return false;
  hit = *h;
  return true;
}

}  // namespace prism
