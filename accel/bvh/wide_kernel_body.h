// The traversal loops of the wide BVH, shared by every instruction set. No include guard and no
// includes on purpose: each wide_traversal_<isa>.cpp includes this file once, inside its own
// namespace, after wide_kernel_common.h and after defining for that instruction set:
//   template <int W, unsigned kOctant> struct NodeRay;   // box test constants, from RaySetup
//   kRuntimeOctant, kKernelUsesRuntimeOctant  // whether one kOctant (kRuntimeOctant) serves all
//   uint32_t intersect_node(const WideNode<W>&, const NodeRay<W, kOctant>&, float tmax,
//                           float* tnear);  // mask of the children entered, entry distances
//   struct TriangleRay;                     // triangle test constants, from (RaySetup, Ray)
//   bool intersect_blocks(const TriangleBlock* blocks, uint32_t count, const TriangleRay&,
//                         float tmax, WideHit& hit, bool any_hit);
//     // replaces hit by a hit in [tmin, tmax] that comes before it (comes_before_hit);
//     // returns whether it did, or with any_hit whether any lane hits
// Every function lands in the including file's namespace, so the copies compiled with
// different instruction sets never meet in the linker.

struct StackEntry {
  uint32_t ref;
  float t;  ///< padded entry distance of the box
};

/// Tests the spheres of one sphere leaf (blocks [first, first + count)) for hits in
/// [ray.tmin, tmax]; replaces `hit` by any that comes before it (hit.t is then the new tmax)
/// and returns whether it did. With any_hit, returns true at the first hit instead.
PRISM_KERNEL_INLINE bool intersect_spheres(const WideBvhView& bvh, const Ray& query_ray,
                                           uint32_t first, uint32_t count, float tmax, WideHit& hit,
                                           bool any_hit) {
  Ray ray = query_ray;
  ray.tmax = tmax;
  bool found = false;
  const uint32_t* ids = bvh.sphere_blocks + 4 * first;
  for (uint32_t i = 0; i < 4 * count; ++i) {
    // Unused lanes repeat the previous sphere.
    if ((i & 3) != 0 && ids[i] == ids[i - 1]) continue;
    const Sphere& s = bvh.spheres[ids[i]];
    // t first: a shadow ray needs nothing else, and u, v (two inverse trigonometric
    // functions) are computed only for a hit that becomes the closest so far.
    float t;
    if (!sphere_hit_t(ray, s.center, s.radius, t)) continue;
    if (any_hit) return true;
    if (!comes_before_hit(t, bvh.sphere_geom_id, ids[i], hit)) continue;
    found = true;
    ray.tmax = t;
    const Vec2 uv = sphere_hit_uv(ray, t, s.center);  // out of line: the baseline program's
    hit = {t, uv.x, uv.y, bvh.sphere_geom_id, ids[i], nullptr};
  }
  return found;
}

PRISM_KERNEL_INLINE bool intersect_leaf(const WideBvhView& bvh, uint32_t ref,
                                        const TriangleRay& triangle_ray, const Ray& ray, float tmax,
                                        WideHit& hit, bool any_hit) {
  const uint32_t first = ref & kLeafFirstMask;
  const uint32_t count = ((ref >> kLeafCountShift) & 15u) + 1;
  if (ref & kSphereLeafFlag) {
    return intersect_spheres(bvh, ray, first, count, tmax, hit, any_hit);
  }
  return intersect_blocks(bvh.triangle_blocks + first, count, triangle_ray, tmax, hit, any_hit);
}

/// Starts loading a node or leaf the traversal will probably visit soon, so that its cache
/// misses overlap the work on the current subtree.
template <int W>
PRISM_KERNEL_INLINE void prefetch_ref(const WideBvhView& bvh, uint32_t ref) {
  const char* p;
  int lines;
  if (ref & kLeafFlag) {
    if (ref & kSphereLeafFlag) return;
    p = reinterpret_cast<const char*>(bvh.triangle_blocks + (ref & kLeafFirstMask));
    lines = 3;
  } else {
    p = reinterpret_cast<const char*>(static_cast<const WideNode<W>*>(bvh.nodes) + ref);
    lines = static_cast<int>(sizeof(WideNode<W>) / 64);
  }
  for (int i = 0; i < lines; ++i) __builtin_prefetch(p + 64 * i);
}

