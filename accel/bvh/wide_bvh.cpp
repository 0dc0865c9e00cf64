#include "accel/bvh/wide_bvh.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"

namespace prism {
namespace {

float node_area(const BinaryNode& n) { return n.bounds().area(); }

/// `plane` moved outward by `by` (>= 0), rounded outward: toward -inf for a lower plane, +inf
/// for an upper one. Infinite planes (empty slots) stay as they are.
float widened_plane(float plane, double by, bool upper) {
  const double exact = upper ? double(plane) + by : double(plane) - by;
  float f = static_cast<float>(exact);
  if (upper ? double(f) < exact : double(f) > exact) {
    f = std::nextafter(f, upper ? kInfinity : -kInfinity);
  }
  return f;
}

template <int W>
class Collapser {
 public:
  Collapser(const BinaryBvh& binary, const SceneGeometry& geometry, WideBvh<W>& out)
      : binary_(binary), geometry_(geometry), out_(out) {}

  void run() {
    out_.empty = binary_.node_count == 0;
    if (out_.empty) return;
    const Bounds3 root_bounds = binary_.nodes[0].bounds();
    root_area_ = root_bounds.area();
    out_.nodes.reserve(binary_.node_count / (W - 1) + 1);
    out_.root = collapse(0, 1);
    if (triangle_blocks_ > kLeafFirstMask || sphere_blocks_ > kLeafFirstMask) {
      throw Error(ErrorKind::kResource, "scene too large for the wide BVH's leaf encoding");
    }
    fill_leaves();
    pad_boxes();

    AccelStats& s = out_.stats;
    s.nodes = out_.nodes.size();
    s.leaves = leaves_;
    s.max_depth = static_cast<size_t>(max_depth_);
    s.bytes = out_.nodes.size() * sizeof(WideNode<W>) +
              out_.triangle_blocks.size() * sizeof(TriangleBlock) +
              out_.sphere_blocks.size() * sizeof(SphereBlock);
    s.sah_cost = root_area_ > 0.0f ? sah_ / root_area_ : 0.0;
  }

 private:
  struct LeafJob {
    uint32_t binary_node;
    uint32_t first_block;
    bool spheres;
  };

  uint32_t collapse(uint32_t binary_index, int depth) {
    max_depth_ = std::max(max_depth_, depth);
    const BinaryNode& bn = binary_.nodes[binary_index];
    if (bn.is_leaf()) return make_leaf(binary_index);
    sah_ += node_area(bn);

    uint32_t kids[W];
    kids[0] = bn.first;
    kids[1] = bn.first + 1;
    int count = 2;
    // Adopt grandchildren through the largest interior child: large boxes are the ones most
    // rays enter, so opening them saves the most node visits.
    while (count < W) {
      int best = -1;
      float best_area = -1.0f;
      for (int i = 0; i < count; ++i) {
        const BinaryNode& c = binary_.nodes[kids[i]];
        if (c.is_leaf()) continue;
        const float a = node_area(c);
        if (a > best_area) {
          best_area = a;
          best = i;
        }
      }
      if (best < 0) break;
      const uint32_t first = binary_.nodes[kids[best]].first;
      kids[best] = first;
      kids[count++] = first + 1;
    }

    WideNode<W> node;
    for (int i = 0; i < W; ++i) {
      for (int a = 0; a < 3; ++a) {
        node.bounds[2 * a][i] = kInfinity;
        node.bounds[2 * a + 1][i] = -kInfinity;
      }
      node.child[i] = 0;
    }
    const auto index = static_cast<uint32_t>(out_.nodes.size());
    out_.nodes.emplace_back();
    for (int i = 0; i < count; ++i) {
      const BinaryNode& c = binary_.nodes[kids[i]];
      for (int a = 0; a < 3; ++a) {
        node.bounds[2 * a][i] = c.lower[a];
        node.bounds[2 * a + 1][i] = c.upper[a];
      }
      node.child[i] = collapse(kids[i], depth + 1);
    }
    out_.nodes[index] = node;
    return index;
  }

  uint32_t make_leaf(uint32_t binary_index) {
    const BinaryNode& bn = binary_.nodes[binary_index];
    const bool spheres = binary_.refs[bn.first].geom_id == geometry_.sphere_geom_id();
    const uint32_t blocks = leaf_blocks(bn.count);
    PRISM_CHECK(blocks <= kMaxLeafBlocks);
    uint32_t& counter = spheres ? sphere_blocks_ : triangle_blocks_;
    const uint32_t first = counter;
    counter += blocks;
    jobs_.push_back({binary_index, first, spheres});
    ++leaves_;
    sah_ += static_cast<double>(node_area(bn)) * bn.count;
    return make_leaf_ref(first, blocks, spheres);
  }

  void fill_leaves() {
    out_.triangle_blocks.resize(triangle_blocks_);
    out_.sphere_blocks.resize(sphere_blocks_);
    triangle_leaf_size_.assign(triangle_blocks_, 0.0f);
    sphere_leaf_size_.assign(sphere_blocks_, 0.0f);
    parallel_for_range(
        jobs_.size(),
        [&](size_t begin, size_t end) {
          for (size_t j = begin; j < end; ++j) fill_leaf(jobs_[j]);
        },
        1024);
  }

