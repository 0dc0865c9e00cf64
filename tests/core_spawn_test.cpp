// Geometric robustness: the spawn rule of core/scene.h (SurfaceInteraction::position_error,
// offset_ray_origin, spawn_ray, spawn_ray_to) keeps secondary rays off the surface they leave at
// every scale and distance from the world origin, with every backend; closed meshes do not leak;
// the bundled Cornell box renders the same scaled and moved. docs/RELIABILITY.md ("Geometric
// robustness") reports the counts these tests print.
//
// - The harness (SecondaryRaysNeverReHitTheirSurface): the bundled Cornell box (walls, a mirror
//   and a glass sphere) and a closed noisy sphere under a light, each scaled by 1e-6 ... 1e6,
//   moved 1e5, and scaled 1e3 + moved 1e7. Paths of camera rays; at each hit a reflection, a
//   refraction (Snell, ior 1.5, entering or leaving), two shadow rays to points of the emitter
//   and four directions 0.01 to 1 degree off the tangent plane (two on each side). A ray
//   re-hits its surface when its first hit is its own triangle (planar: never a genuine second
//   hit), or its own sphere closer than half the distance at which the ray, in double
//   precision from its actual origin, genuinely meets that sphere. Also counted: origins not
//   strictly on the intended side of their surface (in double), and shadow rays stopped by the
//   emitter they aim at. All must be zero. LongSecondaryRays... runs ten times the paths.
// - ClosedMeshesDoNotLeak: from points inside closed meshes (UV sphere, noisy sphere, a cube
//   and a rotated cube with shared vertices), rays aimed exactly at every vertex and at the
//   midpoint and a random point of every edge hit the mesh (intersect and occluded). Embree's
//   default (non-robust) mode is measured and printed, not held to zero.
// - TransformedCornellBoxRendersTheSame: the bundled JSON scene written scaled and moved, loaded
//   and rendered by the path integrator: the image mean equals the original's within the
//   statistical error.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "accel/accelerator.h"
#include "core/parallel.h"
#include "core/primitive_intersection.h"
#include "core/scene.h"
#include "scenes/mesh_generator.h"
#include "scenes/scene_loader.h"
#include "tests/support/integrators_test_scenes.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {

// ---------------------------------------------------------------------------------------------
// The rule itself.

Scene one_triangle_scene(Vec3 p0, Vec3 p1, Vec3 p2) {
  Scene scene;
  TriangleMesh mesh;
  mesh.positions = {p0, p1, p2};
  mesh.triangles = {{0, 1, 2}};
  scene.geometry.meshes.push_back(mesh);
  scene.geometry.finalize();
  return scene;
}

// The one-ulp steps of offset_ray_origin(): next_float_up()/down() (core/math.h) are
// std::nextafter toward +/- infinity bit for bit, on the special values and on random bits.
TEST(CoreSpawn, NextFloatStepsAreNextafterBitForBit) {
  const float kMax = std::numeric_limits<float>::max();
  const float kDenorm = std::numeric_limits<float>::denorm_min();
  std::vector<float> values = {0.0f,
                               -0.0f,
                               kDenorm,
                               -kDenorm,
                               1.0f,
                               -1.0f,
                               kMax,
                               -kMax,
                               std::numeric_limits<float>::min(),
                               -std::numeric_limits<float>::min(),
                               kInfinity,
                               -kInfinity,
                               std::numeric_limits<float>::quiet_NaN()};
  std::mt19937 rng(7);
  for (int i = 0; i < 200000; ++i) values.push_back(std::bit_cast<float>(uint32_t(rng())));
  int checked = 0;
  for (float x : values) {
    const float up = next_float_up(x), down = next_float_down(x);
    if (std::isnan(x)) {
      EXPECT_TRUE(std::isnan(up) && std::isnan(down));
      continue;
    }
    ASSERT_EQ(std::bit_cast<uint32_t>(up), std::bit_cast<uint32_t>(std::nextafter(x, kInfinity)))
        << x;
    ASSERT_EQ(std::bit_cast<uint32_t>(down), std::bit_cast<uint32_t>(std::nextafter(x, -kInfinity)))
        << x;
    ++checked;
  }
  EXPECT_GT(checked, 190000);
}

TEST(CoreSpawn, OffsetMovesAlongTheNormalToTheRequestedSide) {
  const Vec3 p(1.0f, 2.0f, 3.0f), n(0.0f, 0.0f, 1.0f), error(1e-6f);
  for (const Vec3 toward : {Vec3(0.3f, 0.0f, 1.0f), Vec3(0.0f, 0.0f, -1.0f), Vec3(1, 1, -0.01f)}) {
    const Vec3 moved = offset_ray_origin(p, error, n, toward);
    const Vec3 step = moved - p;
    // Along the normal only, to the side of `toward`, whichever way the normal faces, by at
    // least dot(|n|, error).
    EXPECT_EQ(step.x, 0.0f);
    EXPECT_EQ(step.y, 0.0f);
    EXPECT_GT(step.z * toward.z, 0.0f);
    EXPECT_GE(std::abs(step.z), 1e-6f);
    EXPECT_LT(std::abs(step.z), 2e-6f);
    EXPECT_EQ(offset_ray_origin(p, error, -n, toward), moved);
  }
  // With no error at all the point still leaves the surface: one float outward per axis the
  // normal has a component on.
  const Vec3 zero(0.0f);
  const Vec3 up = offset_ray_origin(zero, zero, Vec3(0, 1, 0), Vec3(0.5f, 1.0f, 0.0f));
  EXPECT_EQ(up.x, 0.0f);
  EXPECT_GT(up.y, 0.0f);
  EXPECT_EQ(up.z, 0.0f);
  const Vec3 tilted_n = glm::normalize(Vec3(1.0f, -2.0f, 0.5f));
  const Vec3 tilted = offset_ray_origin(p, zero, tilted_n, -tilted_n);
  EXPECT_LT(tilted.x, p.x);
  EXPECT_GT(tilted.y, p.y);
  EXPECT_LT(tilted.z, p.z);
}

