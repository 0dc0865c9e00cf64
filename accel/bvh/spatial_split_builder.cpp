#include "accel/bvh/spatial_split_builder.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <memory>

#include "accel/bvh/sah_binning.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/parallel_reduce.h"

namespace prism {
namespace {

using sah::Box;

constexpr size_t kParallelRecursion = 4096;
constexpr size_t kParallelScan = 64 * 1024;
constexpr size_t kScanGrain = 16 * 1024;
constexpr int kBalancedDepth = kMaxBvhDepth - 28;
// Below this many references a spatial split saves too little to pay for clipping every
// reference at every bin boundary it crosses (the bins get finer than the triangles).
constexpr size_t kMinSpatialSplitSize = 64;

bool is_empty(const PrimRef& r) {
  return r.lower[0] > r.upper[0] || r.lower[1] > r.upper[1] || r.lower[2] > r.upper[2];
}

float half_area_of(const Box& b, const PrimRef& r) {
  Box u = b;
  u.extend_ref(r);
  return u.half_area();
}

/// Where the bins of one axis lie: plane(i) is the lower side of bin i.
struct SpatialAxis {
  float lower = 0.0f;
  float size = 0.0f;
  float inv_size = 0.0f;
  int bins = 0;

  float plane(int i) const { return lower + static_cast<float>(i) * size; }
  int bin(float x) const {
    return std::clamp(static_cast<int>((x - lower) * inv_size), 0, bins - 1);
  }
};

struct SpatialSplit {
  int axis = -1;
  int bin = 0;
  float cost = kInfinity;
  uint32_t left_count = 0, right_count = 0;
};

class SpatialSplitBuilder {
 public:
  SpatialSplitBuilder(const SceneGeometry& geometry, const BvhBuildSettings& settings,
                      size_t prim_count)
      : geometry_(geometry),
        settings_(settings),
        budget_(static_cast<int64_t>(settings.spatial_budget * static_cast<float>(prim_count))),
        capacity_(prim_count + static_cast<size_t>(std::max<int64_t>(budget_, 0))) {
    // Every triangle's corners in one array: clipping reads them for every bin boundary a
    // reference crosses, and three scattered vertex loads per clip dominated the build.
    mesh_offset_.resize(geometry.meshes.size());
    size_t total = 0;
    for (size_t m = 0; m < geometry.meshes.size(); ++m) {
      mesh_offset_[m] = total;
      total += geometry.meshes[m].triangles.size();
    }
    corners_.resize(total);
    for (size_t m = 0; m < geometry.meshes.size(); ++m) {
      const TriangleMesh& mesh = geometry.meshes[m];
      parallel_for_range(
          mesh.triangles.size(),
          [&](size_t begin, size_t end) {
            for (size_t i = begin; i < end; ++i) {
              const glm::uvec3 t = mesh.triangles[i];
              corners_[mesh_offset_[m] + i] = {mesh.positions[t.x], mesh.positions[t.y],
                                               mesh.positions[t.z]};
            }
          },
          16 * 1024);
    }
  }

  BinaryBvh build(std::vector<PrimRef> refs) {
    BinaryBvh bvh;
    bvh.nodes.reset(new BinaryNode[2 * capacity_]);
    nodes_ = bvh.nodes.get();
    out_refs_.reset(new PrimRef[capacity_]);
    sah::RangeInfo info = range_info(refs);
    root_half_area_ = info.geom.half_area();
    nodes_[0].set_bounds(info.geom.bounds());
    next_node_ = 1;
    build_node(0, std::move(refs), info, 0);
    bvh.node_count = next_node_.load();
    bvh.refs.assign(out_refs_.get(), out_refs_.get() + next_ref_.load());
    return bvh;
  }

 private:
  static sah::RangeInfo range_info(const std::vector<PrimRef>& refs) {
    sah::RangeInfo info;
    for (const PrimRef& r : refs) info.add(r);
    return info;
  }

