#include "accel/bench/bench_rays.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <optional>

#include "core/error.h"
#include "core/parallel.h"
#include "core/sampler.h"

namespace prism {
namespace {

/// Counter-based uniform numbers: value (stream, index, dimension) does not depend on the order
/// or thread it is drawn in, so the sets are the same for any thread count.
class BenchRng {
 public:
  BenchRng(uint64_t seed, uint64_t stream)
      : key_(mix_bits(seed * 0x9e3779b97f4a7c15ULL + stream)) {}
  float get(uint64_t index, uint32_t dimension) const {
    return bits_to_unit_float(
        static_cast<uint32_t>(mix_bits(key_ ^ (index * 8 + dimension)) >> 32));
  }

 private:
  uint64_t key_;
};

Vec3 uniform_sphere(float u1, float u2) {
  const float z = 1.0f - 2.0f * u1;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

Vec3 cosine_hemisphere(const Vec3& n, float u1, float u2) {
  const Vec3 helper = std::abs(n.x) > 0.5f ? Vec3(0, 1, 0) : Vec3(1, 0, 0);
  const Vec3 t = glm::normalize(glm::cross(helper, n));
  const Vec3 b = glm::cross(n, t);
  const float r = std::sqrt(u1);
  const float phi = 2.0f * kPi * u2;
  const float z = std::sqrt(std::max(0.0f, 1.0f - u1));
  return r * std::cos(phi) * t + r * std::sin(phi) * b + z * n;
}

struct SurfacePoint {
  Vec3 position;
  Vec3 error;      ///< SurfaceInteraction::position_error
  Vec3 normal;     ///< geometric, facing the incoming ray
  uint32_t pixel;  ///< of the camera ray this point descends from

  /// What spawn_ray() and spawn_ray_to() read of the hit.
  SurfaceInteraction interaction() const {
    SurfaceInteraction si;
    si.position = position;
    si.position_error = error;
    si.geometric_normal = normal;
    return si;
  }
};

// Hit points of `rays` (in ray order, misses dropped), traced in parallel.
std::vector<SurfacePoint> trace_points(const Scene& scene, const Accelerator& tracer,
                                       const std::vector<Ray>& rays,
                                       const std::vector<uint32_t>& pixels) {
  std::vector<std::optional<SurfacePoint>> points(rays.size());
  parallel_for_range(
      rays.size(),
      [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
          const std::optional<Hit> hit = tracer.intersect(rays[i]);
          if (!hit) continue;
          const SurfaceInteraction si = scene.surface_at(rays[i], *hit);
          Vec3 n = si.geometric_normal;
          if (glm::dot(n, rays[i].direction) > 0.0f) n = -n;
          points[i] = SurfacePoint{si.position, si.position_error, n, pixels[i]};
        }
      },
      1024);
  std::vector<SurfacePoint> out;
  out.reserve(points.size());
  for (const auto& p : points) {
    if (p) out.push_back(*p);
  }
  return out;
}

BenchRaySet bounce(const std::string& name, const std::vector<SurfacePoint>& points,
                   const BenchRng& rng) {
  BenchRaySet set{name, false, std::vector<Ray>(points.size()),
                  std::vector<uint32_t>(points.size())};
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3 d = cosine_hemisphere(points[i].normal, rng.get(i, 0), rng.get(i, 1));
    set.rays[i] = spawn_ray(points[i].interaction(), d);
    set.pixels[i] = points[i].pixel;
  }
  return set;
}

// A ray from `p` towards a point of `light` (or along it for distant lights).
Ray shadow_ray(const SurfacePoint& p, const Light* light, const Bounds3& bounds, float u1,
               float u2) {
  Vec3 target;
  bool distant = false;
  Vec3 dir;
  if (light == nullptr) {
    target = bounds.center() + Vec3(0.0f, bounds.diagonal().y, 0.0f);
  } else if (light->type == LightType::kDirectional) {
    distant = true;
    dir = -light->direction;
  } else if (light->type == LightType::kAmbient) {
    distant = true;
    dir = cosine_hemisphere(p.normal, u1, u2);
  } else if (light->type == LightType::kArea) {
    target = light->position + (u1 - 0.5f) * light->edge_u + (u2 - 0.5f) * light->edge_v;
  } else {
    target = light->position;
  }
  if (distant) return spawn_ray(p.interaction(), dir);
  // As the integrators spawn it (error-bounded at both ends), and at least 1e-3 of the way short
  // of the light so that an emitter's own geometry does not count.
  Ray r = spawn_ray_to(p.interaction(), target);
  r.tmax = std::min(r.tmax, 1.0f - 1e-3f);
  return r;
}

constexpr char kMagic[8] = {'P', 'R', 'I', 'S', 'M', 'R', 'Y', '2'};

}  // namespace

