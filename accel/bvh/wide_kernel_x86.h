// Box and triangle tests of the wide BVH for AVX2 and AVX-512 (VL). No include guard and no
// includes on purpose: wide_traversal_avx2.cpp and wide_traversal_avx512.cpp each include it
// once inside their own namespace (see wide_kernel_body.h), after <immintrin.h>.
//
// The triangle test must give the same bits as intersect_triangle(): the same operations in the
// same order, and these files are compiled with -ffp-contract=off so that no multiply-add is
// fused behind our back (the FMAs in the box test are explicit and only move padded bounds).

/// WatertightRay's axes for every outcome of its comparisons, packed kx | ky << 2 | kz << 4.
/// Index bits: 0 |d.x| >= |d.y|, 1 |d.y| >= |d.z|, 3 |d.x| >= |d.z|, 6 + a d[a] < 0 (bits 2, 4
/// and 5 are ignored). A load instead of branches, which incoherent rays would mispredict.
struct WatertightAxes {
  unsigned char packed[512];
};
constexpr WatertightAxes make_watertight_axes() {
  WatertightAxes table{};
  for (int i = 0; i < 512; ++i) {
    const bool x_ge_y = (i & 1) != 0, y_ge_z = (i & 2) != 0, x_ge_z = (i & 8) != 0;
    const int kz = (x_ge_y && x_ge_z) ? 0 : (y_ge_z ? 1 : 2);  // max_dimension()
    int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    if ((i >> (6 + kz)) & 1) std::swap(kx, ky);
    table.packed[i] = static_cast<unsigned char>(kx | ky << 2 | kz << 4);
  }
  return table;
}
inline constexpr WatertightAxes kWatertightAxes = make_watertight_axes();