/// Closest hit: children are visited nearest first, and stack entries whose box starts beyond
/// the current hit are dropped when popped.
template <int W, unsigned kOctant>
bool intersect_closest_octant(const WideBvhView& bvh, const RaySetup& setup, const Ray& ray,
                              WideHit& hit) {
  const auto* nodes = static_cast<const WideNode<W>*>(bvh.nodes);
  const NodeRay<W, kOctant> node_ray(setup);
  const TriangleRay triangle_ray(setup, ray);
  float tmax = setup.tmax;
  bool found = false;
  StackEntry stack[kStackSize<W>];
  int sp = 0;
  uint32_t ref = bvh.root;
  for (;;) {
    if (!(ref & kLeafFlag)) {
      const WideNode<W>& node = nodes[ref];
      alignas(32) float tnear[W];
      uint32_t mask = intersect_node(node, node_ray, tmax, tnear);
      if (mask != 0) {
        const int i = lowest_lane(mask);
        mask &= mask - 1;
        if (mask == 0) {
          ref = node.child[i];
          continue;
        }
        const int j = lowest_lane(mask);
        mask &= mask - 1;
        if (mask == 0) {
          const bool j_first = tnear[j] < tnear[i];
          const int near = j_first ? j : i, far = j_first ? i : j;
          stack[sp++] = {node.child[far], tnear[far]};
          prefetch_ref<W>(bvh, node.child[far]);
          ref = node.child[near];
          continue;
        }
        // Three or more: insertion-sort the lanes by entry distance, push them farthest first.
        int lanes[W];
        int n = 0;
        auto insert = [&](int lane) {
          int k = n++;
          while (k > 0 && tnear[lanes[k - 1]] > tnear[lane]) {
            lanes[k] = lanes[k - 1];
            --k;
          }
          lanes[k] = lane;
        };
        insert(i);
        insert(j);
        while (mask != 0) {
          insert(lowest_lane(mask));
          mask &= mask - 1;
        }
        for (int k = n - 1; k > 0; --k) {
          stack[sp++] = {node.child[lanes[k]], tnear[lanes[k]]};
          prefetch_ref<W>(bvh, node.child[lanes[k]]);
        }
        ref = node.child[lanes[0]];
        continue;
      }
    } else if (intersect_leaf(bvh, ref, triangle_ray, ray, tmax, hit, false)) {
      found = true;
      tmax = hit.t;
    }
    // Pop the next box that still starts before the closest hit.
    for (;;) {
      if (sp == 0) return found;
      const StackEntry& e = stack[--sp];
      if (e.t <= tmax) {
        ref = e.ref;
        break;
      }
    }
  }
}

/// Any hit: no distance ordering, stop at the first primitive hit.
template <int W, unsigned kOctant>
bool intersect_any_octant(const WideBvhView& bvh, const RaySetup& setup, const Ray& ray) {
  const auto* nodes = static_cast<const WideNode<W>*>(bvh.nodes);
  const NodeRay<W, kOctant> node_ray(setup);
  const TriangleRay triangle_ray(setup, ray);
  const float tmax = setup.tmax;
  WideHit unused = kNoWideHit;
  uint32_t stack[kStackSize<W>];
  int sp = 0;
  uint32_t ref = bvh.root;
  for (;;) {
    if (!(ref & kLeafFlag)) {
      const WideNode<W>& node = nodes[ref];
      alignas(32) float tnear[W];
      uint32_t mask = intersect_node(node, node_ray, tmax, tnear);
      if (mask != 0) {
        // The highest lane first, the others pushed: measured a little faster on shadow rays
        // than the lowest first (the last lanes hold the children opened last in the collapse).
        const int last = 31 - __builtin_clz(mask);
        ref = node.child[last];
        mask &= ~(1u << last);
        while (mask != 0) {
          const uint32_t child = node.child[lowest_lane(mask)];
          stack[sp++] = child;
          prefetch_ref<W>(bvh, child);
          mask &= mask - 1;
        }
        continue;
      }
    } else if (intersect_leaf(bvh, ref, triangle_ray, ray, tmax, unused, true)) {
      return true;
    }
    if (sp == 0) return false;
    ref = stack[--sp];
  }
}

template <unsigned kOctant>
struct OctantTag {
  static constexpr unsigned value = kOctant;
};

/// Calls visit(OctantTag<kOctant>{}) with the kOctant this kernel traverses a ray of `octant`
/// with: kRuntimeOctant for every ray (kKernelUsesRuntimeOctant), or the octant itself, so that
/// every plane offset of the box test is a constant.
template <typename Visit>
PRISM_KERNEL_INLINE bool dispatch_octant(unsigned octant, Visit&& visit) {
  if constexpr (kKernelUsesRuntimeOctant) {
    return visit(OctantTag<kRuntimeOctant>{});
  } else {
    // visit(OctantTag<k>{}) for the k in 0..7 equal to `octant`: the eight instantiations
    // without eight hand-written cases.
    return [&]<unsigned... k>(std::integer_sequence<unsigned, k...>) {
      bool result = false;
      (void)((octant == k ? (result = visit(OctantTag<k>{}), true) : false) || ...);
      return result;
    }
    (std::make_integer_sequence<unsigned, 8>{});
  }
}

// The entry points.
template <int W>
bool intersect_closest(const WideBvhView& bvh, const Ray& ray, WideHit& hit) {
  RaySetup s;
  setup_ray<W>(ray, s);
  return dispatch_octant(s.octant, [&](auto octant) {
    return intersect_closest_octant<W, decltype(octant)::value>(bvh, s, ray, hit);
  });
}

template <int W>
bool intersect_any(const WideBvhView& bvh, const Ray& ray) {
  RaySetup s;
  setup_ray<W>(ray, s);
  return dispatch_octant(s.octant, [&](auto octant) {
    return intersect_any_octant<W, decltype(octant)::value>(bvh, s, ray);
  });
}
