#include "accel/bvh/homework/homework_bvh_builder.h"

#include <algorithm>
#include <tuple>

#include "core/error.h"

namespace prism {
namespace {

/// A node still to be built from prims[begin, end).
struct BuildTask {
  uint32_t begin, end;
  uint32_t parent;  ///< node whose right-child index this task fills; kNoParent for the root
  uint32_t depth;
};
constexpr uint32_t kNoParent = ~0u;

bool before(const HomeworkBuildPrimitive& a, const HomeworkBuildPrimitive& b, int axis) {
  if (a.centroid[axis] != b.centroid[axis]) return a.centroid[axis] < b.centroid[axis];
  return std::tie(a.id.geom_id, a.id.prim_id) < std::tie(b.id.geom_id, b.id.prim_id);
}

}  // namespace

std::vector<HomeworkBuildPrimitive> gather_homework_primitives(const SceneGeometry& geometry) {
  std::vector<HomeworkBuildPrimitive> prims;
  prims.reserve(geometry.primitive_count());
  for (uint32_t g = 0; g < geometry.meshes.size(); ++g) {
    const TriangleMesh& mesh = geometry.meshes[g];
    for (uint32_t i = 0; i < mesh.triangles.size(); ++i) {
      const glm::uvec3& tri = mesh.triangles[i];
      HomeworkBuildPrimitive p;
      p.bounds.extend(mesh.positions[tri.x]);
      p.bounds.extend(mesh.positions[tri.y]);
      p.bounds.extend(mesh.positions[tri.z]);
      p.centroid = p.bounds.center();
      p.id = {g, i};
      prims.push_back(p);
    }
  }
  const uint32_t sphere_geom = geometry.sphere_geom_id();
  for (uint32_t i = 0; i < geometry.spheres.size(); ++i) {
    const Sphere& s = geometry.spheres[i];
    prims.push_back({s.bounds(), s.center, {sphere_geom, i}});
  }
  return prims;
}

HomeworkBvh build_homework_bvh(std::vector<HomeworkBuildPrimitive> prims,
                               const HomeworkBvhOptions& options) {
  PRISM_CHECK(options.max_leaf_size >= 1);
  // Primitive indices and counts are 32-bit in the node layout.
  PRISM_CHECK(prims.size() < size_t(1) << 32);
  HomeworkBvh bvh;
  if (prims.empty()) return bvh;
  const uint32_t n = static_cast<uint32_t>(prims.size());
  bvh.nodes.reserve(2 * (n / options.max_leaf_size) + 1);

  // Depth-first with an explicit stack: a node is appended when its task is popped, and the
  // left task is pushed last, so a left child always directly follows its parent.
  std::vector<BuildTask> stack{{0, n, kNoParent, 0}};
  while (!stack.empty()) {
    const BuildTask task = stack.back();
    stack.pop_back();
    const uint32_t index = static_cast<uint32_t>(bvh.nodes.size());
    if (task.parent != kNoParent) bvh.nodes[task.parent].index = index;
    bvh.max_depth = std::max<size_t>(bvh.max_depth, task.depth);

    Bounds3 bounds, centroids;
    for (uint32_t i = task.begin; i < task.end; ++i) {
      bounds.extend(prims[i].bounds);
      centroids.extend(prims[i].centroid);
    }
    HomeworkBvhNode node{bounds.lower, task.begin, bounds.upper, task.end - task.begin};
    const uint32_t count = task.end - task.begin;
    if (count <= options.max_leaf_size) {
      bvh.nodes.push_back(node);
      continue;
    }
    node.count = 0;
    bvh.nodes.push_back(node);
    // Splitting at the median index (not the spatial middle) halves the count every level,
    // which bounds the depth even when all centroids coincide.
    const int axis = max_dimension(centroids.diagonal());
    const uint32_t mid = task.begin + count / 2;
    std::nth_element(prims.begin() + task.begin, prims.begin() + mid, prims.begin() + task.end,
                     [axis](const HomeworkBuildPrimitive& a, const HomeworkBuildPrimitive& b) {
                       return before(a, b, axis);
                     });
    stack.push_back({mid, task.end, index, task.depth + 1});
    stack.push_back({task.begin, mid, kNoParent, task.depth + 1});
  }
  bvh.prims.resize(prims.size());
  for (size_t i = 0; i < prims.size(); ++i) bvh.prims[i] = prims[i].id;
  return bvh;
}

}  // namespace prism
