#pragma once

#include <vector>

#include "accel/bvh/build_reference.h"

namespace prism {

/// Builds a binary BVH over `refs` by object splits: binned SAH (settings.split == kSah) or the
/// homework's centroid median along the widest axis (kMedian). Runs in parallel (core/parallel.h);
/// the result does not depend on the thread count. Leaves hold at most settings.max_leaf_size
/// references and never mix spheres (geom_id == sphere_geom_id) with triangles. Depth stays
/// below kMaxBvhDepth.
BinaryBvh build_object_split_bvh(std::vector<PrimRef> refs, uint32_t sphere_geom_id,
                                 const BvhBuildSettings& settings);

}  // namespace prism