  // The parts of `ref` below and above the plane at `pos` on `axis`. Either part may come back
  // empty (is_empty) when the primitive inside the reference's box lies on one side.
  void split_reference(const PrimRef& ref, int axis, float pos, PrimRef& left,
                       PrimRef& right) const {
    left = right = ref;
    if (ref.geom_id == geometry_.sphere_geom_id()) {
      left.upper[axis] = std::min(ref.upper[axis], pos);
      right.lower[axis] = std::max(ref.lower[axis], pos);
      return;
    }
    const std::array<Vec3, 3>& v = corners_[mesh_offset_[ref.geom_id] + ref.prim_id];
    Bounds3 lb, rb;
    for (int i = 0; i < 3; ++i) {
      const Vec3& a = v[i];
      const Vec3& b = v[(i + 1) % 3];
      if (a[axis] <= pos) lb.extend(a);
      if (a[axis] >= pos) rb.extend(a);
      if ((a[axis] < pos && b[axis] > pos) || (a[axis] > pos && b[axis] < pos)) {
        const float t = (pos - a[axis]) / (b[axis] - a[axis]);
        Vec3 p = glm::clamp(a + t * (b - a), glm::min(a, b), glm::max(a, b));
        p[axis] = pos;
        lb.extend(p);
        rb.extend(p);
      }
    }
    for (int k = 0; k < 3; ++k) {
      left.lower[k] = std::max(ref.lower[k], lb.lower[k]);
      left.upper[k] = std::min(ref.upper[k], lb.upper[k]);
      right.lower[k] = std::max(ref.lower[k], rb.lower[k]);
      right.upper[k] = std::min(ref.upper[k], rb.upper[k]);
    }
    left.upper[axis] = std::min(left.upper[axis], pos);
    right.lower[axis] = std::max(right.lower[axis], pos);
  }

  struct SpatialBins {
    Box box[3][sah::kMaxBins];
    uint32_t enter[3][sah::kMaxBins] = {};
    uint32_t exit[3][sah::kMaxBins] = {};
  };

  void bin_spatial(const PrimRef* refs, size_t n, const SpatialAxis* axes,
                   SpatialBins& bins) const {
    for (size_t i = 0; i < n; ++i) {
      for (int a = 0; a < 3; ++a) {
        const SpatialAxis& ax = axes[a];
        if (ax.size <= 0.0f) continue;
        const int first = ax.bin(refs[i].lower[a]);
        const int last = std::max(first, ax.bin(refs[i].upper[a]));
        PrimRef rest = refs[i];
        for (int b = first; b < last; ++b) {
          PrimRef left, right;
          split_reference(rest, a, ax.plane(b + 1), left, right);
          if (!is_empty(left)) bins.box[a][b].extend_ref(left);
          rest = right;
          if (is_empty(rest)) break;
        }
        if (!is_empty(rest)) bins.box[a][last].extend_ref(rest);
        ++bins.enter[a][first];
        ++bins.exit[a][last];
      }
    }
  }

  SpatialSplit find_spatial_split(const std::vector<PrimRef>& refs, const Bounds3& bounds,
                                  SpatialAxis* axes) const {
    const int nb = settings_.bins;
    // Only the node's longest axis: clipping every reference at every bin boundary it crosses
    // is the whole cost of a spatial split, and the longest axis is where one pays off.
    const int longest = max_dimension(bounds.diagonal());
    for (int a = 0; a < 3; ++a) {
      const float extent = bounds.upper[a] - bounds.lower[a];
      axes[a] = {bounds.lower[a], extent / nb, extent > 0.0f ? nb / extent : 0.0f, nb};
      if (!(extent > 0.0f) || a != longest) axes[a].size = 0.0f;
    }
    SpatialBins bins;
    if (refs.size() < kParallelScan) {
      bin_spatial(refs.data(), refs.size(), axes, bins);
    } else {
      bins = parallel_reduce(
          0, refs.size(), kScanGrain, SpatialBins(),
          [&](size_t begin, size_t end, SpatialBins b) {
            bin_spatial(refs.data() + begin, end - begin, axes, b);
            return b;
          },
          [nb](SpatialBins x, const SpatialBins& y) {
            for (int a = 0; a < 3; ++a) {
              for (int b = 0; b < nb; ++b) {
                x.box[a][b].extend(y.box[a][b]);
                x.enter[a][b] += y.enter[a][b];
                x.exit[a][b] += y.exit[a][b];
              }
            }
            return x;
          });
    }
    SpatialSplit best;
    float right_cost[sah::kMaxBins];
    uint32_t right_count[sah::kMaxBins];
    for (int a = 0; a < 3; ++a) {
      if (axes[a].size <= 0.0f) continue;
      Box acc;
      uint32_t cnt = 0;
      for (int b = nb - 1; b > 0; --b) {
        acc.extend(bins.box[a][b]);
        cnt += bins.exit[a][b];
        right_count[b] = cnt;
        right_cost[b] = cnt ? acc.half_area() * static_cast<float>(leaf_blocks(cnt)) : kInfinity;
      }
      acc = Box();
      cnt = 0;
      for (int b = 1; b < nb; ++b) {
        acc.extend(bins.box[a][b - 1]);
        cnt += bins.enter[a][b - 1];
        if (cnt == 0) continue;
        const float cost = acc.half_area() * static_cast<float>(leaf_blocks(cnt)) + right_cost[b];
        if (cost < best.cost) best = {a, b, cost, cnt, right_count[b]};
      }
    }
    return best;
  }

