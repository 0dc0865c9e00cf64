#include "accel/bvh/binned_sah_builder.h"

#include <algorithm>
#include <atomic>

#include "accel/bvh/sah_binning.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/parallel_reduce.h"

namespace prism {
namespace {

// Below these sizes the work is too small to pay for a task.
constexpr uint32_t kParallelRecursion = 4096;
constexpr uint32_t kParallelScan = 64 * 1024;
constexpr size_t kScanGrain = 16 * 1024;
// Past this depth every split halves the range, so the total depth stays below kMaxBvhDepth
// even for 2^26 references.
constexpr int kBalancedDepth = kMaxBvhDepth - 28;

sah::RangeInfo range_info(const PrimRef* refs, size_t n) {
  if (n < kParallelScan) {
    sah::RangeInfo info;
    for (size_t i = 0; i < n; ++i) info.add(refs[i]);
    return info;
  }
  return parallel_reduce(
      0, n, kScanGrain, sah::RangeInfo(),
      [&](size_t begin, size_t end, sah::RangeInfo info) {
        for (size_t i = begin; i < end; ++i) info.add(refs[i]);
        return info;
      },
      [](sah::RangeInfo a, const sah::RangeInfo& b) {
        a.merge(b);
        return a;
      });
}

class ObjectSplitBuilder {
 public:
  ObjectSplitBuilder(std::vector<PrimRef>& refs, uint32_t sphere_geom_id,
                     const BvhBuildSettings& settings, BinaryNode* nodes)
      : refs_(refs.data()), sphere_geom_id_(sphere_geom_id), settings_(settings), nodes_(nodes) {}

  size_t build(size_t n) {
    const sah::RangeInfo info = range_info(refs_, n);
    nodes_[0].set_bounds(info.geom.bounds());
    root_half_area_ = info.geom.half_area();
    next_node_ = 1;
    build_node(0, 0, static_cast<uint32_t>(n), info, 0);
    return next_node_.load();
  }

 private:
  void set_leaf(uint32_t node, uint32_t begin, uint32_t end) {
    nodes_[node].first = begin;
    nodes_[node].count = end - begin;
  }

  // Leaves are typed: spheres and triangles take different paths in traversal.
  void make_leaf(uint32_t node, uint32_t begin, uint32_t end) {
    PrimRef* mid = std::partition(refs_ + begin, refs_ + end,
                                  [&](const PrimRef& r) { return r.geom_id == sphere_geom_id_; });
    const uint32_t split = static_cast<uint32_t>(mid - refs_);
    if (split == begin || split == end) {
      set_leaf(node, begin, end);
      return;
    }
    const uint32_t children = next_node_.fetch_add(2);
    nodes_[node].first = children;
    nodes_[node].count = 0;
    nodes_[children].set_bounds(range_info(refs_ + begin, split - begin).geom.bounds());
    nodes_[children + 1].set_bounds(range_info(refs_ + split, end - split).geom.bounds());
    set_leaf(children, begin, split);
    set_leaf(children + 1, split, end);
  }

  // The best object split of [begin, end).
  sah::ObjectSplit best_split(uint32_t begin, uint32_t end, const sah::BinMapping& map) const {
    const uint32_t n = end - begin;
    if (n < kParallelScan) {
      sah::ObjectBins bins(map.bins);
      bins.add(refs_ + begin, n, map);
      return bins.best(map);
    }
    return parallel_reduce(
               begin, end, kScanGrain, sah::ObjectBins(map.bins),
               [&](size_t first, size_t last, sah::ObjectBins bins) {
                 bins.add(refs_ + first, last - first, map);
                 return bins;
               },
               [&](sah::ObjectBins a, const sah::ObjectBins& b) {
                 a.merge(b);
                 return a;
               })
        .best(map);
  }

  // Splits at the median centroid along the widest centroid axis; returns the split index.
  uint32_t median_split(uint32_t begin, uint32_t end, const sah::RangeInfo& info) {
    const Bounds3 cent = info.cent.bounds();
    const int axis = max_dimension(cent.diagonal());
    const uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(
        refs_ + begin, refs_ + mid, refs_ + end,
        [axis](const PrimRef& a, const PrimRef& b) { return a.center2(axis) < b.center2(axis); });
    return mid;
  }