/// The per-ray constants, four lanes at a time. The watertight test's axes and shear are
/// computed exactly as WatertightRay does (same comparisons, the same division 1 / d[kz], same
/// products), without a branch. The box test's reciprocals do not wait for the axes.
template <int W>
PRISM_KERNEL_INLINE void setup_ray(const Ray& ray, RaySetup& s) {
  // Ray is {origin, tmin, direction, tmax}: two unaligned loads fetch it all.
  static_assert(offsetof(Ray, tmin) == offsetof(Ray, origin) + 3 * sizeof(float) &&
                offsetof(Ray, tmax) == offsetof(Ray, direction) + 3 * sizeof(float));
  const __m128 o = _mm_loadu_ps(&ray.origin.x);
  const __m128 d = _mm_loadu_ps(&ray.direction.x);
  const __m128 sign = _mm_set1_ps(-0.0f);
  const __m128 one = _mm_set1_ps(1.0f);
  const __m128 abs_d = _mm_andnot_ps(sign, d);
  const __m128 tiny = _mm_cmplt_ps(abs_d, _mm_set1_ps(kMinDirection));
  const __m128 dd =
      _mm_blendv_ps(d, _mm_or_ps(_mm_and_ps(d, sign), _mm_set1_ps(kMinDirection)), tiny);
  const __m128 inv = _mm_div_ps(one, dd);  // lane 3: 1 / tmax, unused
  // 1 / d without the tiny components replaced: lane kz is WatertightRay's shear_z.
  const __m128 inv_d = _mm_div_ps(one, d);
  const __m128 x_ge = _mm_cmpge_ps(abs_d, _mm_shuffle_ps(abs_d, abs_d, _MM_SHUFFLE(3, 0, 2, 1)));
  const __m128 x_ge_z = _mm_cmpge_ps(abs_d, _mm_shuffle_ps(abs_d, abs_d, _MM_SHUFFLE(3, 1, 0, 2)));
  const int index = (_mm_movemask_ps(x_ge) & 3) | ((_mm_movemask_ps(x_ge_z) & 1) << 3) |
                    ((_mm_movemask_ps(_mm_cmplt_ps(d, _mm_setzero_ps())) & 7) << 6);
  const unsigned axes = kWatertightAxes.packed[index];
  // Lanes kx, ky, kz of d and of 1 / d: shear_x = -d[kx] * shear_z, shear_y likewise.
  const __m128i lanes =
      _mm_srlv_epi32(_mm_set1_epi32(static_cast<int>(axes)), _mm_setr_epi32(0, 2, 4, 4));
  const __m128 inv_k = _mm_permutevar_ps(inv_d, lanes);
  const __m128 shear_z = _mm_shuffle_ps(inv_k, inv_k, _MM_SHUFFLE(2, 2, 2, 2));
  const __m128 shear = _mm_mul_ps(_mm_xor_ps(_mm_permutevar_ps(d, lanes), sign), shear_z);

  const __m128 abs_o = _mm_andnot_ps(sign, o);
  __m128 scale = _mm_max_ps(abs_o, _mm_shuffle_ps(abs_o, abs_o, _MM_SHUFFLE(3, 0, 2, 1)));
  scale = _mm_max_ps(scale, _mm_shuffle_ps(abs_o, abs_o, _MM_SHUFFLE(3, 1, 0, 2)));
  const __m128 pad =
      _mm_mul_ps(_mm_mul_ps(_mm_set1_ps(kOriginPadding), scale), _mm_andnot_ps(sign, inv));
  const __m128 base = _mm_mul_ps(_mm_xor_ps(o, sign), inv);
  // Whole vectors, one per field (kRaySetupTakesVectorStores).
  _mm_storeu_ps(s.org, o);  // org, and tmin: the Ray's tmin follows its origin
  s.tmax = ray.tmax;
  _mm_storeu_ps(s.inv, inv);
  _mm_storeu_ps(s.near_offset, _mm_sub_ps(base, pad));
  _mm_storeu_ps(s.far_offset, _mm_add_ps(base, pad));
  s.octant = static_cast<unsigned>(_mm_movemask_ps(inv)) & 7u;
  _mm_storeu_si128(reinterpret_cast<__m128i*>(&s.kx), _mm_and_si128(lanes, _mm_set1_epi32(3)));
  _mm_storeu_ps(&s.shear_x, _mm_blend_ps(shear, shear_z, 0b0100));  // shear_x, shear_y, shear_z
  // The rows of WideNode<W>::bounds holding the near planes (2 axis, + 1 where the direction is
  // negative) and the far planes (the other one), as offsets in floats: an index the box test's
  // loads scale by themselves.
  constexpr int kRowShift = W == 8 ? 3 : (W == 4 ? 2 : 1);
  static_assert(W == 1 << kRowShift);
  const __m128i near =
      _mm_add_epi32(_mm_setr_epi32(0, 2, 4, 6), _mm_srli_epi32(_mm_castps_si128(inv), 31));
  const __m128i far = _mm_xor_si128(near, _mm_set1_epi32(1));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(s.near_index), _mm_slli_epi32(near, kRowShift));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(s.far_index), _mm_slli_epi32(far, kRowShift));
}

/// The box test's per-ray constants, for every width: the RaySetup, whose scalars the box test
/// broadcasts where it uses them (an FMA's broadcast operand, or one load), including where the
/// rows of the near and far planes of each axis start (by the ray's octant). kOctant is always
/// kRuntimeOctant here (see below). The closest-hit loop calls its leaves out of line, which
/// clobbers every vector register, so the loop reloaded the constants from the stack at each node
/// anyway; broadcasting them once per ray only added ten vector stores per ray
/// (docs/PERFORMANCE.md, "The per-ray set-up").
template <int W, unsigned kOctant>
struct NodeRay {
  explicit NodeRay(const RaySetup& s) : setup(s) {}
  /// The near (far) planes of `node` on `axis`: a row of WideNode::bounds (setup_ray<W>()).
  const float* near_planes(const WideNode<W>& node, int axis) const {
    return &node.bounds[0][0] + setup.near_index[axis];
  }
  const float* far_planes(const WideNode<W>& node, int axis) const {
    return &node.bounds[0][0] + setup.far_index[axis];
  }
  const RaySetup& setup;
};