TEST(CoreSpawn, OffsetScalesWithTheCoordinatesNotAFixedDistance) {
  // The same triangle, hit at the same barycentrics, scaled and moved: the spawned origin's
  // distance from the surface follows the coordinates' precision (no absolute epsilon).
  const auto offset_at = [](double scale, double shift) {
    const auto at = [&](Vec3 p) { return Vec3(DVec3(p) * scale + shift); };
    const Scene scene =
        one_triangle_scene(at({0.0f, 0.0f, 0.0f}), at({1.0f, 0.1f, 0.0f}), at({0.2f, 1.0f, 0.3f}));
    const SurfaceInteraction si = scene.surface_at(Ray{}, Hit{1.0f, 0.3f, 0.3f, 0, 0});
    const Ray r = spawn_ray(si, si.geometric_normal);
    return double(glm::dot(DVec3(r.origin) - DVec3(si.position), DVec3(si.geometric_normal)));
  };
  const double unit = offset_at(1.0, 0.0);
  EXPECT_GT(unit, 0.0);
  EXPECT_LT(unit, 1e-5);  // a few ulps of the triangle's size, not 1e-4
  for (const double scale : {1e-6, 1e-3, 1e3, 1e6}) {
    SCOPED_TRACE(scale);
    EXPECT_NEAR(offset_at(scale, 0.0) / (unit * scale), 1.0, 0.5);
  }
  // Moved 1e5 away, a unit triangle's offset is a few ulps of 1e5 (ulp 0.0078), not 10.
  const double far = offset_at(1.0, 1e5);
  EXPECT_GT(far, 0.004);
  EXPECT_LT(far, 0.1);
}

TEST(CoreSpawn, RebuiltPointsLieWithinTheirErrorBound) {
  // The bound covers the distance between the float point and the exact surface.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0), coord(-1.0, 1.0);
  for (const double shift : {0.0, 1e3, 1e5}) {
    for (int i = 0; i < 2000; ++i) {
      const auto rand_point = [&] {
        return Vec3(DVec3(coord(rng), coord(rng), coord(rng)) * 3.0 + shift);
      };
      Scene scene = one_triangle_scene(rand_point(), rand_point(), rand_point());
      scene.geometry.spheres.push_back(Sphere{rand_point(), float(0.1 + unit(rng)), 0});
      const std::vector<Vec3>& p = scene.geometry.meshes[0].positions;
      if (is_degenerate_triangle(p[0], p[1], p[2])) continue;
      const float u = float(unit(rng)), v = float(unit(rng) * (1.0 - u));
      const SurfaceInteraction si = scene.surface_at(Ray{}, Hit{1.0f, u, v, 0, 0});
      // Distance to the plane of the float vertices, in double.
      const DVec3 n =
          glm::normalize(glm::cross(DVec3(p[1]) - DVec3(p[0]), DVec3(p[2]) - DVec3(p[0])));
      const double distance = std::abs(glm::dot(DVec3(si.position) - DVec3(p[0]), n));
      EXPECT_LE(distance, glm::dot(glm::abs(n), DVec3(si.position_error)));
      const Sphere& s = scene.geometry.spheres[0];
      const SurfaceInteraction ss =
          scene.surface_at(Ray{}, Hit{1.0f, float(unit(rng)), float(unit(rng)), 1, 0});
      const double radial = std::abs(glm::length(DVec3(ss.position) - DVec3(s.center)) - s.radius);
      EXPECT_LE(radial, glm::dot(glm::abs(DVec3(ss.geometric_normal)), DVec3(ss.position_error)));
    }
  }
}

// The wide BVH pads a box by kBoxSizePaddingUlps of its largest primitive's size,
// kBoxCoordinatePaddingUlps of its largest |coordinate| and kBoxOriginPaddingUlps of the ray
// origin's (core/ray.h). A ray leaving an axis-aligned triangle (a Cornell wall, a furniture
// box's face) must start beyond its own flat box's padding, or the BVH tests the triangle's leaf
// again for a hit the offset already rules out (Scene::surface_at() widens the point's error
// bound to it). The move stays a few ulps of the coordinates plus a small fraction of the
// triangle's size.
TEST(CoreSpawn, RaysLeavingFlatTrianglesStartBeyondTheirBoxPadding) {
  Scene scene = one_triangle_scene({-1, -1, 0}, {1, -1, 0}, {-1, 1, 0});
  TriangleMesh small;
  small.positions = {{0.2f, 0.2f, 0.5f}, {0.201f, 0.2f, 0.5f}, {0.2f, 0.201f, 0.5f}};
  small.triangles = {{0, 1, 2}};
  scene.geometry.meshes.push_back(small);
  TriangleMesh off_centre;
  off_centre.positions = {{30.0f, 0.0f, 90.0f}, {31.0f, 0.0f, 90.0f}, {30.0f, 1.0f, 90.0f}};
  off_centre.triangles = {{0, 1, 2}};
  scene.geometry.meshes.push_back(off_centre);
  scene.geometry.finalize();
  constexpr float kU = 1.0f / (1 << 24);
  struct Case {
    uint32_t mesh;
    float plane, size, coordinate;
  };
  const Case cases[] = {{0, 0.0f, 2.0f, 1.0f}, {1, 0.5f, 0.001f, 0.501f}, {2, 90.0f, 1.0f, 90.0f}};
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int i = 0; i < 1000; ++i) {
    const float u = unit(rng), v = unit(rng) * (1.0f - u);
    const Vec3 away(unit(rng) - 0.5f, unit(rng) - 0.5f, 1.0f);
    for (const Case& c : cases) {
      const SurfaceInteraction si = scene.surface_at(Ray{}, Hit{1.0f, u, v, c.mesh, 0});
      const Ray up = spawn_ray(si, away);
      const float offset = up.origin.z - c.plane;
      const float padding =
          kU * (kBoxSizePaddingUlps * c.size + kBoxCoordinatePaddingUlps * c.coordinate +
                kBoxOriginPaddingUlps * max_component(glm::abs(up.origin)));
      // The box's upper plane, widened and rounded up, is at most one more ulp above this.
      EXPECT_GT(offset, padding + 2.0f * kU * c.plane)
          << "mesh " << c.mesh << " u " << u << " v " << v;
      EXPECT_LT(offset, 2.0f * padding) << "mesh " << c.mesh << " u " << u << " v " << v;
    }
  }
}

