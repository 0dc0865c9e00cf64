#pragma once

// Plain data shared by the wide BVH's builders (object splits by binned SAH or median, spatial
// splits) and by the collapse into wide nodes: primitive references and the binary tree they build.

#include <cstdint>
#include <memory>
#include <vector>

#include "core/bounds.h"
#include "core/scene_geometry.h"

namespace prism {

/// One primitive (or, after a spatial split, the part of one inside a box) with its bounds.
/// Laid out as two 16-byte rows so that SSE min/max can merge bounds without shuffles; the
/// id lanes are never read as floats.
struct alignas(16) PrimRef {
  float lower[3];
  uint32_t geom_id;
  float upper[3];
  uint32_t prim_id;

  Bounds3 bounds() const {
    return {Vec3(lower[0], lower[1], lower[2]), Vec3(upper[0], upper[1], upper[2])};
  }
  /// Twice the centre along `axis` (builders bin on it; the factor 2 cancels).
  float center2(int axis) const { return lower[axis] + upper[axis]; }
};

/// How the binary tree is split.
enum class SplitMethod {
  kMedian,   ///< the homework's rule: the median primitive along the widest centroid axis
  kSah,      ///< binned surface area heuristic on centroids
  kSpatial,  ///< binned SAH plus spatial splits that clip long triangles (SBVH)
};

/// Builder parameters (`--set bvh.*`).
struct BvhBuildSettings {
  SplitMethod split = SplitMethod::kSah;
  int bins = 32;                ///< bins per axis for SAH and spatial splits
  float traversal_cost = 1;     ///< cost of visiting an interior node
  float leaf_cost = 1;          ///< cost of intersecting one block of kLeafBlockSize primitives
  int max_leaf_size = 64;       ///< primitives per leaf, at most kMaxLeafPrimitives
  float spatial_alpha = 1e-5f;  ///< try spatial splits when child overlap > alpha * root area
  float spatial_budget = 0.5f;  ///< extra references spatial splits may add, x primitive count
  int reinsertion_passes = 2;   ///< rounds of optimize_by_reinsertion() after the build
};

/// Primitives per SIMD block in a leaf; SAH charges leaves per started block.
inline constexpr int kLeafBlockSize = 4;
/// Largest leaf any builder emits (the wide layout encodes up to 16 blocks per leaf).
inline constexpr int kMaxLeafPrimitives = 64;
/// Depth the binary builders never exceed, so traversal stacks have a fixed size.
inline constexpr int kMaxBvhDepth = 64;

/// A node of the binary tree. Leaves reference refs [first, first + count); interior nodes
/// (count == 0) have children `first` and `first + 1`. Trivial on purpose: builders allocate
/// the worst-case node count up front without touching the memory.
struct BinaryNode {
  float lower[3];
  uint32_t first;
  float upper[3];
  uint32_t count;

  bool is_leaf() const { return count != 0; }
  Bounds3 bounds() const {
    return {Vec3(lower[0], lower[1], lower[2]), Vec3(upper[0], upper[1], upper[2])};
  }
  void set_bounds(const Bounds3& b) {
    for (int a = 0; a < 3; ++a) {
      lower[a] = b.lower[a];
      upper[a] = b.upper[a];
    }
  }
};

/// The output of every builder: node 0 is the root; an empty tree has no nodes.
struct BinaryBvh {
  std::unique_ptr<BinaryNode[]> nodes;
  size_t node_count = 0;
  std::vector<PrimRef> refs;  ///< leaf order
};

/// One reference per triangle and per sphere of `geometry` (spheres use sphere_geom_id()),
/// leaving out degenerate triangles (is_degenerate_triangle(): never hit), so a tree built from
/// them has no lane a kernel must check for degeneracy.
std::vector<PrimRef> make_prim_refs(const SceneGeometry& geometry);

/// Number of blocks of kLeafBlockSize needed for n primitives.
inline uint32_t leaf_blocks(uint32_t n) { return (n + kLeafBlockSize - 1) / kLeafBlockSize; }

}  // namespace prism