/// The x86 kernels take the ray's octant at run time: where the near and far rows start comes
/// from the RaySetup (an indexed load costs nothing), and one instantiation of the traversal serves
/// every ray. Measured against one instantiation per octant (a switch on the octant per ray): 5%
/// more rays per second on incoherent rays, whose octants the branch predictor cannot guess.
inline constexpr unsigned kRuntimeOctant = 8;
inline constexpr bool kKernelUsesRuntimeOctant = true;

/// Slab test of all children: returns the mask of children the ray enters in [tmin, tmax],
/// with their padded entry distances in tnear.
template <unsigned kOctant>
PRISM_KERNEL_INLINE uint32_t intersect_node(const WideNode<8>& node, const NodeRay<8, kOctant>& ray,
                                            float tmax, float* tnear) {
  const RaySetup& s = ray.setup;
  __m256 tn = _mm256_broadcast_ss(&s.tmin);
  __m256 tf = _mm256_set1_ps(tmax);
  for (int a = 0; a < 3; ++a) {
    const __m256 inv = _mm256_broadcast_ss(&s.inv[a]);
    const __m256 n = _mm256_fmadd_ps(_mm256_load_ps(ray.near_planes(node, a)), inv,
                                     _mm256_broadcast_ss(&s.near_offset[a]));
    const __m256 f = _mm256_fmadd_ps(_mm256_load_ps(ray.far_planes(node, a)), inv,
                                     _mm256_broadcast_ss(&s.far_offset[a]));
    tn = _mm256_max_ps(n, tn);
    tf = _mm256_min_ps(f, tf);
  }
  _mm256_store_ps(tnear, tn);
#ifdef __AVX512VL__
  return _mm256_cmp_ps_mask(tn, tf, _CMP_LE_OQ);
#else
  return static_cast<uint32_t>(_mm256_movemask_ps(_mm256_cmp_ps(tn, tf, _CMP_LE_OQ)));
#endif
}

template <unsigned kOctant>
PRISM_KERNEL_INLINE uint32_t intersect_node(const WideNode<4>& node, const NodeRay<4, kOctant>& ray,
                                            float tmax, float* tnear) {
  const RaySetup& s = ray.setup;
  __m128 tn = _mm_broadcast_ss(&s.tmin);
  __m128 tf = _mm_set1_ps(tmax);
  for (int a = 0; a < 3; ++a) {
    const __m128 inv = _mm_broadcast_ss(&s.inv[a]);
    const __m128 n = _mm_fmadd_ps(_mm_load_ps(ray.near_planes(node, a)), inv,
                                  _mm_broadcast_ss(&s.near_offset[a]));
    const __m128 f =
        _mm_fmadd_ps(_mm_load_ps(ray.far_planes(node, a)), inv, _mm_broadcast_ss(&s.far_offset[a]));
    tn = _mm_max_ps(n, tn);
    tf = _mm_min_ps(f, tf);
  }
  _mm_store_ps(tnear, tn);
#ifdef __AVX512VL__
  return _mm_cmp_ps_mask(tn, tf, _CMP_LE_OQ);
#else
  return static_cast<uint32_t>(_mm_movemask_ps(_mm_cmp_ps(tn, tf, _CMP_LE_OQ)));
#endif
}

template <unsigned kOctant>
PRISM_KERNEL_INLINE uint32_t intersect_node(const WideNode<2>& node, const NodeRay<2, kOctant>& ray,
                                            float tmax, float* tnear) {
  // Two floats per plane; the upper lanes are zero and masked off below.
  auto load2 = [](const float* p) {
    return _mm_castpd_ps(_mm_load_sd(reinterpret_cast<const double*>(p)));
  };
  const RaySetup& s = ray.setup;
  __m128 tn = _mm_broadcast_ss(&s.tmin);
  __m128 tf = _mm_set1_ps(tmax);
  for (int a = 0; a < 3; ++a) {
    const __m128 inv = _mm_broadcast_ss(&s.inv[a]);
    const __m128 n =
        _mm_fmadd_ps(load2(ray.near_planes(node, a)), inv, _mm_broadcast_ss(&s.near_offset[a]));
    const __m128 f =
        _mm_fmadd_ps(load2(ray.far_planes(node, a)), inv, _mm_broadcast_ss(&s.far_offset[a]));
    tn = _mm_max_ps(n, tn);
    tf = _mm_min_ps(f, tf);
  }
  alignas(16) float tn4[4];
  _mm_store_ps(tn4, tn);
  tnear[0] = tn4[0];
  tnear[1] = tn4[1];
  return static_cast<uint32_t>(_mm_movemask_ps(_mm_cmp_ps(tn, tf, _CMP_LE_OQ))) & 3u;
}

