#pragma once

#include <cstdint>
#include <vector>

#include "accel/bvh/homework/homework_bvh.h"
#include "core/scene_geometry.h"

namespace prism {

/// Every primitive of `geometry` (triangles of mesh 0, 1, ..., then spheres), with bounds.
std::vector<HomeworkBuildPrimitive> gather_homework_primitives(const SceneGeometry& geometry);

/// Options of the homework's builder (`--set bvh.max_leaf_size`).
struct HomeworkBvhOptions {
  uint32_t max_leaf_size = 4;  ///< a node with at most this many primitives becomes a leaf
};

/// The homework's median split: each node is split on the largest axis of its centroid bounds
/// at the median primitive (both halves hold n/2 primitives) until it holds at most
/// max_leaf_size primitives. Iterative and depth-bounded: depth <= ceil(log2(n)) for any input,
/// including n identical primitives. Deterministic: equal centroids are ordered by
/// (geom_id, prim_id). Takes `prims` by value because it reorders them.
HomeworkBvh build_homework_bvh(std::vector<HomeworkBuildPrimitive> prims,
                               const HomeworkBvhOptions& options);

}  // namespace prism
