// The ray/sphere test's arithmetic, one source for every copy of it. No include guard and no
// includes on purpose: core/primitive_intersection.cpp includes it for intersect_sphere_t(), and
// each wide_traversal_<isa>.cpp (through accel/bvh/wide_kernel_common.h) inside its own
// namespace, so that the BVH's kernels test spheres inline, with the same operations in the same
// order (the same bits). Plain float arithmetic and builtins only: an inline function of glm or
// the standard library compiled with AVX-512 could be the copy the linker keeps for the baseline
// program too. The including file provides Ray and Vec3.

/// intersect_sphere_t() of core/primitive_intersection.h: true and the root's t, or false.
inline __attribute__((always_inline)) bool sphere_hit_t(const Ray& ray, const Vec3& center,
                                                        float radius, float& t) {
  const float fx = ray.origin.x - center.x, fy = ray.origin.y - center.y,
              fz = ray.origin.z - center.z;
  const float dx = ray.direction.x, dy = ray.direction.y, dz = ray.direction.z;
  // Dot and cross products in glm's order: (x + y) + z.
  const float a = dx * dx + dy * dy + dz * dz;
  const float half_b = fx * dx + fy * dy + fz * dz;
  const float c = (fx * fx + fy * fy + fz * fz) - radius * radius;
  // Discriminant in the form that does not cancel for distant spheres (Ray Tracing Gems, ch. 7):
  // a (r^2 - |l|^2), l = f - (half_b / a) d the line's closest point to the centre, written as
  // a r^2 - |f x d|^2 (Lagrange's identity), which needs no division: a miss costs none, and a
  // hit's two divisions below run side by side.
  const float cx = fy * dz - dy * fz, cy = fz * dx - dz * fx, cz = fx * dy - dx * fy;
  const float disc = a * (radius * radius) - (cx * cx + cy * cy + cz * cz);
  if (!(disc >= 0.0f)) return false;
  const float q = -half_b - __builtin_copysignf(__builtin_sqrtf(disc), half_b);
  float t0 = c / q;
  float t1 = q / a;
  if (t0 > t1) {
    const float larger = t0;
    t0 = t1;
    t1 = larger;
  }
  if (t0 >= ray.tmin && t0 <= ray.tmax) {
    t = t0;
    return true;
  }
  if (t1 >= ray.tmin && t1 <= ray.tmax) {
    t = t1;
    return true;
  }
  return false;
}