TEST(CoreSpawn, ShadowRaysEndShortOfTheirTargetByTheCoordinatesPrecision) {
  const Scene scene = one_triangle_scene({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  SurfaceInteraction si = scene.surface_at(Ray{}, Hit{1.0f, 0.25f, 0.25f, 0, 0});
  const Ray near = spawn_ray_to(si, si.position + Vec3(0.0f, 0.0f, 2.0f));
  EXPECT_FLOAT_EQ(near.tmax, 1.0f - kShadowEpsilon);
  EXPECT_GT(near.origin.z, 0.0f);
  // 1e7 away, a target 1000 units off is known to about an ulp (1): the ray stops well short.
  si.position = Vec3(1e7f, 1e7f, 1e7f);
  si.position_error = Vec3(4.0f);
  const Ray far = spawn_ray_to(si, si.position + Vec3(0.0f, 0.0f, 1000.0f));
  EXPECT_LT(far.tmax, 1.0f - 2.0f / 1000.0f);
  EXPECT_GT(far.tmax, 0.9f);
}

TEST(CoreSpawn, BuiltRaysCarryTheirPartsAndSpawnedRaysTheirDirection) {
  // build_ray() writes the two vectors {origin, tmin} and {direction, tmax}: every field lands
  // where Ray has it.
  const Ray built = build_ray({1.0f, -2.0f, 3.5f}, {0.0f, 0.6f, -0.8f}, 0.25f, 7.0f);
  EXPECT_EQ(built.origin, Vec3(1.0f, -2.0f, 3.5f));
  EXPECT_EQ(built.direction, Vec3(0.0f, 0.6f, -0.8f));
  EXPECT_EQ(built.tmin, 0.25f);
  EXPECT_EQ(built.tmax, 7.0f);
  const Scene scene = one_triangle_scene({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  const SurfaceInteraction si = scene.surface_at(Ray{}, Hit{1.0f, 0.25f, 0.25f, 0, 0});
  const Vec3 up = glm::normalize(Vec3(0.1f, 0.2f, 1.0f));
  const Ray leaving = spawn_ray(si, up);
  EXPECT_EQ(leaving.direction, up);
  EXPECT_EQ(leaving.tmin, 0.0f);
  EXPECT_EQ(leaving.tmax, kInfinity);
  EXPECT_EQ(leaving.origin,
            offset_ray_origin(si.position, si.position_error, si.geometric_normal, up));
  const Vec3 target = si.position + Vec3(0.0f, 0.0f, 2.0f);
  const Ray shadow = spawn_ray_to(si, target);
  EXPECT_EQ(shadow.tmin, 0.0f);
  EXPECT_EQ(shadow.direction, target - shadow.origin);
}

// ---------------------------------------------------------------------------------------------
// Scenes, transforms and backends of the harness.

/// p -> p * scale + shift (every coordinate moved by shift), in double, rounded once.
struct Transform {
  double scale;
  double shift;
  const char* label;
  Vec3 point(const Vec3& p) const { return Vec3(DVec3(p) * scale + shift); }
};

constexpr Transform kTransforms[] = {
    {1e-6, 0.0, "x1e-6"}, {1e-3, 0.0, "x1e-3"}, {1.0, 0.0, "x1"},       {1e3, 0.0, "x1e3"},
    {1e6, 0.0, "x1e6"},   {1.0, 1e5, "+1e5"},   {1e3, 1e7, "x1e3+1e7"},
};

Scene transformed(Scene scene, const Transform& t) {
  for (TriangleMesh& mesh : scene.geometry.meshes) {
    for (Vec3& p : mesh.positions) p = t.point(p);
  }
  for (Sphere& s : scene.geometry.spheres) {
    s.center = t.point(s.center);
    s.radius = float(double(s.radius) * t.scale);
  }
  scene.camera.position = t.point(scene.camera.position);
  scene.camera.target = t.point(scene.camera.target);
  scene.camera.focal_distance = float(double(scene.camera.focal_distance) * t.scale);
  scene.camera.znear = float(double(scene.camera.znear) * t.scale);
  scene.geometry.finalize();
  scene.validate();
  return scene;
}

/// The bundled Cornell box with a mirror and a glass sphere.
Scene cornell_spheres() { return load_scene(bundled_scene_dir() / "cornell_spheres.json"); }

/// A closed noisy sphere (radius about 1) under a square emitter, seen from +z.
Scene noisy_sphere_under_a_light(size_t triangles) {
  Scene scene;
  scene.source = "noisy sphere (core_spawn_test)";
  test::add_material(scene, MaterialType::kGlass, Rgb(1.0f), "glass");
  const uint32_t lamp = test::add_material(scene, MaterialType::kEmission, Rgb(10.0f), "light");
  scene.geometry.meshes.push_back(generate_mesh(GeneratedMeshKind::kNoisySphere, triangles, 3, 0));
  scene.geometry.meshes.push_back(
      test::quad("light", {-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}, lamp));
  scene.camera.position = Vec3(0.3f, 0.5f, 4.0f);
  scene.camera.target = Vec3(0.0f);
  scene.camera.hfov_deg = scene.camera.vfov_deg = 30.0f;
  scene.camera.znear = 0.0f;
  scene.geometry.finalize();
  scene.validate();
  return scene;
}

std::unique_ptr<Accelerator> make_backend(const std::string& name, const SceneGeometry& g) {
  ParamSet params;
  std::string backend = name;
  if (name == "embree_robust") {
    backend = "embree";
    params.set("embree.robust", "true");
  }
  std::unique_ptr<Accelerator> accel = accelerator_registry().create(backend, params);
  accel->build(g);
  return accel;
}

// ---------------------------------------------------------------------------------------------
// The self-intersection harness.

struct SpawnCounts {
  size_t primary_hits = 0;
  size_t reflection = 0, refraction = 0, shadow = 0, grazing = 0;
  size_t self_hits = 0;       ///< first hit on the surface left, not a genuine second hit
  size_t self_blocks = 0;     ///< shadow rays blocked by the surface they leave
  size_t wrong_side = 0;      ///< origins not strictly on the intended side (double)
  size_t emitter_blocks = 0;  ///< shadow rays blocked by the emitter they aim at
  size_t tunnels = 0;         ///< origins moved through other geometry
  double max_offset = 0.0;    ///< largest |origin - hit point| over the scene's diagonal
  std::string first_failure;

  size_t secondary() const { return reflection + refraction + shadow + grazing; }
  void add(const SpawnCounts& o) {
    primary_hits += o.primary_hits;
    reflection += o.reflection;
    refraction += o.refraction;
    shadow += o.shadow;
    grazing += o.grazing;
    self_hits += o.self_hits;
    self_blocks += o.self_blocks;
    wrong_side += o.wrong_side;
    emitter_blocks += o.emitter_blocks;
    tunnels += o.tunnels;
    max_offset = std::max(max_offset, o.max_offset);
    if (first_failure.empty()) first_failure = o.first_failure;
  }
};

/// Whether `ray`, spawned at `si`, starts strictly on `direction`'s side of si's surface, in
/// double precision.
bool on_intended_side(const Scene& scene, const SurfaceInteraction& si, const Ray& ray,
                      const Vec3& direction) {
  const SceneGeometry& g = scene.geometry;
  if (g.is_sphere(si.geom_id)) {
    // Outside when the ray leaves to the outward normal's side, inside otherwise.
    const Sphere& s = g.spheres[si.prim_id];
    const DVec3 f = DVec3(ray.origin) - DVec3(s.center);
    const double excess = glm::dot(f, f) - double(s.radius) * s.radius;
    return glm::dot(direction, si.geometric_normal) > 0.0f ? excess > 0.0 : excess < 0.0;
  }
  const TriangleMesh& mesh = g.meshes[si.geom_id];
  const glm::uvec3 tri = mesh.triangles[si.prim_id];
  const DVec3 p0(mesh.positions[tri.x]);
  const DVec3 n = glm::cross(DVec3(mesh.positions[tri.y]) - p0, DVec3(mesh.positions[tri.z]) - p0);
  const double side = glm::dot(n, DVec3(direction));
  const double height = glm::dot(n, DVec3(ray.origin) - p0);
  return side > 0.0 ? height > 0.0 : height < 0.0;
}

/// Whether `hit`, the first hit of `ray` spawned at `si`, is si's own surface again where no
/// genuine second intersection is.
bool is_self_hit(const Scene& scene, const SurfaceInteraction& si, const Ray& ray,
                 const std::optional<Hit>& hit) {
  if (!hit || hit->geom_id != si.geom_id || hit->prim_id != si.prim_id) return false;
  if (!scene.geometry.is_sphere(si.geom_id)) return true;  // planar: never hit twice
  // A sphere is met again only by a ray entering it, at the far end of the chord
  // 2 r cos(angle to the inward normal); self-hits come at t ~ 0.
  const float length = glm::length(ray.direction);
  const float chord = 2.0f * scene.geometry.spheres[si.prim_id].radius *
                      std::max(0.0f, -glm::dot(ray.direction / length, si.geometric_normal));
  return hit->t * length < 0.5f * chord;
}

/// Points of the scene's emitters: uniform on a random emissive triangle, in float as the
/// lights compute them.
struct EmitterSampler {
  std::vector<std::pair<uint32_t, uint32_t>> triangles;  // (geom_id, prim_id)

  explicit EmitterSampler(const Scene& scene) {
    for (size_t i = 0; i < scene.geometry.meshes.size(); ++i) {
      const TriangleMesh& m = scene.geometry.meshes[i];
      if (!scene.materials[m.material_id].is_emissive()) continue;
      for (size_t t = 0; t < m.triangles.size(); ++t)
        triangles.emplace_back(uint32_t(i), uint32_t(t));
    }
  }
  bool is_emitter(const Scene& scene, uint32_t geom_id) const {
    return !scene.geometry.is_sphere(geom_id) &&
           scene.materials[scene.geometry.meshes[geom_id].material_id].is_emissive();
  }
  /// A point, its emitter's mesh and the emitter's front normal (the triangle's winding).
  Vec3 sample(const Scene& scene, std::mt19937& rng, uint32_t* geom_id, Vec3* normal) const {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const auto [g, t] =
        triangles[std::uniform_int_distribution<size_t>(0, triangles.size() - 1)(rng)];
    *geom_id = g;
    const TriangleMesh& m = scene.geometry.meshes[g];
    const glm::uvec3 tri = m.triangles[t];
    *normal = glm::normalize(glm::cross(m.positions[tri.y] - m.positions[tri.x],
                                        m.positions[tri.z] - m.positions[tri.x]));
    float b0 = unit(rng), b1 = unit(rng);
    if (b0 + b1 > 1.0f) {
      b0 = 1.0f - b0;
      b1 = 1.0f - b1;
    }
    return (1.0f - b0 - b1) * m.positions[tri.x] + b0 * m.positions[tri.y] +
           b1 * m.positions[tri.z];
  }
};

/// Snell refraction of the unit `wi` (toward the surface) about the unit `n` facing it, with
/// eta = eta_incident / eta_transmitted; nothing on total internal reflection.
std::optional<Vec3> refract(const Vec3& wi, const Vec3& n, float eta) {
  const float cos_i = -glm::dot(wi, n);
  const float sin2_t = eta * eta * std::max(0.0f, 1.0f - cos_i * cos_i);
  if (sin2_t >= 1.0f) return std::nullopt;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  return glm::normalize(eta * wi + (eta * cos_i - cos_t) * n);
}

/// `paths` camera paths (up to 4 hits each) through `scene` with `accel`, spawning and checking
/// the secondary rays at each hit.
SpawnCounts run_spawn_harness(const Scene& scene, const Accelerator& accel, size_t paths,
                              uint64_t seed) {
  const EmitterSampler emitters(scene);
  const double diagonal = glm::length(scene.geometry.bounds().diagonal());
  std::mutex mutex;
  SpawnCounts total;
  parallel_for_range(paths, [&](size_t begin, size_t end) {
    SpawnCounts c;
    const auto check = [&](const SurfaceInteraction& si, const Ray& ray, const Vec3& direction,
                           const char* what) {
      const std::optional<Hit> hit = accel.intersect(ray);
      const bool wrong_side = !on_intended_side(scene, si, ray, direction);
      // The way back from the origin to the hit point crosses nothing in its first half.
      const std::optional<Hit> way_back =
          accel.intersect(Ray{ray.origin, 0.0f, si.position - ray.origin, 0.5f});
      const bool tunnel =
          way_back && (way_back->geom_id != si.geom_id || way_back->prim_id != si.prim_id);
      c.tunnels += tunnel;
      c.max_offset =
          std::max(c.max_offset, glm::length(DVec3(ray.origin) - DVec3(si.position)) / diagonal);
      const bool self = is_self_hit(scene, si, ray, hit);
      c.wrong_side += wrong_side;
      c.self_hits += self;
      if ((wrong_side || self) && c.first_failure.empty()) {
        char text[512];
        std::snprintf(text, sizeof text,
                      "%s ray from geom %u prim %u: origin (%a, %a, %a) direction (%a, %a, %a)%s%s",
                      what, si.geom_id, si.prim_id, ray.origin.x, ray.origin.y, ray.origin.z,
                      ray.direction.x, ray.direction.y, ray.direction.z,
                      wrong_side ? " starts on the wrong side" : "",
                      self ? " re-hits its surface" : "");
        c.first_failure = text;
      }
      return hit;
    };
    for (size_t path = begin; path < end; ++path) {
      std::mt19937 rng(uint32_t(seed * 1000003u + path));
      std::uniform_real_distribution<float> unit(0.0f, 1.0f);
      Ray ray = scene.camera.generate_ray(Vec2(unit(rng), unit(rng)));
      for (int depth = 0; depth < 4; ++depth) {
        const std::optional<Hit> hit = accel.intersect(ray);
        if (!hit) break;
        if (depth == 0) ++c.primary_hits;
        const SurfaceInteraction si = scene.surface_at(ray, *hit);
        const Vec3 wi = glm::normalize(ray.direction);
        const Vec3 ng = si.geometric_normal;
        const Vec3 front = glm::dot(wi, ng) < 0.0f ? ng : -ng;  // faces the incoming ray
        // Reflection and refraction; glass of ior 1.5 entering where the ray meets the normal's
        // side, leaving where it meets the other.
        const Vec3 reflected = glm::normalize(wi - 2.0f * glm::dot(wi, front) * front);
        check(si, spawn_ray(si, reflected), reflected, "reflection");
        ++c.reflection;
        const std::optional<Vec3> refracted =
            refract(wi, front, glm::dot(wi, ng) < 0.0f ? 1.0f / 1.5f : 1.5f);
        if (refracted) {
          check(si, spawn_ray(si, *refracted), *refracted, "refraction");
          ++c.refraction;
        }
        // Shadow rays to emitter points, built as ShadingPoint::unoccluded builds them.
        if (!emitters.is_emitter(scene, si.geom_id) && !emitters.triangles.empty()) {
          for (int i = 0; i < 2; ++i) {
            uint32_t emitter = 0;
            Vec3 emitter_normal;
            const Vec3 q = emitters.sample(scene, rng, &emitter, &emitter_normal);
            const float distance = glm::length(q - si.position);
            if (!(distance > 0.0f)) continue;
            const Vec3 w = (q - si.position) / distance;
            // As the lights sample: one-sided emitters, seen from the front only.
            if (glm::dot(w, ng) == 0.0f || !(glm::dot(w, emitter_normal) < 0.0f)) continue;
            const Ray shadow = spawn_ray_to(si, si.position + distance * w);
            const std::optional<Hit> blocker = check(si, shadow, w, "shadow");
            c.self_blocks += is_self_hit(scene, si, shadow, blocker);
            c.emitter_blocks += blocker && blocker->geom_id == emitter;
            ++c.shadow;
          }
        }
        // Grazing: 0.01 to 1 degree off the tangent plane, log-uniform, two on each side.
        const Vec3 helper = std::abs(ng.x) > 0.5f ? Vec3(0, 1, 0) : Vec3(1, 0, 0);
        const Vec3 t1 = glm::normalize(glm::cross(helper, ng)), t2 = glm::cross(ng, t1);
        for (int i = 0; i < 4; ++i) {
          const float phi = 2.0f * kPi * unit(rng);
          const float degrees = std::pow(10.0f, -2.0f + 2.0f * unit(rng));
          const float alpha = radians(degrees) * (i < 2 ? 1.0f : -1.0f);
          const Vec3 tangent = std::cos(phi) * t1 + std::sin(phi) * t2;
          const Vec3 graze = glm::normalize(std::cos(alpha) * tangent + std::sin(alpha) * ng);
          check(si, spawn_ray(si, graze), graze, "grazing");
          ++c.grazing;
        }
        // Continue, mostly through refraction so that paths also leave surfaces from inside.
        const Vec3 next = refracted && unit(rng) < 0.7f ? *refracted : reflected;
        ray = spawn_ray(si, next);
      }
    }
    const std::lock_guard<std::mutex> lock(mutex);
    total.add(c);
  });
  return total;
}

class CoreSpawn : public testing::TestWithParam<std::string> {};

void run_spawn_suite(const std::string& backend, size_t cornell_paths, size_t noisy_paths) {
  struct Case {
    const char* name;
    Scene scene;
    size_t paths;
  };
  std::vector<Case> cases;
  cases.push_back({"cornell", cornell_spheres(), cornell_paths});
  cases.push_back({"noisy", noisy_sphere_under_a_light(2000), noisy_paths});
  SpawnCounts all;
  for (const Case& base : cases) {
    for (const Transform& t : kTransforms) {
      SCOPED_TRACE(std::string(base.name) + " " + t.label);
      const Scene scene = transformed(base.scene, t);
      const std::unique_ptr<Accelerator> accel = make_backend(backend, scene.geometry);
      const SpawnCounts c = run_spawn_harness(scene, *accel, base.paths, 17);
      std::printf(
          "%-7s %-9s %-6s primary hits %6zu  secondary %7zu (reflection %6zu refraction %6zu "
          "shadow %6zu grazing %6zu)  self-hits %zu  self-blocked shadow rays %zu  wrong-side "
          "origins %zu  emitter-blocked %zu  tunnels %zu  largest offset %.2g of the diagonal\n",
          base.name, t.label, backend.c_str(), c.primary_hits, c.secondary(), c.reflection,
          c.refraction, c.shadow, c.grazing, c.self_hits, c.self_blocks, c.wrong_side,
          c.emitter_blocks, c.tunnels, c.max_offset);
      EXPECT_GT(c.primary_hits, base.paths / 2);
      EXPECT_EQ(c.self_hits, 0u) << c.first_failure;
      EXPECT_EQ(c.self_blocks, 0u) << c.first_failure;
      EXPECT_EQ(c.wrong_side, 0u) << c.first_failure;
      // The far end: a light point rebuilt in float lies up to an ulp behind its emitter, which
      // stops rays that meet the emitter at a grazing angle (cos below ~1e-3 here); without the
      // end's rounding margin of spawn_ray_to() it was 13% of them at +1e5.
      EXPECT_LE(c.emitter_blocks, c.shadow / 200);
      if (t.shift == 0.0) {
        // Nothing is closer to a surface than a few ulps, so no origin moves through anything.
        EXPECT_EQ(c.tunnels, 0u);
        EXPECT_LT(c.max_offset, 1e-5);
      } else {
        // Moved away, surfaces 0.01 apart (the light under the ceiling, the sphere on the floor)
        // are an ulp apart: origins an ulp off one may pass the other (counted, not failed).
        EXPECT_LT(c.max_offset, 1e-2);
      }
      all.add(c);
    }
  }
  std::printf("%s: %zu secondary rays, %zu self-hits, %zu self-blocked shadow rays\n",
              backend.c_str(), all.secondary(), all.self_hits, all.self_blocks);
  testing::Test::RecordProperty("secondary_rays", std::to_string(all.secondary()));
}

// Brute force tests every triangle of the 2000-triangle noisy sphere per ray: fewer paths there
// keep it short (also under the sanitizers). About 1.2 million secondary rays over the backends.
TEST_P(CoreSpawn, SecondaryRaysNeverReHitTheirSurface) {
  run_spawn_suite(GetParam(), 2250, GetParam() == "brute" ? 300 : 2250);
}

// Ten times the paths. Run with PRISM_LONG_TESTS=1 (ctest -L long).
TEST_P(CoreSpawn, LongSecondaryRaysNeverReHitTheirSurface) {
  const char* env = std::getenv("PRISM_LONG_TESTS");
  if (env == nullptr || std::string(env) != "1") {
    GTEST_SKIP() << "long run: set PRISM_LONG_TESTS=1";
  }
  run_spawn_suite(GetParam(), 22500, 22500);
}

// ---------------------------------------------------------------------------------------------
// Closed meshes do not leak.

/// A cube [-1, 1]^3 of 6 n x n grids sharing their vertices along the cube's edges, wound
/// outward; rotated by `rotation` (radians about a fixed skew axis) when non-zero.
TriangleMesh subdivided_cube(int n, double rotation) {
  TriangleMesh mesh;
  mesh.name = "cube";
  std::map<std::tuple<int, int, int>, uint32_t> index;
  const glm::dmat4 turn =
      glm::rotate(glm::dmat4(1.0), rotation, glm::normalize(glm::dvec3(1.0, 2.0, 3.0)));
  const auto vertex = [&](glm::ivec3 lattice) {
    const auto key = std::make_tuple(lattice.x, lattice.y, lattice.z);
    const auto found = index.find(key);
    if (found != index.end()) return found->second;
    const glm::dvec3 p = glm::dvec3(lattice) * (2.0 / n) - 1.0;
    mesh.positions.push_back(Vec3(glm::dvec3(turn * glm::dvec4(p, 1.0))));
    index.emplace(key, uint32_t(mesh.positions.size() - 1));
    return uint32_t(mesh.positions.size() - 1);
  };
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side <= n; side += n) {
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          const auto at = [&](int di, int dj) {
            glm::ivec3 l(0);
            l[axis] = side;
            l[a] = i + di;
            l[b] = j + dj;
            return vertex(l);
          };
          const uint32_t v00 = at(0, 0), v10 = at(1, 0), v11 = at(1, 1), v01 = at(0, 1);
          if (side == n) {  // outward: +axis
            mesh.triangles.push_back({v00, v10, v11});
            mesh.triangles.push_back({v00, v11, v01});
          } else {
            mesh.triangles.push_back({v00, v11, v10});
            mesh.triangles.push_back({v00, v01, v11});
          }
        }
      }
    }
  }
  return mesh;
}