std::vector<BenchRaySet> make_bench_ray_sets(const Scene& scene, const Accelerator& tracer,
                                             const BenchRayOptions& options) {
  PRISM_CHECK(options.width > 0 && options.height > 0);
  const auto pixels = static_cast<size_t>(options.width) * static_cast<size_t>(options.height);
  std::vector<BenchRaySet> sets;

  BenchRaySet primary{"P", false, std::vector<Ray>(pixels), std::vector<uint32_t>(pixels)};
  const BenchRng pixel_rng(options.seed, 1);
  for (size_t i = 0; i < pixels; ++i) {
    primary.pixels[i] = static_cast<uint32_t>(i);
    const float x = static_cast<float>(i % static_cast<size_t>(options.width));
    const float y = static_cast<float>(i / static_cast<size_t>(options.width));
    const Vec2 film((x + pixel_rng.get(i, 0)) / static_cast<float>(options.width),
                    (y + pixel_rng.get(i, 1)) / static_cast<float>(options.height));
    primary.rays[i] =
        scene.camera.generate_ray(film, Vec2(pixel_rng.get(i, 2), pixel_rng.get(i, 3)));
  }
  const std::vector<SurfacePoint> primary_hits =
      trace_points(scene, tracer, primary.rays, primary.pixels);

  const Bounds3 bounds = scene.geometry.bounds();
  BenchRaySet shadow{"S", true, std::vector<Ray>(primary_hits.size()),
                     std::vector<uint32_t>(primary_hits.size())};
  const BenchRng shadow_rng(options.seed, 2);
  for (size_t i = 0; i < primary_hits.size(); ++i) {
    const Light* light = scene.lights.empty() ? nullptr : &scene.lights[i % scene.lights.size()];
    shadow.rays[i] =
        shadow_ray(primary_hits[i], light, bounds, shadow_rng.get(i, 0), shadow_rng.get(i, 1));
    shadow.pixels[i] = primary_hits[i].pixel;
  }

  BenchRaySet d1 = bounce("D1", primary_hits, BenchRng(options.seed, 3));
  const std::vector<SurfacePoint> d1_hits = trace_points(scene, tracer, d1.rays, d1.pixels);
  BenchRaySet d2 = bounce("D2", d1_hits, BenchRng(options.seed, 4));

  BenchRaySet random{"R", false, std::vector<Ray>(pixels), {}};
  const BenchRng random_rng(options.seed, 5);
  const Vec3 extent = bounds.empty() ? Vec3(2.0f) : bounds.diagonal();
  const Vec3 lower = bounds.empty() ? Vec3(-1.0f) : bounds.lower;
  for (size_t i = 0; i < pixels; ++i) {
    const Vec3 o =
        lower + extent * Vec3(random_rng.get(i, 0), random_rng.get(i, 1), random_rng.get(i, 2));
    random.rays[i] =
        Ray{o, 0.0f, uniform_sphere(random_rng.get(i, 3), random_rng.get(i, 4)), kInfinity};
  }

  sets.push_back(std::move(primary));
  sets.push_back(std::move(shadow));
  sets.push_back(std::move(d1));
  sets.push_back(std::move(d2));
  sets.push_back(std::move(random));
  return sets;
}