/// The watertight test's per-ray constants: a view of the RaySetup, whose scalars the triangle
/// test broadcasts where it uses them, as NodeRay does.
struct TriangleRay {
  TriangleRay(const RaySetup& q, const Ray&) : setup(q) {}
  /// For the scalar code: the whole test of lanes with a zero edge function, with the same
  /// values setup_ray() computed.
  WatertightRay watertight(float tmax) const {
    WatertightRay w;
    w.origin = Vec3(setup.org[0], setup.org[1], setup.org[2]);
    w.kx = setup.kx;
    w.ky = setup.ky;
    w.kz = setup.kz;
    w.shear_x = setup.shear_x;
    w.shear_y = setup.shear_y;
    w.shear_z = setup.shear_z;
    w.tmin = setup.tmin;
    w.tmax = tmax;
    return w;
  }
  const RaySetup& setup;
};

// One template serves one block (4 lanes, __m128) and two blocks at once (8 lanes, __m256);
// these overloads are all it needs.
inline __m128 vadd(__m128 a, __m128 b) { return _mm_add_ps(a, b); }
inline __m256 vadd(__m256 a, __m256 b) { return _mm256_add_ps(a, b); }
inline __m128 vsub(__m128 a, __m128 b) { return _mm_sub_ps(a, b); }
inline __m256 vsub(__m256 a, __m256 b) { return _mm256_sub_ps(a, b); }
inline __m128 vmul(__m128 a, __m128 b) { return _mm_mul_ps(a, b); }
inline __m256 vmul(__m256 a, __m256 b) { return _mm256_mul_ps(a, b); }
inline __m128 vdiv(__m128 a, __m128 b) { return _mm_div_ps(a, b); }
inline __m256 vdiv(__m256 a, __m256 b) { return _mm256_div_ps(a, b); }
inline __m128 vor(__m128 a, __m128 b) { return _mm_or_ps(a, b); }
inline __m256 vor(__m256 a, __m256 b) { return _mm256_or_ps(a, b); }
inline __m128 vand(__m128 a, __m128 b) { return _mm_and_ps(a, b); }
inline __m256 vand(__m256 a, __m256 b) { return _mm256_and_ps(a, b); }
inline __m128 vandnot(__m128 a, __m128 b) { return _mm_andnot_ps(a, b); }
inline __m256 vandnot(__m256 a, __m256 b) { return _mm256_andnot_ps(a, b); }
inline __m128 vmin(__m128 a, __m128 b) { return _mm_min_ps(a, b); }
inline __m256 vmin(__m256 a, __m256 b) { return _mm256_min_ps(a, b); }
inline __m128 vblend(__m128 a, __m128 b, __m128 m) { return _mm_blendv_ps(a, b, m); }
inline __m256 vblend(__m256 a, __m256 b, __m256 m) { return _mm256_blendv_ps(a, b, m); }
inline int vmask(__m128 a) { return _mm_movemask_ps(a); }
inline int vmask(__m256 a) { return _mm256_movemask_ps(a); }
inline void vstore(float* p, __m128 a) { _mm_store_ps(p, a); }
inline void vstore(float* p, __m256 a) { _mm256_store_ps(p, a); }
template <int kPredicate>
inline __m128 vcmp(__m128 a, __m128 b) {
  return _mm_cmp_ps(a, b, kPredicate);
}
template <int kPredicate>
inline __m256 vcmp(__m256 a, __m256 b) {
  return _mm256_cmp_ps(a, b, kPredicate);
}