struct LeakCounts {
  size_t rays = 0;
  size_t at_vertices = 0;       ///< intersect() found nothing for a ray aimed at a vertex
  size_t at_edges = 0;          ///< ... at a point of an edge
  size_t escaped_occluded = 0;  ///< occluded() found nothing (either kind)

  size_t escaped() const { return at_vertices + at_edges; }
  void add(const LeakCounts& o) {
    rays += o.rays;
    at_vertices += o.at_vertices;
    at_edges += o.at_edges;
    escaped_occluded += o.escaped_occluded;
  }
};

/// Rays from `origins` points inside the closed `mesh` (its bounds' centre, then random points
/// within `inner_radius` of it) aimed exactly at every vertex and at the midpoint and a random
/// point of every edge.
LeakCounts aim_at_vertices_and_edges(const TriangleMesh& mesh, const Accelerator& accel,
                                     float inner_radius, int origins, uint64_t seed) {
  std::mt19937 rng{uint32_t(seed)};
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), sym(-1.0f, 1.0f);
  std::vector<Vec3> targets = mesh.positions;
  const size_t vertices = targets.size();
  std::map<std::pair<uint32_t, uint32_t>, bool> edges;
  for (const glm::uvec3& t : mesh.triangles) {
    for (int e = 0; e < 3; ++e) {
      const uint32_t i = t[e], j = t[(e + 1) % 3];
      edges[{std::min(i, j), std::max(i, j)}] = true;
    }
  }
  for (const auto& [edge, unused] : edges) {
    const Vec3 a = mesh.positions[edge.first], b = mesh.positions[edge.second];
    targets.push_back(0.5f * (a + b));
    targets.push_back(a + unit(rng) * (b - a));
  }
  LeakCounts total;
  std::mutex mutex;
  const Vec3 centre = mesh.bounds().center();
  for (int k = 0; k < origins; ++k) {
    // Inside the ball of radius inner_radius (a cube's corner at most sqrt(3) / 1.8 of it out).
    const Vec3 origin =
        k == 0 ? centre : centre + inner_radius * Vec3(sym(rng), sym(rng), sym(rng)) / 1.8f;
    parallel_for_range(targets.size(), [&](size_t begin, size_t end) {
      LeakCounts c;
      for (size_t i = begin; i < end; ++i) {
        const Ray ray{origin, 0.0f, targets[i] - origin, kInfinity};
        const bool escaped = !accel.intersect(ray).has_value();
        (i < vertices ? c.at_vertices : c.at_edges) += escaped;
        c.escaped_occluded += !accel.occluded(ray);
        ++c.rays;
      }
      const std::lock_guard<std::mutex> lock(mutex);
      total.add(c);
    });
  }
  return total;
}

