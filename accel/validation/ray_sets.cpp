#include "accel/validation/ray_sets.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace prism {
namespace {

/// SplitMix64: tiny, fast, and the same sequence on every standard library (unlike the
/// <random> distributions).
class Rng {
 public:
  explicit Rng(uint64_t seed) : state_(seed) {}
  uint64_t next() {
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1).
  float uniform() { return float(next() >> 40) * 0x1p-24f; }
  float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }
  size_t index(size_t n) { return size_t(next() % n); }

 private:
  uint64_t state_;
};

Vec3 uniform_direction(Rng& rng) {
  const float z = rng.uniform(-1.0f, 1.0f);
  const float phi = rng.uniform(0.0f, 2.0f * kPi);
  const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {s * std::cos(phi), s * std::sin(phi), z};
}

Vec3 point_in(const Bounds3& b, Rng& rng) {
  return {rng.uniform(b.lower.x, b.upper.x), rng.uniform(b.lower.y, b.upper.y),
          rng.uniform(b.lower.z, b.upper.z)};
}

/// The box rays are generated in: `bounds`, [-1, 1]^3 when empty, and every axis at least a
/// tenth of the longest one (origins inside a flat scene's box would all lie on its plane).
Bounds3 usable_bounds(const Bounds3& bounds) {
  if (bounds.empty()) return {Vec3(-1.0f), Vec3(1.0f)};
  const float longest = std::max(max_component(bounds.diagonal()), 1e-3f);
  const Vec3 grow = glm::max(Vec3(0.0f), 0.05f * longest - 0.5f * bounds.diagonal());
  return {bounds.lower - grow, bounds.upper + grow};
}

/// The box grown by a quarter of its diagonal on every side (at least 0.1 in total).
Bounds3 with_margin(const Bounds3& b) {
  const float margin = std::max(0.25f * glm::length(b.diagonal()), 0.1f);
  return {b.lower - Vec3(margin), b.upper + Vec3(margin)};
}

/// A direction from `origin` to `target`, or a random one when they coincide.
Vec3 toward(const Vec3& origin, const Vec3& target, Rng& rng) {
  const Vec3 d = target - origin;
  return d == Vec3(0.0f) ? uniform_direction(rng) : d;
}

}  // namespace

std::vector<Ray> random_rays(const Bounds3& bounds, size_t count, uint64_t seed) {
  Rng rng(seed * 0x2545f4914f6cdd1dull + 1);
  const Bounds3 box = usable_bounds(bounds);
  const Bounds3 outer = with_margin(box);
  const float size = glm::length(outer.diagonal());
  std::vector<Ray> rays(count);
  for (Ray& ray : rays) {
    ray.origin = rng.uniform() < 0.5f ? point_in(box, rng) : point_in(outer, rng);
    ray.direction =
        rng.uniform() < 0.3f ? toward(ray.origin, point_in(box, rng), rng) : uniform_direction(rng);
    // Directions need not be unit length: t is then in units of |direction|.
    if (rng.uniform() < 0.2f) ray.direction *= std::exp2(rng.uniform(-3.0f, 3.0f));
    const float reach = size / glm::length(ray.direction);
    const float kind = rng.uniform();
    if (kind < 0.6f) {
      ray.tmin = 0.0f;
      ray.tmax = kInfinity;
    } else if (kind < 0.75f) {
      ray.tmin = rng.uniform(0.0f, 0.5f) * reach;
      ray.tmax = kInfinity;
    } else if (kind < 0.9f) {
      ray.tmin = rng.uniform(0.0f, 0.5f) * reach;
      ray.tmax = ray.tmin + rng.uniform(0.0f, 0.5f) * reach;
    } else {
      ray.tmin = 0.0f;
      ray.tmax = rng.uniform(0.0f, 0.5f) * reach;
    }
  }
  return rays;
}

std::vector<Ray> feature_rays(const SceneGeometry& geometry, size_t count, uint64_t seed) {
  std::vector<Ray> rays;
  const size_t triangles = geometry.triangle_count();
  const size_t spheres = geometry.spheres.size();
  if (triangles + spheres == 0) return rays;
  Rng rng(seed * 0x9e3779b97f4a7c15ull + 7);
  const Bounds3 outer = with_margin(usable_bounds(geometry.bounds()));
  // First global triangle index of each mesh, to pick triangles uniformly.
  std::vector<size_t> first(geometry.meshes.size() + 1, 0);
  for (size_t m = 0; m < geometry.meshes.size(); ++m) {
    first[m + 1] = first[m] + geometry.meshes[m].triangles.size();
  }
  rays.reserve(count);
  while (rays.size() < count) {
    Ray ray;
    ray.origin = point_in(outer, rng);
    if (spheres > 0 && (triangles == 0 || rng.uniform() < 0.15f)) {
      // A point on the sphere seen at right angles from the origin: the ray through it
      // passes just inside the silhouette.
      const Sphere& s = geometry.spheres[rng.index(spheres)];
      const Vec3 w = s.center - ray.origin;
      Vec3 side = glm::cross(w, uniform_direction(rng));
      if (glm::length(side) == 0.0f) side = Vec3(1.0f, 0.0f, 0.0f);
      const Vec3 target = s.center + s.radius * glm::normalize(side);
      ray.direction = toward(ray.origin, target, rng);
    } else {
      const size_t global = rng.index(triangles);
      const size_t m =
          size_t(std::upper_bound(first.begin(), first.end(), global) - first.begin() - 1);
      const TriangleMesh& mesh = geometry.meshes[m];
      const glm::uvec3& tri = mesh.triangles[global - first[m]];
      const int corner = int(rng.index(3));
      const Vec3& a = mesh.positions[tri[corner]];
      const Vec3& b = mesh.positions[tri[(corner + 1) % 3]];
      const float kind = rng.uniform();
      Vec3 target;
      if (kind < 1.0f / 3.0f) {
        target = a;
      } else if (kind < 2.0f / 3.0f) {
        target = 0.5f * (a + b);
      } else {
        const float s = rng.uniform();
        target = (1.0f - s) * a + s * b;
      }
      ray.direction = toward(ray.origin, target, rng);
    }
    const float end = rng.uniform();
    if (end < 0.1f) {
      ray.tmax = 1.0f;  // the ray ends exactly at its target
    } else if (end < 0.15f) {
      ray.tmin = 1.0f;  // or starts there
    }
    rays.push_back(ray);
  }
  return rays;
}

std::string format_ray(const Ray& ray) {
  char buf[320];
  std::snprintf(buf, sizeof buf, "origin=(%a, %a, %a) direction=(%a, %a, %a) tmin=%a tmax=%a",
                double(ray.origin.x), double(ray.origin.y), double(ray.origin.z),
                double(ray.direction.x), double(ray.direction.y), double(ray.direction.z),
                double(ray.tmin), double(ray.tmax));
  return buf;
}

std::optional<Ray> parse_ray(const std::string& text) {
  Ray ray;
  int consumed = 0;
  // %f reads hexadecimal floats, inf and nan as well.
  const int n =
      std::sscanf(text.c_str(), " origin=(%f, %f, %f) direction=(%f, %f, %f) tmin=%f tmax=%f %n",
                  &ray.origin.x, &ray.origin.y, &ray.origin.z, &ray.direction.x, &ray.direction.y,
                  &ray.direction.z, &ray.tmin, &ray.tmax, &consumed);
  if (n != 8 || size_t(consumed) != text.size()) return std::nullopt;
  return ray;
}

}  // namespace prism