/// Safety factor of the float t's error bound in intersect_triangles(), in units of the bound's
/// leading term: 16 float epsilons where the analysis needs about 5.
inline constexpr float kTErrorScale = 16.0f / (1 << 24);

template <typename V>
struct Lanes;

template <>
struct Lanes<__m128> {
  static constexpr int kCount = 4;
  static __m128 set1(float x) { return _mm_set1_ps(x); }
  /// Every bit of a lane set to the lane's sign bit.
  static __m128 sign_mask(__m128 a) {
    return _mm_castsi128_ps(_mm_srai_epi32(_mm_castps_si128(a), 31));
  }
  static __m128 load(const TriangleBlock* const* blocks, int vertex, int axis) {
    return _mm_load_ps(blocks[0]->p[vertex][axis]);
  }
  static __m128 horizontal_min(__m128 a) {
    const __m128 m = _mm_min_ps(a, _mm_shuffle_ps(a, a, _MM_SHUFFLE(2, 3, 0, 1)));
    return _mm_min_ps(m, _mm_shuffle_ps(m, m, _MM_SHUFFLE(1, 0, 3, 2)));
  }
};

template <>
struct Lanes<__m256> {
  static constexpr int kCount = 8;
  static __m256 set1(float x) { return _mm256_set1_ps(x); }
  static __m256 sign_mask(__m256 a) {
    return _mm256_castsi256_ps(_mm256_srai_epi32(_mm256_castps_si256(a), 31));
  }
  static __m256 load(const TriangleBlock* const* blocks, int vertex, int axis) {
    return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_load_ps(blocks[0]->p[vertex][axis])),
                                _mm_load_ps(blocks[1]->p[vertex][axis]), 1);
  }
  static __m256 horizontal_min(__m256 a) {
    __m256 m = _mm256_min_ps(a, _mm256_permute2f128_ps(a, a, 1));
    m = _mm256_min_ps(m, _mm256_shuffle_ps(m, m, _MM_SHUFFLE(2, 3, 0, 1)));
    return _mm256_min_ps(m, _mm256_shuffle_ps(m, m, _MM_SHUFFLE(1, 0, 3, 2)));
  }
};

/// sheared_triangle_hit() (core/primitive_intersection.cpp) on four lanes at once, in double:
/// the same operations in the same order, so t, u, v are its bits. `s` holds the nine sheared
/// coordinates (ax, ay, az, bx, ... cz), `stride` floats apart; writes t, u, v of these four lanes
/// and returns the mask (bits 0-3) of those with a non-zero determinant and t in [tmin, tmax].
PRISM_KERNEL_INLINE int double_hit_parameters4(const float* s, int stride, float shear_z,
                                               float tmin, float tmax, float* t, float* u,
                                               float* v) {
  auto load = [&](int k) { return _mm256_cvtps_pd(_mm_load_ps(s + stride * k)); };
  const __m256d ax = load(0), ay = load(1), az = load(2), bx = load(3), by = load(4), bz = load(5),
                cx = load(6), cy = load(7), cz = load(8);
  const __m256d e0 = _mm256_sub_pd(_mm256_mul_pd(bx, cy), _mm256_mul_pd(by, cx));
  const __m256d e1 = _mm256_sub_pd(_mm256_mul_pd(cx, ay), _mm256_mul_pd(cy, ax));
  const __m256d e2 = _mm256_sub_pd(_mm256_mul_pd(ax, by), _mm256_mul_pd(ay, bx));
  const __m256d det = _mm256_add_pd(_mm256_add_pd(e0, e1), e2);
  const __m256d t_scaled =
      _mm256_mul_pd(_mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(e0, az), _mm256_mul_pd(e1, bz)),
                                  _mm256_mul_pd(e2, cz)),
                    _mm256_set1_pd(static_cast<double>(shear_z)));
  const __m256d inv_det = _mm256_div_pd(_mm256_set1_pd(1.0), det);
  const __m128 tf = _mm256_cvtpd_ps(_mm256_mul_pd(t_scaled, inv_det));
  _mm_store_ps(t, tf);
  _mm_store_ps(u, _mm256_cvtpd_ps(_mm256_mul_pd(e1, inv_det)));
  _mm_store_ps(v, _mm256_cvtpd_ps(_mm256_mul_pd(e2, inv_det)));
  const int nonzero = _mm256_movemask_pd(_mm256_cmp_pd(det, _mm256_setzero_pd(), _CMP_NEQ_OQ));
  const __m128 in_range = _mm_and_ps(_mm_cmp_ps(tf, _mm_set1_ps(tmin), _CMP_GE_OQ),
                                     _mm_cmp_ps(tf, _mm_set1_ps(tmax), _CMP_LE_OQ));
  return nonzero & _mm_movemask_ps(in_range);
}