  void fill_leaf(const LeafJob& job) {
    const BinaryNode& bn = binary_.nodes[job.binary_node];
    const PrimRef* refs = binary_.refs.data() + bn.first;
    const int count = static_cast<int>(bn.count);
    for (int b = 0; b * kLeafBlockSize < count; ++b) {
      const int n = std::min(kLeafBlockSize, count - b * kLeafBlockSize);
      const PrimRef* block_refs = refs + b * kLeafBlockSize;
      if (job.spheres) {
        SphereBlock& sb = out_.sphere_blocks[job.first_block + b];
        for (int lane = 0; lane < 4; ++lane)
          sb.sphere[lane] = block_refs[std::min(lane, n - 1)].prim_id;
      } else {
        fill_triangle_block(geometry_, block_refs, n, out_.triangle_blocks[job.first_block + b]);
      }
    }
    float size = 0.0f;
    for (int i = 0; i < count; ++i) size = std::max(size, primitive_size(refs[i]));
    (job.spheres ? sphere_leaf_size_ : triangle_leaf_size_)[job.first_block] = size;
  }

  /// The largest extent of the whole primitive (not of a spatial split's part of it): its box's
  /// largest side, a sphere's diameter.
  float primitive_size(const PrimRef& r) const {
    if (r.geom_id == geometry_.sphere_geom_id()) return 2.0f * geometry_.spheres[r.prim_id].radius;
    const TriangleMesh& mesh = geometry_.meshes[r.geom_id];
    const glm::uvec3 tri = mesh.triangles[r.prim_id];
    return triangle_size(mesh.positions[tri.x], mesh.positions[tri.y], mesh.positions[tri.z]);
  }

  /// Widens every child box by kBoxSizePaddingUlps ulps of the largest primitive under it and
  /// kBoxCoordinatePaddingUlps ulps of its largest |coordinate| (core/ray.h): the part of the
  /// traversal's padding that depends on the box, not on the ray.
  /// Children come after their parents in `nodes`, so one backward pass sees every child's size
  /// before its parent's.
  void pad_boxes() {
    std::vector<float> node_size(out_.nodes.size(), 0.0f);
    const double size_unit = double(kBoxSizePaddingUlps) / (1 << 24);
    const double coordinate_unit = double(kBoxCoordinatePaddingUlps) / (1 << 24);
    for (size_t index = out_.nodes.size(); index-- > 0;) {
      WideNode<W>& node = out_.nodes[index];
      float largest = 0.0f;
      for (int i = 0; i < W; ++i) {
        if (!(node.bounds[0][i] <= node.bounds[1][i])) continue;  // empty slot
        const uint32_t c = node.child[i];
        float size;
        if ((c & kLeafFlag) == 0) {
          size = node_size[c];
        } else {
          const uint32_t first = c & kLeafFirstMask;
          size = (c & kSphereLeafFlag) != 0 ? sphere_leaf_size_[first] : triangle_leaf_size_[first];
        }
        largest = std::max(largest, size);
        double coordinate = 0.0;
        for (int a = 0; a < 6; ++a)
          coordinate = std::max(coordinate, double(std::abs(node.bounds[a][i])));
        const double by = size_unit * size + coordinate_unit * coordinate;
        for (int a = 0; a < 3; ++a) {
          node.bounds[2 * a][i] = widened_plane(node.bounds[2 * a][i], by, false);
          node.bounds[2 * a + 1][i] = widened_plane(node.bounds[2 * a + 1][i], by, true);
        }
      }
      node_size[index] = largest;
    }
    triangle_leaf_size_ = {};
    sphere_leaf_size_ = {};
  }

  const BinaryBvh& binary_;
  const SceneGeometry& geometry_;
  WideBvh<W>& out_;
  std::vector<LeafJob> jobs_;
  /// The largest primitive size of each leaf, by the leaf's first block (fill_leaf()).
  std::vector<float> triangle_leaf_size_, sphere_leaf_size_;
  uint32_t triangle_blocks_ = 0;
  uint32_t sphere_blocks_ = 0;
  size_t leaves_ = 0;
  int max_depth_ = 0;
  float root_area_ = 0.0f;
  double sah_ = 0.0;
};

}  // namespace

template <int W>
WideBvh<W> collapse_to_wide(const BinaryBvh& binary, const SceneGeometry& geometry) {
  WideBvh<W> out;
  Collapser<W>(binary, geometry, out).run();
  return out;
}

template WideBvh<2> collapse_to_wide<2>(const BinaryBvh&, const SceneGeometry&);
template WideBvh<4> collapse_to_wide<4>(const BinaryBvh&, const SceneGeometry&);
template WideBvh<8> collapse_to_wide<8>(const BinaryBvh&, const SceneGeometry&);

}  // namespace prism