void run_leak_suite(const std::string& backend, int origins) {
  struct Solid {
    const char* name;
    TriangleMesh mesh;
    float inner_radius;  ///< inside the solid around its centre, before the transform
  };
  const std::vector<Solid> solids = {
      {"sphere", generate_mesh(GeneratedMeshKind::kSphere, 800), 0.5f},
      {"noisy", generate_mesh(GeneratedMeshKind::kNoisySphere, 800, 2), 0.4f},
      {"cube", subdivided_cube(6, 0.0), 0.8f},
      {"tilted", subdivided_cube(6, 0.7), 0.8f},
  };
  LeakCounts total;
  for (const Solid& solid : solids) {
    for (const Transform& t : kTransforms) {
      if (t.scale == 1e-3) continue;  // between 1e-6 and 1: nothing new
      SCOPED_TRACE(std::string(solid.name) + " " + t.label);
      SceneGeometry geometry;
      geometry.meshes.push_back(solid.mesh);
      for (Vec3& p : geometry.meshes[0].positions) p = t.point(p);
      geometry.finalize();
      const std::unique_ptr<Accelerator> accel = make_backend(backend, geometry);
      const LeakCounts c = aim_at_vertices_and_edges(
          geometry.meshes[0], *accel, float(solid.inner_radius * t.scale), origins, 29);
      std::printf(
          "%-6s %-9s %-13s rays %7zu  escaped at vertices %zu, at edges %zu, occluded() %zu\n",
          solid.name, t.label, backend.c_str(), c.rays, c.at_vertices, c.at_edges,
          c.escaped_occluded);
      total.add(c);
      if (backend == "brute" || backend == "bvh") {
        EXPECT_EQ(c.escaped(), 0u);
        EXPECT_EQ(c.escaped_occluded, 0u);
      }
    }
  }
  std::printf(
      "%s: %zu rays at shared vertices and edges, escaped at vertices %zu, at edges %zu, "
      "occluded() %zu\n",
      backend.c_str(), total.rays, total.at_vertices, total.at_edges, total.escaped_occluded);
  if (backend == "embree_robust") {
    // Robust Embree is watertight across edges, and nearly at vertices: a few rays aimed exactly
    // at a vertex of the UV sphere slip through (2 of 160k here).
    EXPECT_EQ(total.at_edges, 0u);
    EXPECT_LE(total.at_vertices, total.rays / 20000);
  }
  // Embree's default, non-robust mode leaks a few percent of these rays: printed, not failed
  // (docs/RELIABILITY.md).
}

