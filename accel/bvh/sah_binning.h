#pragma once

// Centroid binning for the SAH builders. Baseline x86-64 (SSE2) only: builders run on any CPU.

#include <emmintrin.h>

#include <algorithm>
#include <cstdint>

#include "accel/bvh/build_reference.h"

namespace prism::sah {

inline constexpr int kMaxBins = 64;

/// An axis-aligned box in two SSE registers; lane 3 is ignored.
struct Box {
  __m128 lo = _mm_set1_ps(kInfinity);
  __m128 hi = _mm_set1_ps(-kInfinity);

  void extend(__m128 l, __m128 h) {
    lo = _mm_min_ps(lo, l);
    hi = _mm_max_ps(hi, h);
  }
  void extend(const Box& b) { extend(b.lo, b.hi); }
  void extend_ref(const PrimRef& r) { extend(_mm_load_ps(r.lower), _mm_load_ps(r.upper)); }
  bool empty() const {
    alignas(16) float l[4], h[4];
    _mm_store_ps(l, lo);
    _mm_store_ps(h, hi);
    return l[0] > h[0] || l[1] > h[1] || l[2] > h[2];
  }
  /// Half the surface area; 0 when empty.
  float half_area() const {
    alignas(16) float d[4];
    _mm_store_ps(d, _mm_sub_ps(hi, lo));
    if (d[0] < 0.0f || d[1] < 0.0f || d[2] < 0.0f) return 0.0f;
    return d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
  }
  Bounds3 bounds() const {
    alignas(16) float l[4], h[4];
    _mm_store_ps(l, lo);
    _mm_store_ps(h, hi);
    return {Vec3(l[0], l[1], l[2]), Vec3(h[0], h[1], h[2])};
  }
};

/// Twice the centroid of a reference (lane 3 garbage).
inline __m128 center2(const PrimRef& r) {
  return _mm_add_ps(_mm_load_ps(r.lower), _mm_load_ps(r.upper));
}

/// Geometry bounds and centroid bounds (of center2) of a set of references.
struct RangeInfo {
  Box geom;
  Box cent;
  void add(const PrimRef& r) {
    const __m128 l = _mm_load_ps(r.lower), h = _mm_load_ps(r.upper);
    geom.extend(l, h);
    const __m128 c = _mm_add_ps(l, h);
    cent.extend(c, c);
  }
  void merge(const RangeInfo& o) {
    geom.extend(o.geom);
    cent.extend(o.cent);
  }
};

/// Maps centroids to bins along each axis.
struct BinMapping {
  int bins = 0;
  __m128 offset;
  __m128 scale;
  float offset_s[3];
  float scale_s[3];

  BinMapping(const Box& cent, int bin_count) : bins(bin_count), offset(cent.lo) {
    alignas(16) float ext[4];
    _mm_store_ps(ext, _mm_sub_ps(cent.hi, cent.lo));
    alignas(16) float s[4] = {0, 0, 0, 0};
    // The factor below 1 keeps the largest centroid inside the last bin after rounding.
    for (int a = 0; a < 3; ++a) s[a] = ext[a] > 0.0f ? bin_count * 0.99999f / ext[a] : 0.0f;
    scale = _mm_load_ps(s);
    alignas(16) float o[4];
    _mm_store_ps(o, offset);
    for (int a = 0; a < 3; ++a) {
      offset_s[a] = o[a];
      scale_s[a] = s[a];
    }
  }
  /// Bin of `r` on all three axes (index 3 is garbage).
  void bin3(const PrimRef& r, int out[4]) const {
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out), bin3(r));
  }
  /// bin3() in a register. The clamp to [0, bins - 1] happens before the truncation, in float:
  /// the same bins as truncating and then clamping the integer, without leaving SSE2.
  __m128i bin3(const PrimRef& r) const {
    const __m128 f = _mm_mul_ps(_mm_sub_ps(center2(r), offset), scale);
    const __m128 last = _mm_set1_ps(static_cast<float>(bins - 1));
    return _mm_cvttps_epi32(_mm_min_ps(_mm_max_ps(f, _mm_setzero_ps()), last));
  }
  /// bin3()'s value on one axis, with the same arithmetic (so partitions match the bins).
  int bin(const PrimRef& r, int axis) const {
    const int b = static_cast<int>((r.center2(axis) - offset_s[axis]) * scale_s[axis]);
    return std::clamp(b, 0, bins - 1);
  }
  bool degenerate(int axis) const {
    alignas(16) float s[4];
    _mm_store_ps(s, scale);
    return s[axis] == 0.0f;
  }
};

/// The best object split found: references with bin < `bin` on `axis` go left.
struct ObjectSplit {
  int axis = -1;
  int bin = 0;
  float cost = kInfinity;  ///< sum over children of half area x blocks
  bool valid() const { return axis >= 0; }
};