void thin_ray_sets(std::vector<BenchRaySet>& sets, size_t stride) {
  if (stride <= 1) return;
  for (BenchRaySet& s : sets) {
    size_t kept = 0;
    for (size_t i = 0; i < s.rays.size(); i += stride, ++kept) {
      s.rays[kept] = s.rays[i];
      if (!s.pixels.empty()) s.pixels[kept] = s.pixels[i];
    }
    s.rays.resize(kept);
    if (!s.pixels.empty()) s.pixels.resize(kept);
  }
}

void save_ray_sets(const std::filesystem::path& path, const std::vector<BenchRaySet>& sets) {
  std::ofstream out(path, std::ios::binary);
  auto put = [&](const void* data, size_t bytes) {
    out.write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes));
  };
  put(kMagic, sizeof(kMagic));
  const auto count = static_cast<uint32_t>(sets.size());
  put(&count, sizeof(count));
  for (const BenchRaySet& s : sets) {
    const auto name_size = static_cast<uint32_t>(s.name.size());
    put(&name_size, sizeof(name_size));
    put(s.name.data(), s.name.size());
    const uint8_t occlusion = s.occlusion ? 1 : 0;
    put(&occlusion, 1);
    const uint64_t rays = s.rays.size();
    put(&rays, sizeof(rays));
    static_assert(sizeof(Ray) == 8 * sizeof(float));
    put(s.rays.data(), s.rays.size() * sizeof(Ray));
    const uint8_t has_pixels = s.pixels.size() == s.rays.size() && !s.rays.empty() ? 1 : 0;
    put(&has_pixels, 1);
    if (has_pixels) put(s.pixels.data(), s.pixels.size() * sizeof(uint32_t));
  }
  if (!out) throw Error(ErrorKind::kOutput, "cannot write ray sets", {path.string(), 0, {}});
}

std::vector<BenchRaySet> load_ray_sets(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  const ErrorLocation where{path.string(), 0, {}};
  if (!in) throw Error(ErrorKind::kInput, "cannot open ray sets", where);
  auto get = [&](void* data, size_t bytes) {
    in.read(static_cast<char*>(data), static_cast<std::streamsize>(bytes));
    if (!in) throw Error(ErrorKind::kInput, "truncated ray set file", where);
  };
  char magic[8];
  get(magic, sizeof(magic));
  if (std::memcmp(magic, kMagic, sizeof(kMagic)) != 0) {
    throw Error(ErrorKind::kInput, "not a prism ray set file", where);
  }
  uint32_t count = 0;
  get(&count, sizeof(count));
  if (count > 1024) throw Error(ErrorKind::kInput, "implausible ray set count", where);
  std::vector<BenchRaySet> sets(count);
  for (BenchRaySet& s : sets) {
    uint32_t name_size = 0;
    get(&name_size, sizeof(name_size));
    if (name_size > 256) throw Error(ErrorKind::kInput, "implausible ray set name", where);
    s.name.resize(name_size);
    get(s.name.data(), name_size);
    uint8_t occlusion = 0;
    get(&occlusion, 1);
    s.occlusion = occlusion != 0;
    uint64_t rays = 0;
    get(&rays, sizeof(rays));
    if (rays > (uint64_t{1} << 32)) throw Error(ErrorKind::kInput, "implausible ray count", where);
    s.rays.resize(rays);
    get(s.rays.data(), rays * sizeof(Ray));
    uint8_t has_pixels = 0;
    get(&has_pixels, 1);
    if (has_pixels) {
      s.pixels.resize(rays);
      get(s.pixels.data(), rays * sizeof(uint32_t));
    }
  }
  return sets;
}

}  // namespace prism