/// double_hit_parameters4() on the lanes of `candidates` (one or two blocks): the mask of those
/// hit in [tmin, tmax], with their t, u, v. A block without a candidate lane is skipped.
template <typename V>
PRISM_KERNEL_INLINE int double_hit_parameters(const V* const sheared[9], int candidates,
                                              const TriangleRay& ray, float tmax, float* t,
                                              float* u, float* v) {
  constexpr int kCount = Lanes<V>::kCount;
  alignas(32) float s[9][kCount];
  for (int k = 0; k < 9; ++k) vstore(s[k], *sheared[k]);
  int mask = 0;
  for (int first = 0; first < kCount; first += 4) {
    if (((candidates >> first) & 15) == 0) continue;
    mask |= double_hit_parameters4(&s[0][first], kCount, ray.setup.shear_z, ray.setup.tmin, tmax,
                                   t + first, u + first, v + first)
            << first;
  }
  return mask & candidates;
}

/// Watertight triangle tests on the lanes of one or two blocks at once: the hit decision in
/// intersect_triangle()'s order of operations, then t, u, v of the lanes hit in double precision
/// (double_hit_parameters(), sheared_triangle_hit()'s bits). Lanes with an exactly zero edge
/// function go through the scalar test (its double-precision path). The tree holds no degenerate
/// triangle (make_prim_refs()), so no lane is checked for one. Replaces `hit` by a hit in
/// [tmin, tmax] that comes before it and returns whether it did (any_hit: whether any lane hits).
template <typename V>
PRISM_KERNEL_INLINE bool intersect_triangles(const TriangleBlock* const* blocks,
                                             const TriangleRay& ray, float tmax, WideHit& hit,
                                             bool any_hit) {
  using L = Lanes<V>;
  const RaySetup& q = ray.setup;
  const int kx = q.kx, ky = q.ky, kz = q.kz;
  const V oz = L::set1(q.org[kz]), ox = L::set1(q.org[kx]), oy = L::set1(q.org[ky]);
  const V sx = L::set1(q.shear_x), sy = L::set1(q.shear_y);
  const V az = vsub(L::load(blocks, 0, kz), oz);
  const V bz = vsub(L::load(blocks, 1, kz), oz);
  const V cz = vsub(L::load(blocks, 2, kz), oz);
  const V ax = vadd(vsub(L::load(blocks, 0, kx), ox), vmul(sx, az));
  const V ay = vadd(vsub(L::load(blocks, 0, ky), oy), vmul(sy, az));
  const V bx = vadd(vsub(L::load(blocks, 1, kx), ox), vmul(sx, bz));
  const V by = vadd(vsub(L::load(blocks, 1, ky), oy), vmul(sy, bz));
  const V cx = vadd(vsub(L::load(blocks, 2, kx), ox), vmul(sx, cz));
  const V cy = vadd(vsub(L::load(blocks, 2, ky), oy), vmul(sy, cz));

  const V e0 = vsub(vmul(bx, cy), vmul(by, cx));
  const V e1 = vsub(vmul(cx, ay), vmul(cy, ax));
  const V e2 = vsub(vmul(ax, by), vmul(ay, bx));
  // Lanes with an edge function exactly zero (or NaN) take the scalar test, which decides
  // them in double precision; for all others the sign bit is the sign, so mixed signs (the ray
  // passes outside) are an OR of the signs without an AND of them.
  const V zero = L::set1(0.0f);
  const V special =
      vor(vor(vcmp<_CMP_EQ_UQ>(e0, zero), vcmp<_CMP_EQ_UQ>(e1, zero)), vcmp<_CMP_EQ_UQ>(e2, zero));
  const V outside = vandnot(vand(vand(e0, e1), e2), vor(vor(e0, e1), e2));  // sign bit only
  constexpr int kAll = (1 << L::kCount) - 1;
  const int special_mask = vmask(special);
  // Most blocks a ray reaches miss all their triangles: stop before t and the division.
  if (vmask(outside) == kAll && special_mask == 0) return false;
  const V det = vadd(vadd(e0, e1), e2);
  // A float t with a bound on how far it can be from the double-precision t the scalar code
  // computes from the same sheared vertices: a lane whose t cannot be in [tmin, tmax] needs no
  // scalar test. The bound only filters, it decides nothing, so the bits stay brute force's.
  // e_i is off by at most 2 eps (|x y| + |x' y'|) =: 2 eps E_i, so T = sum e_i z_i by about
  // eps sum E_i |z_i| and det by eps sum E_i, each plus a few eps of itself; t = T s / det.
  const V sign = L::set1(-0.0f);
  const V sz = L::set1(q.shear_z);
  const V t_num = vadd(vadd(vmul(e0, az), vmul(e1, bz)), vmul(e2, cz));
  const V inv_det = vdiv(L::set1(1.0f), det);
  const V t = vmul(vmul(t_num, sz), inv_det);
  const auto vabs = [&](V x) { return vandnot(sign, x); };
  const V big0 = vadd(vabs(vmul(bx, cy)), vabs(vmul(by, cx)));
  const V big1 = vadd(vabs(vmul(cx, ay)), vabs(vmul(cy, ax)));
  const V big2 = vadd(vabs(vmul(ax, by)), vabs(vmul(ay, bx)));
  const V num_error = vadd(vadd(vmul(big0, vabs(az)), vmul(big1, vabs(bz))), vmul(big2, vabs(cz)));
  const V det_error = vadd(vadd(big0, big1), big2);
  const V t_error = vadd(
      vmul(L::set1(kTErrorScale), vmul(vadd(num_error, vmul(vabs(vmul(t_num, inv_det)), det_error)),
                                       vabs(vmul(sz, inv_det)))),
      vmul(L::set1(kTErrorScale), vabs(t)));
  // NaN t (det 0, infinities) compares false both ways: such lanes go to the scalar test.
  const V out_of_range = vor(vcmp<_CMP_GT_OQ>(vsub(t, t_error), L::set1(tmax)),
                             vcmp<_CMP_LT_OQ>(vadd(t, t_error), L::set1(q.tmin)));
  const V ok =
      vandnot(vor(vor(L::sign_mask(outside), special), out_of_range), vcmp<_CMP_NEQ_UQ>(det, zero));
  const int mask = vmask(ok);
  if (mask == 0 && special_mask == 0) return false;
  // Any hit: a lane whose t lies in [tmin, tmax] even moved by its error bound is hit in double
  // precision too (its double t is within the bound of this one, and rounding it to float keeps
  // it between the float tmin and tmax), so the answer is known without the double step. The
  // same bound the filter above relies on; the answer is still brute force's.
  if (any_hit && mask != 0) {
    const V surely_in_range = vand(vcmp<_CMP_GE_OQ>(vsub(t, t_error), L::set1(q.tmin)),
                                   vcmp<_CMP_LE_OQ>(vadd(t, t_error), L::set1(tmax)));
    if ((vmask(surely_in_range) & mask) != 0) return true;
  }
  auto geom = [&](int lane) { return blocks[lane >> 2]->geom_id[lane & 3]; };
  auto prim = [&](int lane) { return blocks[lane >> 2]->prim_id[lane & 3]; };
  auto vertices = [&](int lane) { return &blocks[lane >> 2]->p[0][0][lane & 3]; };
  // The lanes the ray passes through take t, u, v in double precision, four lanes at a time, as
  // intersect_triangle() does one; lanes with a zero edge function take the whole scalar test.
  // Either way the bits are brute force's.
  bool found = false;
  if (mask != 0) {
    alignas(32) float lane_t[L::kCount], lane_u[L::kCount], lane_v[L::kCount];
    const V* sheared[9] = {&ax, &ay, &az, &bx, &by, &bz, &cx, &cy, &cz};
    const int hit_mask = double_hit_parameters<V>(sheared, mask, ray, tmax, lane_t, lane_u, lane_v);
    for (unsigned z = static_cast<unsigned>(hit_mask); z != 0; z &= z - 1) {
      const int lane = lowest_lane(z);
      // Each lane is in [tmin, tmax] as the call began; after a lane is taken, hit.t is the
      // shrunk tmax and comes_before_hit() refuses what lies beyond it.
      if (!any_hit && !comes_before_hit(lane_t[lane], geom(lane), prim(lane), hit)) continue;
      if (any_hit) return true;
      tmax = lane_t[lane];
      hit = {lane_t[lane], lane_u[lane], lane_v[lane], geom(lane), prim(lane), vertices(lane)};
      found = true;
    }
  }
  for (unsigned z = static_cast<unsigned>(special_mask); z != 0; z &= z - 1) {
    const int lane = lowest_lane(z);
    PrimitiveHit h;
    if (!intersect_block_lane(ray.watertight(tmax), *blocks[lane >> 2], lane & 3, h)) continue;
    if (any_hit) return true;
    if (!comes_before_hit(h.t, geom(lane), prim(lane), hit)) continue;
    tmax = h.t;
    hit = {h.t, h.u, h.v, geom(lane), prim(lane), vertices(lane)};
    found = true;
  }
  return found;
}