/// Per-axis bin counts and bounds. Only the first `bins` entries are initialized and used, so
/// that the many small nodes near the leaves pay for the bins they use, not for kMaxBins.
struct ObjectBins {
  explicit ObjectBins(int bin_count) : bins(bin_count) {
    const __m128 inf = _mm_set1_ps(kInfinity), ninf = _mm_set1_ps(-kInfinity);
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < bins; ++b) {
        lo[a][b] = inf;
        hi[a][b] = ninf;
        count[a][b] = 0;
      }
    }
  }

  int bins;
  __m128 lo[3][kMaxBins];
  __m128 hi[3][kMaxBins];
  uint32_t count[3][kMaxBins];

  Box box(int axis, int bin) const { return {lo[axis][bin], hi[axis][bin]}; }

  void add(const PrimRef* refs, size_t n, const BinMapping& map) {
    // Two references per iteration, their bin indices taken out of the registers up front: the
    // loads and stores of the two interleave, which hides most of the latency when both land in
    // the same bin.
    size_t i = 0;
    for (; i + 1 < n; i += 2) {
      const __m128i b0 = map.bin3(refs[i]);
      const __m128i b1 = map.bin3(refs[i + 1]);
      const int b0x = _mm_cvtsi128_si32(b0), b1x = _mm_cvtsi128_si32(b1);
      const int b0y = _mm_cvtsi128_si32(_mm_shuffle_epi32(b0, 0x55));
      const int b1y = _mm_cvtsi128_si32(_mm_shuffle_epi32(b1, 0x55));
      const int b0z = _mm_cvtsi128_si32(_mm_shuffle_epi32(b0, 0xAA));
      const int b1z = _mm_cvtsi128_si32(_mm_shuffle_epi32(b1, 0xAA));
      const __m128 l0 = _mm_load_ps(refs[i].lower), h0 = _mm_load_ps(refs[i].upper);
      const __m128 l1 = _mm_load_ps(refs[i + 1].lower), h1 = _mm_load_ps(refs[i + 1].upper);
      add_one(0, b0x, l0, h0);
      add_one(1, b0y, l0, h0);
      add_one(2, b0z, l0, h0);
      add_one(0, b1x, l1, h1);
      add_one(1, b1y, l1, h1);
      add_one(2, b1z, l1, h1);
    }
    for (; i < n; ++i) {
      alignas(16) int b[4];
      map.bin3(refs[i], b);
      const __m128 l = _mm_load_ps(refs[i].lower), h = _mm_load_ps(refs[i].upper);
      for (int a = 0; a < 3; ++a) add_one(a, b[a], l, h);
    }
  }
  void add_one(int axis, int bin, __m128 l, __m128 h) {
    lo[axis][bin] = _mm_min_ps(lo[axis][bin], l);
    hi[axis][bin] = _mm_max_ps(hi[axis][bin], h);
    ++count[axis][bin];
  }
  void merge(const ObjectBins& o) {
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < bins; ++b) {
        lo[a][b] = _mm_min_ps(lo[a][b], o.lo[a][b]);
        hi[a][b] = _mm_max_ps(hi[a][b], o.hi[a][b]);
        count[a][b] += o.count[a][b];
      }
    }
  }
  /// Bounds of both sides of `split`.
  void split_bounds(const ObjectSplit& split, Box& left, Box& right) const {
    for (int b = 0; b < bins; ++b) (b < split.bin ? left : right).extend(box(split.axis, b));
  }
  /// SAH sweep over every bin boundary of every non-degenerate axis.
  ObjectSplit best(const BinMapping& map) const {
    ObjectSplit best;
    float right_cost[kMaxBins];
    for (int a = 0; a < 3; ++a) {
      if (map.degenerate(a)) continue;
      Box acc;
      uint32_t cnt = 0;
      for (int b = bins - 1; b > 0; --b) {
        acc.extend(lo[a][b], hi[a][b]);
        cnt += count[a][b];
        right_cost[b] = cnt ? acc.half_area() * static_cast<float>(leaf_blocks(cnt)) : kInfinity;
      }
      acc = Box();
      cnt = 0;
      for (int b = 1; b < bins; ++b) {
        acc.extend(lo[a][b - 1], hi[a][b - 1]);
        cnt += count[a][b - 1];
        if (cnt == 0) continue;
        const float cost = acc.half_area() * static_cast<float>(leaf_blocks(cnt)) + right_cost[b];
        if (cost < best.cost) best = {a, b, cost};
      }
    }
    return best;
  }
};

/// Bins worth using for n references: fewer for small nodes, where 32 bins would mostly be
/// empty and their set-up and sweep would cost more than the references.
inline int bins_for(size_t n, int max_bins) {
  return static_cast<int>(std::clamp<size_t>(n / 2, 4, static_cast<size_t>(max_bins)));
}

// Nodes that most rays reach. SAH weighs a node by its share of the root's area (the share of
// rays that reach it), but binning and the leaf decision look only at the node's references,
// and a few large triangles near the root (a room's walls around a detailed mesh, as in the
// CS184 Cornell scenes) defeat both: n / 2 bins across a handful of centroids miss the splits
// that give each wall its own thin box, and the leaf cost, a block test against a binary
// split's traversal, ignores that after the collapse to 8-wide nodes that split costs a few
// lanes of a box test the parent makes anyway. A room-sized leaf is then tested by nearly every
// ray. Measured in docs/PERFORMANCE.md ("Nodes that most rays reach"): CBbunny's SAH cost 22.4
// -> 8.3, its shadow rays from 0.78x Embree's speed to 1.06-1.13x; the build time of
// 1M-triangle meshes within noise, since few nodes are that large.

/// Nodes with at least this share of the root's area are binned with every bin.
inline constexpr float kManyRaysAreaFraction = 0.01f;
/// Nodes with at least this share of the root's area become leaves only when they hold at most
/// kLargeLeafPrimitives references (two triangles: one wall).
inline constexpr float kLargeLeafAreaFraction = 0.2f;
inline constexpr size_t kLargeLeafPrimitives = 2;

/// bins_for() for a node whose box has `area_fraction` of the root box's area.
inline int bins_for(size_t n, int max_bins, float area_fraction) {
  return area_fraction >= kManyRaysAreaFraction ? max_bins : bins_for(n, max_bins);
}

/// Whether SAH may make a leaf of a node of n references whose box has `area_fraction` of the
/// root box's area (it still may split it, as always).
inline bool may_be_leaf(size_t n, float area_fraction) {
  return area_fraction < kLargeLeafAreaFraction || n <= kLargeLeafPrimitives;
}

}  // namespace prism::sah