  // Splits at `split`, deciding per straddling reference whether clipping it beats moving it
  // whole to one side ("reference unsplitting").
  void partition_spatial(const std::vector<PrimRef>& refs, const SpatialAxis& ax, int axis,
                         const SpatialSplit& split, std::vector<PrimRef>& left,
                         std::vector<PrimRef>& right) const {
    Box lbox, rbox;
    std::vector<const PrimRef*> straddling;
    left.reserve(split.left_count);
    right.reserve(split.right_count);
    for (const PrimRef& r : refs) {
      const int first = ax.bin(r.lower[axis]);
      const int last = std::max(first, ax.bin(r.upper[axis]));
      if (last < split.bin) {
        left.push_back(r);
        lbox.extend_ref(r);
      } else if (first >= split.bin) {
        right.push_back(r);
        rbox.extend_ref(r);
      } else {
        straddling.push_back(&r);
      }
    }
    const float pos = ax.plane(split.bin);
    auto nl = static_cast<float>(left.size() + straddling.size());
    auto nr = static_cast<float>(right.size() + straddling.size());
    for (const PrimRef* r : straddling) {
      PrimRef lpart, rpart;
      split_reference(*r, axis, pos, lpart, rpart);
      Box ls = lbox, rs = rbox;
      if (!is_empty(lpart)) ls.extend_ref(lpart);
      if (!is_empty(rpart)) rs.extend_ref(rpart);
      const float c_split = ls.half_area() * nl + rs.half_area() * nr;
      const float c_left = half_area_of(lbox, *r) * nl + rbox.half_area() * (nr - 1.0f);
      const float c_right = lbox.half_area() * (nl - 1.0f) + half_area_of(rbox, *r) * nr;
      if ((c_left < c_split && c_left <= c_right) || is_empty(rpart)) {
        left.push_back(*r);
        lbox.extend_ref(*r);
        nr -= 1.0f;
      } else if (c_right < c_split || is_empty(lpart)) {
        right.push_back(*r);
        rbox.extend_ref(*r);
        nl -= 1.0f;
      } else {
        left.push_back(lpart);
        right.push_back(rpart);
        lbox = ls;
        rbox = rs;
      }
    }
  }

  void make_leaf(uint32_t node, std::vector<PrimRef>& refs) {
    auto mid = std::partition(refs.begin(), refs.end(), [&](const PrimRef& r) {
      return r.geom_id == geometry_.sphere_geom_id();
    });
    const auto spheres = static_cast<uint32_t>(mid - refs.begin());
    const auto n = static_cast<uint32_t>(refs.size());
    const uint32_t first = next_ref_.fetch_add(n);
    PRISM_CHECK(first + n <= capacity_);
    std::copy(refs.begin(), refs.end(), out_refs_.get() + first);
    if (spheres == 0 || spheres == n) {
      nodes_[node].first = first;
      nodes_[node].count = n;
      return;
    }
    const uint32_t children = next_node_.fetch_add(2);
    nodes_[node].first = children;
    nodes_[node].count = 0;
    sah::RangeInfo si, ti;
    for (uint32_t i = 0; i < n; ++i) (i < spheres ? si : ti).add(refs[i]);
    nodes_[children].set_bounds(si.geom.bounds());
    nodes_[children].first = first;
    nodes_[children].count = spheres;
    nodes_[children + 1].set_bounds(ti.geom.bounds());
    nodes_[children + 1].first = first + spheres;
    nodes_[children + 1].count = n - spheres;
  }