TEST_P(CoreSpawn, ClosedMeshesDoNotLeak) {
  run_leak_suite(GetParam(), GetParam() == "brute" ? 1 : 3);
}

// Ten times the origins. Run with PRISM_LONG_TESTS=1 (ctest -L long).
TEST_P(CoreSpawn, LongClosedMeshesDoNotLeak) {
  const char* env = std::getenv("PRISM_LONG_TESTS");
  if (env == nullptr || std::string(env) != "1") {
    GTEST_SKIP() << "long run: set PRISM_LONG_TESTS=1";
  }
  run_leak_suite(GetParam(), 30);
}

// ---------------------------------------------------------------------------------------------
// The bundled Cornell box renders the same scaled and moved (issue 11: moved 1e5 it lost its
// red and blue walls and its spheres went black; scaled 1e-6 it was black).

/// The bundled JSON scene `name` with every coordinate mapped by `t` (positions, sphere
/// centres and radii, the camera's position and target), as a JSON document.
nlohmann::json transformed_json(const std::string& name, const Transform& t) {
  std::ifstream in(bundled_scene_dir() / name);
  nlohmann::json doc = nlohmann::json::parse(in);
  const auto map = [&](nlohmann::json& p) {
    const Vec3 q = t.point(Vec3(p[0].get<float>(), p[1].get<float>(), p[2].get<float>()));
    p = nlohmann::json::array({q.x, q.y, q.z});
  };
  for (nlohmann::json& mesh : doc["meshes"]) {
    for (nlohmann::json& p : mesh["positions"]) map(p);
  }
  for (nlohmann::json& sphere : doc["spheres"]) {
    map(sphere["center"]);
    sphere["radius"] = float(sphere["radius"].get<double>() * t.scale);
  }
  map(doc["camera"]["position"]);
  map(doc["camera"]["target"]);
  return doc;
}