/// The blocks of one leaf: two at a time in 8 lanes, an odd last one in 4. Same contract as
/// intersect_triangles().
template <bool kAnyHit>
PRISM_KERNEL_INLINE bool intersect_leaf_blocks(const TriangleBlock* blocks, uint32_t count,
                                               const TriangleRay& ray, float tmax, WideHit& hit) {
  bool found = false;
  uint32_t b = 0;
  for (; b + 2 <= count; b += 2) {
    const TriangleBlock* pair[2] = {blocks + b, blocks + b + 1};
    if (intersect_triangles<__m256>(pair, ray, tmax, hit, kAnyHit)) {
      if (kAnyHit) return true;
      found = true;
      tmax = hit.t;
    }
  }
  if (b < count) {
    const TriangleBlock* single[1] = {blocks + b};
    if (intersect_triangles<__m128>(single, ray, tmax, hit, kAnyHit)) found = true;
  }
  return found;
}

/// The closest-hit loop calls its leaves out of line: inlined there, it measured no faster
/// (within 1%, 2026-12-02 and again 2026-12-03), and the loop stays small.
__attribute__((noinline)) bool intersect_closest_blocks(const TriangleBlock* blocks, uint32_t count,
                                                        const TriangleRay& ray, float tmax,
                                                        WideHit& hit) {
  return intersect_leaf_blocks<false>(blocks, count, ray, tmax, hit);
}

/// intersect_leaf_blocks() for both loops: inlined into the any-hit loop (shadow rays 3-6%
/// faster, 2026-12-03: no call that spills the box test's registers), out of line for the
/// closest-hit loop.
PRISM_KERNEL_INLINE bool intersect_blocks(const TriangleBlock* blocks, uint32_t count,
                                          const TriangleRay& ray, float tmax, WideHit& hit,
                                          bool any_hit) {
  if (any_hit) return intersect_leaf_blocks<true>(blocks, count, ray, tmax, hit);
  return intersect_closest_blocks(blocks, count, ray, tmax, hit);
}
