// The batched queries behind the Python module's Accelerator.intersect() and occluded()
// (core/app/ray_batch.h): on every backend, the same bits as Accelerator::intersect() and
// occluded() called ray by ray, with shared or per-ray bounds and any thread count.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "accel/accelerator.h"
#include "core/app/ray_batch.h"
#include "core/parallel.h"
#include "scenes/mesh_generator.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

/// Rays as the Python module hands them over: flat arrays, bounds per ray.
struct Rays {
  std::vector<float> origins, directions, tmin, tmax;
  size_t size() const { return tmin.size(); }
};

/// Random rays through the unit box, with a few that cannot hit (a zero direction, a NaN, an
/// inverted interval) and bounds that cut some hits off.
Rays random_rays(size_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> box(-1.5f, 1.5f), unit(-1.0f, 1.0f), near(-0.5f, 1.0f);
  Rays r;
  for (size_t i = 0; i < count; ++i) {
    const float o[3] = {box(rng), box(rng), box(rng)};
    const float d[3] = {unit(rng), unit(rng), unit(rng)};
    r.origins.insert(r.origins.end(), o, o + 3);
    r.directions.insert(r.directions.end(), d, d + 3);
    r.tmin.push_back(near(rng));
    r.tmax.push_back(i % 5 == 0 ? 1.5f : kInf);
  }
  r.directions[0] = r.directions[1] = r.directions[2] = 0.0f;
  r.origins[3] = std::numeric_limits<float>::quiet_NaN();
  r.tmin[2] = 2.0f;
  r.tmax[2] = 1.0f;
  return r;
}

class AppRayBatch : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    geometry_.meshes.push_back(generate_mesh(GeneratedMeshKind::kNoisySphere, 2000));
    geometry_.meshes.push_back(generate_mesh(GeneratedMeshKind::kSoup, 500, 7));
    geometry_.spheres.push_back(Sphere{.center = Vec3(0.2f, 0.1f, 0.0f), .radius = 0.5f});
    geometry_.finalize();
    accel_ = accelerator_registry().create(GetParam(), {});
    accel_->build(geometry_);
  }

  /// The batch of `rays`, with every bound per ray or the first one for all.
  static RayBatch batch_of(const Rays& rays, bool shared_bounds) {
    const size_t bounds = shared_bounds ? 1 : rays.size();
    return RayBatch{.origins = rays.origins,
                    .directions = rays.directions,
                    .tmin = {rays.tmin.data(), bounds},
                    .tmax = {rays.tmax.data(), bounds},
                    .size = rays.size()};
  }

  /// intersect_batch() and occluded_batch() against the per-ray calls, bit for bit.
  void expect_same_as_single_rays(const RayBatch& batch) {
    const size_t n = batch.size;
    std::vector<float> t(n), u(n), v(n);
    std::vector<int64_t> geom_id(n), prim_id(n);
    auto hit = std::make_unique<bool[]>(n);
    auto occluded = std::make_unique<bool[]>(n);
    intersect_batch(*accel_, batch, HitArrays{t, u, v, geom_id, prim_id, {hit.get(), n}});
    occluded_batch(*accel_, batch, {occluded.get(), n});
    size_t hits = 0;
    for (size_t i = 0; i < n; ++i) {
      const std::optional<Hit> expected = accel_->intersect(batch.ray(i));
      ASSERT_EQ(hit[i], expected.has_value()) << "ray " << i;
      EXPECT_EQ(occluded[i], accel_->occluded(batch.ray(i))) << "ray " << i;
      EXPECT_EQ(occluded[i], hit[i]) << "ray " << i;
      if (!expected) {
        EXPECT_EQ(t[i], kInf);
        EXPECT_EQ(u[i], 0.0f);
        EXPECT_EQ(v[i], 0.0f);
        EXPECT_EQ(geom_id[i], -1);
        EXPECT_EQ(prim_id[i], -1);
        continue;
      }
      ++hits;
      // Bit for bit: memcmp also tells -0 from +0.
      EXPECT_EQ(std::memcmp(&t[i], &expected->t, sizeof(float)), 0) << "ray " << i;
      EXPECT_EQ(std::memcmp(&u[i], &expected->u, sizeof(float)), 0) << "ray " << i;
      EXPECT_EQ(std::memcmp(&v[i], &expected->v, sizeof(float)), 0) << "ray " << i;
      EXPECT_EQ(geom_id[i], int64_t(expected->geom_id)) << "ray " << i;
      EXPECT_EQ(prim_id[i], int64_t(expected->prim_id)) << "ray " << i;
    }
    // The rays must exercise hits and misses both.
    EXPECT_GT(hits, n / 10);
    EXPECT_LT(hits, n);
  }

  SceneGeometry geometry_;
  std::unique_ptr<Accelerator> accel_;
};

TEST_P(AppRayBatch, PerRayBoundsGiveTheSingleRayResults) {
  const Rays rays = random_rays(test::sanitizer_share(20000), 1);
  expect_same_as_single_rays(batch_of(rays, false));
}

TEST_P(AppRayBatch, SharedBoundsGiveTheSingleRayResults) {
  Rays rays = random_rays(5000, 2);
  rays.tmin[0] = 0.0f;
  rays.tmax[0] = kInf;
  expect_same_as_single_rays(batch_of(rays, true));
}

TEST_P(AppRayBatch, OneThreadGivesTheSameResults) {
  const ThreadLimit one(1);
  const Rays rays = random_rays(3000, 3);
  expect_same_as_single_rays(batch_of(rays, false));
}

TEST_P(AppRayBatch, NoRaysIsFine) {
  const RayBatch batch{};  // no rays
  EXPECT_NO_THROW(intersect_batch(*accel_, batch, HitArrays{}));
  EXPECT_NO_THROW(occluded_batch(*accel_, batch, {}));
}

TEST_P(AppRayBatch, WrongSizesAreInternalErrors) {
  const Rays rays = random_rays(10, 4);
  RayBatch batch = batch_of(rays, false);
  batch.size = 11;
  EXPECT_THROW(occluded_batch(*accel_, batch, {}), Error);
}

INSTANTIATE_TEST_SUITE_P(Backends, AppRayBatch, ::testing::Values("brute", "bvh", "embree"),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace prism