  void build_node(uint32_t node, std::vector<PrimRef> refs, const sah::RangeInfo& info, int depth) {
    const size_t n = refs.size();
    const auto max_leaf = static_cast<size_t>(settings_.max_leaf_size);
    if (n <= 1) {
      make_leaf(node, refs);
      return;
    }
    std::vector<PrimRef> left, right;
    bool done = false;
    if (depth < kBalancedDepth) {
      const float area = info.geom.half_area();
      const float area_fraction = area / root_half_area_;
      const sah::BinMapping map(info.cent, sah::bins_for(n, settings_.bins, area_fraction));
      sah::ObjectBins obins(map.bins);
      obins.add(refs.data(), n, map);
      const sah::ObjectSplit object = obins.best(map);
      float best_cost = object.cost;

      // Spatial splits pay off only where object splits leave children overlapping.
      SpatialSplit spatial;
      SpatialAxis axes[3];
      const Bounds3 bounds = info.geom.bounds();
      bool try_spatial =
          n >= kMinSpatialSplitSize && budget_used_.load(std::memory_order_relaxed) < budget_;
      if (try_spatial && object.valid()) {
        Box l, r;
        obins.split_bounds(object, l, r);
        Box overlap;
        overlap.lo = _mm_max_ps(l.lo, r.lo);
        overlap.hi = _mm_min_ps(l.hi, r.hi);
        try_spatial = overlap.half_area() > settings_.spatial_alpha * root_half_area_;
      }
      if (try_spatial) {
        spatial = find_spatial_split(refs, bounds, axes);
        if (spatial.cost < best_cost) {
          best_cost = spatial.cost;
        } else {
          spatial.axis = -1;
        }
      }

      if (n <= max_leaf && sah::may_be_leaf(n, area_fraction)) {
        const float leaf_cost = settings_.leaf_cost * static_cast<float>(leaf_blocks(n));
        const float split_cost =
            best_cost < kInfinity && area > 0.0f
                ? settings_.traversal_cost + settings_.leaf_cost * best_cost / area
                : kInfinity;
        if (leaf_cost <= split_cost) {
          make_leaf(node, refs);
          return;
        }
      }
      if (spatial.axis >= 0) {
        const int64_t extra = static_cast<int64_t>(spatial.left_count + spatial.right_count) -
                              static_cast<int64_t>(n);
        if (budget_used_.fetch_add(extra) + extra <= budget_) {
          partition_spatial(refs, axes[spatial.axis], spatial.axis, spatial, left, right);
          done = !left.empty() && !right.empty();
          if (!done) {
            left.clear();
            right.clear();
          }
        } else {
          budget_used_.fetch_sub(extra);
        }
      }
      if (!done && object.valid()) {
        auto mid = std::partition(refs.begin(), refs.end(), [&](const PrimRef& r) {
          return map.bin(r, object.axis) < object.bin;
        });
        left.assign(refs.begin(), mid);
        right.assign(mid, refs.end());
        done = !left.empty() && !right.empty();
      }
    }
    if (!done) {
      if (n <= max_leaf) {
        make_leaf(node, refs);
        return;
      }
      const int axis = max_dimension(info.cent.bounds().diagonal());
      auto mid = refs.begin() + static_cast<std::ptrdiff_t>(n / 2);
      std::nth_element(refs.begin(), mid, refs.end(), [axis](const PrimRef& a, const PrimRef& b) {
        return a.center2(axis) < b.center2(axis);
      });
      left.assign(refs.begin(), mid);
      right.assign(mid, refs.end());
    }
    refs = {};  // release before recursing: the children hold copies

    const sah::RangeInfo left_info = range_info(left);
    const sah::RangeInfo right_info = range_info(right);
    const uint32_t children = next_node_.fetch_add(2);
    PRISM_CHECK(children + 1 < 2 * capacity_);
    nodes_[node].first = children;
    nodes_[node].count = 0;
    nodes_[children].set_bounds(left_info.geom.bounds());
    nodes_[children + 1].set_bounds(right_info.geom.bounds());
    if (n > kParallelRecursion) {
      parallel_invoke([&] { build_node(children, std::move(left), left_info, depth + 1); },
                      [&] { build_node(children + 1, std::move(right), right_info, depth + 1); });
    } else {
      build_node(children, std::move(left), left_info, depth + 1);
      build_node(children + 1, std::move(right), right_info, depth + 1);
    }
  }

  const SceneGeometry& geometry_;
  std::vector<size_t> mesh_offset_;
  std::vector<std::array<Vec3, 3>> corners_;
  const BvhBuildSettings& settings_;
  const int64_t budget_;
  const size_t capacity_;
  std::atomic<int64_t> budget_used_{0};
  float root_half_area_ = 0.0f;
  BinaryNode* nodes_ = nullptr;
  std::unique_ptr<PrimRef[]> out_refs_;
  std::atomic<uint32_t> next_node_{0};
  std::atomic<uint32_t> next_ref_{0};
};

}  // namespace

BinaryBvh build_spatial_split_bvh(const SceneGeometry& geometry, std::vector<PrimRef> refs,
                                  const BvhBuildSettings& settings) {
  PRISM_CHECK(settings.bins >= 2 && settings.bins <= sah::kMaxBins);
  PRISM_CHECK(settings.max_leaf_size >= 1 && settings.max_leaf_size <= kMaxLeafPrimitives);
  if (refs.empty()) return {};
  SpatialSplitBuilder builder(geometry, settings, refs.size());
  return builder.build(std::move(refs));
}

}  // namespace prism