TEST_P(CoreSpawn, TransformedCornellBoxRendersTheSame) {
  const std::filesystem::path dir = test::make_temp_dir("core_spawn");
  test::TestRender r;
  r.width = 40;
  r.height = 30;
  r.spp = 64;
  r.accelerator = GetParam() == "embree_robust" ? "embree" : GetParam();
  ParamSet params;
  if (GetParam() == "embree_robust") params.set("embree.robust", "true");
  // The same seed as the reference: a transform that changes nothing renders the same image,
  // and expect_same_mean()'s error bar (of two independent renders) is then conservative.
  const Scene original = cornell_spheres();
  const Image reference = test::render_scene(original, "path", params, r);
  for (const Transform& t : kTransforms) {
    if (t.scale == 1.0 && t.shift == 0.0) continue;
    SCOPED_TRACE(t.label);
    const std::filesystem::path file = dir / (std::string("cornell_") + t.label + ".json");
    std::ofstream(file) << transformed_json("cornell_spheres.json", t).dump();
    const Scene scene = load_scene(file);
    const Image image = test::render_scene(scene, "path", params, r);
    std::printf("%-13s %-9s mean R %.4f G %.4f B %.4f (original %.4f %.4f %.4f)\n",
                GetParam().c_str(), t.label, test::image_mean(image, 0).mean,
                test::image_mean(image, 1).mean, test::image_mean(image, 2).mean,
                test::image_mean(reference, 0).mean, test::image_mean(reference, 1).mean,
                test::image_mean(reference, 2).mean);
    test::expect_same_mean(reference, image, 4.0, t.label);
  }
  std::filesystem::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Backends, CoreSpawn,
                         testing::Values("brute", "bvh", "embree", "embree_robust"),
                         [](const testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });

}  // namespace
}  // namespace prism