  void build_node(uint32_t node, uint32_t begin, uint32_t end, const sah::RangeInfo& info,
                  int depth) {
    const uint32_t n = end - begin;
    const auto max_leaf = static_cast<uint32_t>(settings_.max_leaf_size);
    if (n <= 1 || (settings_.split == SplitMethod::kMedian && n <= max_leaf)) {
      make_leaf(node, begin, end);
      return;
    }

    uint32_t split = 0;
    sah::RangeInfo left_info, right_info;
    bool partitioned = false;
    if (settings_.split == SplitMethod::kSah && depth < kBalancedDepth) {
      const float area = info.geom.half_area();
      const float area_fraction = area / root_half_area_;
      const sah::BinMapping map(info.cent, sah::bins_for(n, settings_.bins, area_fraction));
      const sah::ObjectSplit best = best_split(begin, end, map);
      const float leaf_cost = settings_.leaf_cost * static_cast<float>(leaf_blocks(n));
      if (n <= max_leaf && sah::may_be_leaf(n, area_fraction)) {
        const float split_cost =
            best.valid() && area > 0.0f
                ? settings_.traversal_cost + settings_.leaf_cost * best.cost / area
                : kInfinity;
        if (leaf_cost <= split_cost) {
          make_leaf(node, begin, end);
          return;
        }
      }
      if (best.valid()) {
        split = partition(begin, end, map, best, left_info, right_info);
        partitioned = split != begin && split != end;
      }
    }
    if (!partitioned) {
      split = median_split(begin, end, info);
      left_info = range_info(refs_ + begin, split - begin);
      right_info = range_info(refs_ + split, end - split);
    }

    const uint32_t children = next_node_.fetch_add(2);
    nodes_[node].first = children;
    nodes_[node].count = 0;
    nodes_[children].set_bounds(left_info.geom.bounds());
    nodes_[children + 1].set_bounds(right_info.geom.bounds());
    if (n > kParallelRecursion) {
      parallel_invoke([&] { build_node(children, begin, split, left_info, depth + 1); },
                      [&] { build_node(children + 1, split, end, right_info, depth + 1); });
    } else {
      build_node(children, begin, split, left_info, depth + 1);
      build_node(children + 1, split, end, right_info, depth + 1);
    }
  }

  // In-place partition by bin, gathering both sides' bounds on the way.
  uint32_t partition(uint32_t begin, uint32_t end, const sah::BinMapping& map,
                     const sah::ObjectSplit& split, sah::RangeInfo& left, sah::RangeInfo& right) {
    PrimRef* l = refs_ + begin;
    PrimRef* r = refs_ + end;
    const int axis = split.axis;
    while (true) {
      while (l < r && map.bin(*l, axis) < split.bin) left.add(*l++);
      while (l < r && map.bin(*(r - 1), axis) >= split.bin) right.add(*--r);
      if (l >= r) break;
      std::swap(*l, *(r - 1));
      left.add(*l++);
      right.add(*--r);
    }
    return static_cast<uint32_t>(l - refs_);
  }

  PrimRef* refs_;
  uint32_t sphere_geom_id_;
  const BvhBuildSettings& settings_;
  BinaryNode* nodes_;
  float root_half_area_ = 0.0f;
  std::atomic<uint32_t> next_node_{0};
};

}  // namespace

BinaryBvh build_object_split_bvh(std::vector<PrimRef> refs, uint32_t sphere_geom_id,
                                 const BvhBuildSettings& settings) {
  PRISM_CHECK(settings.bins >= 2 && settings.bins <= sah::kMaxBins);
  PRISM_CHECK(settings.max_leaf_size >= 1 && settings.max_leaf_size <= kMaxLeafPrimitives);
  BinaryBvh bvh;
  if (refs.empty()) return bvh;
  // A tree with n non-empty leaves has at most 2n - 1 nodes; the memory is only touched as
  // nodes are created.
  bvh.nodes.reset(new BinaryNode[2 * refs.size()]);
  ObjectSplitBuilder builder(refs, sphere_geom_id, settings, bvh.nodes.get());
  bvh.node_count = builder.build(refs.size());
  bvh.refs = std::move(refs);
  return bvh;
}

}  // namespace prism
