// Lights (integrators/lights/): chi-square goodness of fit of sample_li() against pdf_li(), the
// values of delta lights, and the light set (selection by power, emissive meshes counted once).
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "core/angles.h"
#include "core/error.h"
#include "core/sampler.h"
#include "integrators/lights/area_light.h"
#include "integrators/lights/environment_light.h"
#include "integrators/lights/light_set.h"
#include "integrators/lights/point_light.h"
#include "integrators/sampling/warp.h"
#include "tests/support/chi_square.h"

namespace prism {
namespace {

using test::ChiSquareResult;
using test::directional_chi_square;
using test::DirectionalChiSquareOptions;
using test::DirectionPdf;
using test::DirectionSampler;
using test::sidak_significance;

constexpr size_t kChiSquareTests = 64;  // shared with integrators_bsdf_test.cpp
const double kSignificance = sidak_significance(0.01, kChiSquareTests);

/// Nearest intersection of a ray with a triangle (Moller-Trumbore), or nothing.
std::optional<float> hit_triangle(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b,
                                  const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 p = glm::cross(d, e2);
  const float det = glm::dot(e1, p);
  if (std::abs(det) < 1e-12f) return std::nullopt;
  const Vec3 s = o - a;
  const float u = glm::dot(s, p) / det;
  if (u < 0.0f || u > 1.0f) return std::nullopt;
  const Vec3 q = glm::cross(s, e1);
  const float v = glm::dot(d, q) / det;
  if (v < 0.0f || u + v > 1.0f) return std::nullopt;
  const float t = glm::dot(e2, q) / det;
  return t > 0.0f ? std::optional<float>(t) : std::nullopt;
}

/// The first triangle of `mesh` that the ray from `p` along `w` hits, as the surface point a
/// light's pdf_li() takes (prim_id, position, geometric normal), or nothing.
std::optional<SurfaceInteraction> hit_mesh(const TriangleMesh& mesh, const Vec3& p, const Vec3& w) {
  for (uint32_t i = 0; i < mesh.triangles.size(); ++i) {
    const glm::uvec3 t = mesh.triangles[i];
    const Vec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
    const auto hit = hit_triangle(p, w, a, b, c);
    if (!hit) continue;
    SurfaceInteraction si;
    si.prim_id = i;
    si.position = p + *hit * w;
    si.geometric_normal = glm::normalize(glm::cross(b - a, c - a));
    return si;
  }
  return std::nullopt;
}

TriangleMesh tilted_quad() {
  TriangleMesh mesh;
  mesh.name = "emitter";
  // A 1 x 0.5 quad above the origin, tilted, wound so that its normal faces down-ish.
  mesh.positions = {
      {-0.5f, -0.25f, 2.0f}, {0.5f, -0.25f, 2.3f}, {0.5f, 0.25f, 2.3f}, {-0.5f, 0.25f, 2.0f}};
  mesh.triangles = {{0, 2, 1}, {0, 3, 2}};
  mesh.finalize();
  return mesh;
}

/// The tilted quad's far corner moved along its long edge: a parallelogram, not a rectangle.
TriangleMesh tilted_parallelogram() {
  TriangleMesh mesh = tilted_quad();
  mesh.positions[2] += Vec3(0.3f, 0.0f, 0.09f);
  mesh.positions[3] += Vec3(0.3f, 0.0f, 0.09f);
  mesh.finalize();
  return mesh;
}

TEST(IntegratorsLights, MeshLightSamplesRectanglesAsOne) {
  const TriangleMesh quad = tilted_quad();
  EXPECT_TRUE(MeshLight(quad, Rgb(1.0f), false).is_rectangle());
  EXPECT_TRUE(MeshLight(quad, Rgb(1.0f), true).is_rectangle());
  EXPECT_FALSE(MeshLight(tilted_parallelogram(), Rgb(1.0f), false).is_rectangle());
  // The same rectangle wound the other way, and as the other diagonal's two triangles.
  TriangleMesh flipped = quad;
  flipped.triangles = {{0, 1, 2}, {0, 2, 3}};
  EXPECT_TRUE(MeshLight(flipped, Rgb(1.0f), false).is_rectangle());
  TriangleMesh other_diagonal = quad;
  other_diagonal.triangles = {{0, 3, 1}, {1, 3, 2}};
  EXPECT_TRUE(MeshLight(other_diagonal, Rgb(1.0f), false).is_rectangle());
  TriangleMesh one = quad;
  one.triangles.pop_back();
  EXPECT_FALSE(MeshLight(one, Rgb(1.0f), false).is_rectangle());
}

TEST(IntegratorsLights, MeshLightSamplingMatchesPdf) {
  // The rectangle (sampled as one) in each of its samplings, and a parallelogram (two
  // triangles, which the rectangle sampling leaves alone).
  struct Case {
    TriangleMesh mesh;
    RectangleSampling rectangles;
  };
  const Case cases[] = {{tilted_quad(), RectangleSampling::kBilinear},
                        {tilted_quad(), RectangleSampling::kSolidAngle},
                        {tilted_quad(), RectangleSampling::kArea},
                        {tilted_parallelogram(), RectangleSampling::kBilinear}};
  for (const Case& c : cases) {
    const TriangleMesh& mesh = c.mesh;
    const MeshLight light(mesh, Rgb(2.0f), false, {}, c.rectangles);
    // Below the quad (solid angle) and close to it, where its
    // triangles' solid angles differ most.
    for (const Vec3& p : {Vec3(0.0f), Vec3(1.5f, -0.5f, 0.5f), Vec3(0.3f, 0.1f, 1.85f)}) {
      const DirectionSampler sampler = [&](float, Vec2 u) -> std::optional<Vec3> {
        const auto s = light.sample_li(p, u);
        if (!s) return std::nullopt;
        return s->wi;
      };
      const DirectionPdf pdf = [&](const Vec3& w) -> double {
        const auto si = hit_mesh(mesh, p, w);
        return si ? light.pdf_li(p, *si) : 0.0;
      };
      DirectionalChiSquareOptions options;
      options.theta_bins = 40;  // the light subtends a small solid angle
      options.phi_bins = 80;
      const ChiSquareResult r = directional_chi_square(sampler, pdf, options);
      EXPECT_EQ(r.impossible_observations, 0u);
      EXPECT_GT(r.p_value, kSignificance) << r.summary() << " at " << p.x << " " << p.y << " "
                                          << p.z << ", rectangle sampling " << int(c.rectangles);
    }
  }
}

TEST(IntegratorsLights, MeshLightFarAwayIsSampledInArea) {
  // Seen from afar the quad's triangles subtend less than kMinSphericalSolidAngle, too small
  // for the histogram's cells: 1 / pdf must average to the solid angle instead, and pdf_li()
  // must repeat sample_li()'s density.
  const TriangleMesh mesh = tilted_quad();
  const MeshLight light(mesh, Rgb(2.0f), false);
  const Vec3 p(2.0f, 1.0f, -60.0f);
  float omega = 0.0f;
  for (const glm::uvec3& t : mesh.triangles) {
    const float o = triangle_solid_angle(mesh.positions[t.x] - p, mesh.positions[t.y] - p,
                                         mesh.positions[t.z] - p);
    EXPECT_LT(o, MeshLight::kMinSphericalSolidAngle);
    omega += o;
  }
  IndependentSampler rng(7);
  double sum = 0.0;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    rng.start_pixel_sample({0, 0}, uint32_t(k));
    const auto s = light.sample_li(p, rng.get_2d());
    ASSERT_TRUE(s);
    sum += 1.0 / s->pdf;
    if (const auto si = hit_mesh(mesh, p, s->wi)) {
      EXPECT_NEAR(light.pdf_li(p, *si), s->pdf, 1e-3f * s->pdf);
    }
  }
  EXPECT_NEAR(sum / n, omega, 0.01 * omega);
}

/// Checks the light rays `light` emits: each carries the light's power (untextured emitters
/// sampled in area and cosine), leaves a point of the emitter on its emitting side, and the
/// directions are cosine-distributed (mean cosine 2/3); `front_fraction` of them leave the
/// side `front(point)` says is the front. Grazing samples may be dropped, one in a thousand.
template <typename FrontNormal>
void expect_emission_samples(const LightSource& light, FrontNormal front, double front_fraction) {
  const int n = 20000;
  double cos_sum = 0.0;
  int front_count = 0, missing = 0;
  for (int i = 0; i < n; ++i) {
    // The fractional parts in double: in float they fall on multiples of 2^-10 for large i, and
    // one in a thousand is exactly 0, whose direction (on the disk's rim) is exactly grazing.
    const Vec2 u_point((float(i) + 0.5f) / float(n), float(std::fmod(0.618034 * i, 1.0)));
    const Vec2 u_direction(float(std::fmod(0.754878 * i, 1.0)),
                           float(std::fmod(0.569840 * i, 1.0)));
    const std::optional<LightLeSample> s = light.sample_le(u_point, u_direction);
    if (!s) {
      ++missing;  // grazing directions are dropped
      continue;
    }
    EXPECT_NEAR(luminance(s->beta), luminance(light.power()), 1e-4 * luminance(light.power()));
    const float c = glm::dot(s->direction, s->point.geometric_normal);
    ASSERT_GT(c, 0.0f) << "a direction into the emitter";
    EXPECT_NEAR(glm::length(s->direction), 1.0f, 1e-5f);
    cos_sum += c;
    if (glm::dot(s->point.geometric_normal, front(s->point.position)) > 0.0f) ++front_count;
    // The ray leaves the surface: its origin is off it on the emitting side.
    const Ray ray = spawn_ray(s->point, s->direction);
    EXPECT_GE(glm::dot(ray.origin - s->point.position, s->point.geometric_normal), 0.0f);
  }
  EXPECT_LT(missing, n / 1000);
  EXPECT_NEAR(cos_sum / (n - missing), 2.0 / 3.0, 0.01);
  EXPECT_NEAR(double(front_count) / (n - missing), front_fraction, 0.02);
}

TEST(IntegratorsLights, EmissionSamplesCarryThePowerFromTheEmittingSide) {
  const TriangleMesh mesh = tilted_quad();
  const Vec3 front_normal = glm::normalize(
      glm::cross(mesh.positions[2] - mesh.positions[0], mesh.positions[1] - mesh.positions[0]));
  const auto quad_front = [&](const Vec3&) { return front_normal; };
  expect_emission_samples(MeshLight(mesh, Rgb(2.0f), false), quad_front, 1.0);
  expect_emission_samples(MeshLight(mesh, Rgb(2.0f), true), quad_front, 0.5);
  const Sphere sphere{Vec3(1.0f, -2.0f, 0.5f), 0.75f, 0};
  const auto outward = [&](const Vec3& p) { return p - sphere.center; };
  expect_emission_samples(SphereLight(sphere, Rgb(0.5f, 1.0f, 2.0f), false), outward, 1.0);
  expect_emission_samples(SphereLight(sphere, Rgb(0.5f, 1.0f, 2.0f), true), outward, 0.5);
  // Points lie on the emitter.
  const MeshLight light(mesh, Rgb(2.0f), false);
  for (const Vec2 u : {Vec2(0.1f, 0.2f), Vec2(0.7f, 0.9f)}) {
    const std::optional<LightLeSample> s = light.sample_le(u, Vec2(0.5f));
    ASSERT_TRUE(s.has_value());
    EXPECT_NEAR(glm::dot(s->point.position - mesh.positions[0], front_normal), 0.0f, 1e-5f);
  }
  // Lights that are not scene geometry emit no rays for light tracing.
  Light point;
  point.type = LightType::kPoint;
  EXPECT_FALSE(PointLight(point).sample_le(Vec2(0.5f), Vec2(0.5f)).has_value());
}

TEST(IntegratorsLights, TriangleSolidAngle) {
  // An octant: a quarter of a hemisphere, whatever the vertices' lengths.
  EXPECT_NEAR(triangle_solid_angle({2, 0, 0}, {0, 1, 0}, {0, 0, 3}), kPi / 2.0f, 1e-5f);
  // The two halves of a centred w x h rectangle at distance d add up to
  // 4 asin(w h / sqrt((w^2 + 4 d^2) (h^2 + 4 d^2))).
  const float w = 1.2f, h = 0.7f, d = 0.4f;
  const Vec3 a(-w / 2, -h / 2, d), b(w / 2, -h / 2, d), c(w / 2, h / 2, d), e(-w / 2, h / 2, d);
  const float expected =
      4.0f * std::asin(w * h / std::sqrt((w * w + 4 * d * d) * (h * h + 4 * d * d)));
  EXPECT_NEAR(triangle_solid_angle(a, b, c) + triangle_solid_angle(a, c, e), expected, 1e-5f);
  EXPECT_NEAR(triangle_solid_angle(a, b, a), 0.0f, 1e-6f);  // degenerate
}

TEST(IntegratorsLights, Atan2OfNonNegativeYMatchesLibm) {
  // Every octant boundary and a dense sweep of angles and magnitudes, in float.
  float worst = 0.0f;
  for (int i = 0; i <= 20000; ++i) {
    const double angle = kPi * double(i) / 20000.0;
    for (const double radius : {1e-30, 1e-3, 1.0, 7.5, 1e20}) {
      const float y = std::max(0.0f, float(radius * std::sin(angle)));
      const float x = float(radius * std::cos(angle));
      worst = std::max(worst, std::abs(atan2_nonnegative_y(y, x) - std::atan2(y, x)));
    }
  }
  EXPECT_LE(worst, 2.5e-7f);
  EXPECT_EQ(atan2_nonnegative_y(0.0f, 0.0f), 0.0f);
  EXPECT_FLOAT_EQ(atan2_nonnegative_y(0.0f, -2.0f), kPi);
  EXPECT_FLOAT_EQ(atan2_nonnegative_y(3.0f, 0.0f), 0.5f * kPi);
  EXPECT_FLOAT_EQ(atan2_nonnegative_y(std::numeric_limits<float>::infinity(), 1.0f), 0.5f * kPi);
  EXPECT_TRUE(std::isnan(atan2_nonnegative_y(std::nanf(""), 1.0f)));
  EXPECT_TRUE(std::isnan(atan2_nonnegative_y(1.0f, std::nanf(""))));
}

TEST(IntegratorsLights, SphericalTriangleSamplingMatchesPdf) {
  // Triangles subtending large and small solid angles, one covering almost a hemisphere.
  const Vec3 triangles[][3] = {{{-1.0f, -1.0f, 1.0f}, {1.5f, -0.5f, 1.0f}, {0.0f, 1.0f, 1.0f}},
                               {{0.2f, 0.1f, 2.0f}, {0.6f, 0.2f, 2.5f}, {0.3f, 0.7f, 1.8f}},
                               {{-9.0f, -9.0f, 0.3f}, {9.0f, -9.0f, 0.3f}, {0.0f, 12.0f, 0.3f}}};
  for (const auto& v : triangles) {
    const float omega = triangle_solid_angle(v[0], v[1], v[2]);
    ASSERT_GT(omega, 0.0f);
    const Vec3 a = glm::normalize(v[0]), b = glm::normalize(v[1]), c = glm::normalize(v[2]);
    const DirectionSampler sampler = [&](float, Vec2 u) {
      return sample_spherical_triangle(a, b, c, omega, u);
    };
    const DirectionPdf pdf = [&](const Vec3& w) -> double {
      return hit_triangle(Vec3(0.0f), w, v[0], v[1], v[2]) ? 1.0 / omega : 0.0;
    };
    DirectionalChiSquareOptions options;
    options.theta_bins = 40;
    options.phi_bins = 80;
    const ChiSquareResult r = directional_chi_square(sampler, pdf, options);
    EXPECT_EQ(r.impossible_observations, 0u) << omega;
    EXPECT_GT(r.p_value, kSignificance) << r.summary();
  }
}

TEST(IntegratorsLights, SphereLightSamplingMatchesPdf) {
  const Sphere sphere{Vec3(0.3f, 0.2f, 1.5f), 0.6f, 0};
  const SphereLight light(sphere, Rgb(1.0f), false);
  const Vec3 p(0.0f);
  const DirectionSampler sampler = [&](float, Vec2 u) -> std::optional<Vec3> {
    const auto s = light.sample_li(p, u);
    if (!s) return std::nullopt;
    return s->wi;
  };
  const DirectionPdf pdf = [&](const Vec3& w) -> double {
    // Nearest hit with the sphere from outside: the visible cap is what sample_li() yields.
    const Vec3 oc = p - sphere.center;
    const float b = glm::dot(oc, w);
    const float c = glm::dot(oc, oc) - sphere.radius * sphere.radius;
    const float disc = b * b - c;
    if (disc < 0.0f) return 0.0;
    const float t = -b - std::sqrt(disc);
    if (t <= 0.0f) return 0.0;
    SurfaceInteraction si;
    si.position = p + t * w;
    si.geometric_normal = glm::normalize(si.position - sphere.center);
    return light.pdf_li(p, si);
  };
  DirectionalChiSquareOptions options;
  options.theta_bins = 40;
  options.phi_bins = 80;
  const ChiSquareResult r = directional_chi_square(sampler, pdf, options);
  EXPECT_EQ(r.impossible_observations, 0u);
  EXPECT_GT(r.p_value, kSignificance) << r.summary();
}

TEST(IntegratorsLights, ParallelogramLightSamplingIsUniformInArea) {
  Light l;
  l.type = LightType::kArea;
  l.color = Rgb(5.0f);
  l.position = Vec3(0.2f, 0.0f, 1.0f);
  l.direction = glm::normalize(Vec3(0.2f, 0.0f, -1.0f));
  l.edge_u = Vec3(0.8f, 0.0f, 0.16f);
  l.edge_v = Vec3(0.0f, 0.6f, 0.0f);
  const ParallelogramLight light(l, false);
  const Vec3 p(0.0f);
  const Vec3 corner = l.position - 0.5f * (l.edge_u + l.edge_v);
  const float area = glm::length(glm::cross(l.edge_u, l.edge_v));
  const DirectionSampler sampler = [&](float, Vec2 u) -> std::optional<Vec3> {
    const auto s = light.sample_li(p, u);
    if (!s) return std::nullopt;
    EXPECT_EQ(s->li, l.color);
    return s->wi;
  };
  const DirectionPdf pdf = [&](const Vec3& w) -> double {
    const Vec3 a = corner, b = corner + l.edge_u, c = corner + l.edge_u + l.edge_v,
               d = corner + l.edge_v;
    std::optional<float> t = hit_triangle(p, w, a, b, c);
    if (!t) t = hit_triangle(p, w, a, c, d);
    if (!t) return 0.0;
    const float cos_light = std::abs(glm::dot(l.direction, w));
    return (*t) * (*t) / (area * cos_light);
  };
  DirectionalChiSquareOptions options;
  options.theta_bins = 40;
  options.phi_bins = 80;
  const ChiSquareResult r = directional_chi_square(sampler, pdf, options);
  EXPECT_EQ(r.impossible_observations, 0u);
  EXPECT_GT(r.p_value, kSignificance) << r.summary();
  // One-sided: nothing reaches a point behind it.
  EXPECT_FALSE(light.sample_li(Vec3(0.0f, 0.0f, 3.0f), {0.5f, 0.5f}).has_value());
}

TEST(IntegratorsLights, AmbientLightSamplingMatchesPdf) {
  Light l;
  l.type = LightType::kAmbient;
  l.color = Rgb(0.5f);
  l.up = glm::normalize(Vec3(0.3f, 0.1f, 1.0f));
  const AmbientLight light(l, 1.0f, true);
  EXPECT_EQ(light.kind(), LightKind::kInfinite);
  EXPECT_TRUE(light.is_hittable());
  const DirectionSampler sampler = [&](float, Vec2 u) -> std::optional<Vec3> {
    const auto s = light.sample_li(Vec3(0.0f), u);
    if (!s) return std::nullopt;
    return s->wi;
  };
  const DirectionPdf pdf = [&](const Vec3& w) { return double(light.pdf_li_escaped(w)); };
  const ChiSquareResult r = directional_chi_square(sampler, pdf);
  EXPECT_EQ(r.impossible_observations, 0u);
  EXPECT_GT(r.p_value, kSignificance) << r.summary();
  EXPECT_EQ(light.le_escaped(l.up), l.color);
  EXPECT_EQ(light.le_escaped(-l.up), Rgb(0.0f));
  // Hidden (the default in a LightSet): light sampling alone finds it, the same way.
  const AmbientLight hidden(l, 1.0f, false);
  EXPECT_EQ(hidden.kind(), LightKind::kHiddenInfinite);
  EXPECT_FALSE(hidden.is_hittable());
  EXPECT_FALSE(hidden.is_delta());
  const auto a = light.sample_li(Vec3(0.0f), {0.3f, 0.7f});
  const auto b = hidden.sample_li(Vec3(0.0f), {0.3f, 0.7f});
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->wi, b->wi);
  EXPECT_EQ(a->pdf, b->pdf);
  EXPECT_EQ(a->li, b->li);
}

TEST(IntegratorsLights, TwoSidedEmittersSampleBothSides) {
  // From behind the tilted quad (its front faces down-ish): nothing one-sided, the same
  // density as seen from the front when two-sided, and the same radiance on both faces.
  const TriangleMesh mesh = tilted_quad();
  const MeshLight one_sided(mesh, Rgb(2.0f), false);
  const MeshLight light(mesh, Rgb(2.0f), true);
  EXPECT_EQ(light.power(), 2.0f * one_sided.power());
  const Vec3 behind(0.2f, 0.1f, 4.0f);
  EXPECT_FALSE(one_sided.sample_li(behind, {0.5f, 0.5f}).has_value());
  const DirectionSampler sampler = [&](float, Vec2 u) -> std::optional<Vec3> {
    const auto s = light.sample_li(behind, u);
    if (!s) return std::nullopt;
    EXPECT_EQ(s->li, Rgb(2.0f));
    return s->wi;
  };
  SurfaceInteraction back;  // a point of the quad seen from above: the normal as surface_at
  const DirectionPdf pdf = [&](const Vec3& w) -> double {
    const auto si = hit_mesh(mesh, behind, w);
    if (!si) return 0.0;
    back = *si;
    return light.pdf_li(behind, *si);
  };
  DirectionalChiSquareOptions options;
  options.theta_bins = 40;
  options.phi_bins = 80;
  const ChiSquareResult r = directional_chi_square(sampler, pdf, options);
  EXPECT_EQ(r.impossible_observations, 0u);
  EXPECT_GT(r.p_value, kSignificance) << r.summary();
  EXPECT_EQ(one_sided.pdf_li(behind, back), 0.0f);
  EXPECT_GT(light.pdf_li(behind, back), 0.0f);
  const Vec3 up(0.0f, 0.0f, 1.0f);  // leaving the quad's back
  EXPECT_EQ(one_sided.le(back, up), Rgb(0.0f));
  EXPECT_EQ(light.le(back, up), Rgb(2.0f));
  EXPECT_EQ(light.le(back, -up), Rgb(2.0f));

  // A two-sided sphere lights its inside: every direction from within meets it once.
  const Sphere sphere{Vec3(0.3f, 0.2f, 1.5f), 0.6f, 0};
  const SphereLight ball(sphere, Rgb(1.0f), true);
  const Vec3 inside = sphere.center + Vec3(0.1f, -0.2f, 0.15f);
  EXPECT_FALSE(SphereLight(sphere, Rgb(1.0f), false).sample_li(inside, {0.4f, 0.6f}));
  const DirectionSampler ball_sampler = [&](float, Vec2 u) -> std::optional<Vec3> {
    const auto s = ball.sample_li(inside, u);
    if (!s) return std::nullopt;
    return s->wi;
  };
  const DirectionPdf ball_pdf = [&](const Vec3& w) -> double {
    const Vec3 oc = inside - sphere.center;
    const float b = glm::dot(oc, w);
    const float c = glm::dot(oc, oc) - sphere.radius * sphere.radius;
    const float t = -b + std::sqrt(b * b - c);  // c < 0 inside: one root ahead
    SurfaceInteraction si;
    si.position = inside + t * w;
    si.geometric_normal = glm::normalize(si.position - sphere.center);
    return ball.pdf_li(inside, si);
  };
  const ChiSquareResult rb = directional_chi_square(ball_sampler, ball_pdf);
  EXPECT_EQ(rb.impossible_observations, 0u);
  EXPECT_GT(rb.p_value, kSignificance) << rb.summary();

  // The CGL area light: seen from behind only when two-sided, with the same density.
  Light l;
  l.type = LightType::kArea;
  l.color = Rgb(5.0f);
  l.position = Vec3(0.0f, 0.0f, 1.0f);
  l.direction = Vec3(0.0f, 0.0f, -1.0f);
  l.edge_u = Vec3(0.8f, 0.0f, 0.0f);
  l.edge_v = Vec3(0.0f, 0.6f, 0.0f);
  const ParallelogramLight front_only(l, false), both(l, true);
  EXPECT_EQ(both.power(), 2.0f * front_only.power());
  EXPECT_FALSE(front_only.sample_li(Vec3(0.0f, 0.0f, 2.0f), {0.3f, 0.6f}));
  const auto below = both.sample_li(Vec3(0.0f), {0.3f, 0.6f});
  const auto above = both.sample_li(Vec3(0.0f, 0.0f, 2.0f), {0.3f, 0.6f});
  ASSERT_TRUE(below && above);
  EXPECT_FLOAT_EQ(below->pdf, above->pdf);
  EXPECT_EQ(above->li, l.color);
}

/// A small lat-long map: a dim gradient, a bright spot, and a black band.
Image test_environment() {
  Image image;
  image.width = 32;
  image.height = 16;
  image.channel_names = {"R", "G", "B", "A"};
  image.pixels.assign(size_t(image.width) * image.height * 4, 0.0f);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const float g = y >= 10 && y < 12 ? 0.0f : 0.1f + 0.02f * float(x);
      image.at(x, y, 0) = g;
      image.at(x, y, 1) = 0.5f * g;
      image.at(x, y, 2) = y == 3 ? -1.0f : g;  // negative values count as zero
      image.at(x, y, 3) = 1.0f;
    }
  }
  image.at(5, 4, 0) = image.at(5, 4, 1) = image.at(5, 4, 2) = 50.0f;
  return image;
}

TEST(IntegratorsLights, EnvironmentSamplingMatchesPdf) {
  const EnvironmentLight light(test_environment(), glm::normalize(Vec3(0.0f, 0.2f, 1.0f)), 1.0f);
  const DirectionSampler sampler = [&](float, Vec2 u) -> std::optional<Vec3> {
    const auto s = light.sample_li(Vec3(0.0f), u);
    if (!s) return std::nullopt;
    // The radiance returned is the radiance seen along that direction.
    const Rgb le = light.le_escaped(s->wi);
    EXPECT_NEAR(s->li.r, le.r, 1e-5f * (1.0f + le.r));
    EXPECT_GT(luminance(s->li), 0.0f);
    return s->wi;
  };
  const DirectionPdf pdf = [&](const Vec3& w) { return double(light.pdf_li_escaped(w)); };
  DirectionalChiSquareOptions options;
  options.theta_bins = 40;
  options.phi_bins = 80;
  const ChiSquareResult r = directional_chi_square(sampler, pdf, options);
  EXPECT_EQ(r.impossible_observations, 0u);
  EXPECT_GT(r.p_value, kSignificance) << r.summary();
  Image no_rgb;
  no_rgb.width = no_rgb.height = 1;
  no_rgb.channel_names = {"Y"};
  no_rgb.pixels = {1.0f};
  EXPECT_THROW(EnvironmentLight(no_rgb, Vec3(0, 0, 1), 1.0f), Error);
}

TEST(IntegratorsLights, PointAndSpotLightsFollowColladaAttenuation) {
  Light l;
  l.type = LightType::kPoint;
  l.color = Rgb(4.0f);
  l.position = Vec3(0.0f, 0.0f, 2.0f);
  l.constant_attenuation = 1.0f;
  l.linear_attenuation = 0.5f;
  l.quadratic_attenuation = 0.25f;
  const PointLight point(l);
  const auto s = point.sample_li(Vec3(0.0f), {0.3f, 0.3f});
  ASSERT_TRUE(s);
  EXPECT_TRUE(point.is_delta());
  EXPECT_NEAR(s->distance, 2.0f, 1e-6f);
  EXPECT_NEAR(s->wi.z, 1.0f, 1e-6f);
  EXPECT_NEAR(s->li.r, 4.0f / (1.0f + 0.5f * 2.0f + 0.25f * 4.0f), 1e-5f);

  l.type = LightType::kSpot;
  l.direction = Vec3(0.0f, 0.0f, -1.0f);
  l.falloff_angle_deg = 60.0f;  // full cone: 30 degrees off the axis
  l.falloff_exponent = 2.0f;
  const PointLight spot(l);
  const auto on_axis = spot.sample_li(Vec3(0.0f), {0.5f, 0.5f});
  ASSERT_TRUE(on_axis);
  EXPECT_NEAR(on_axis->li.r, s->li.r, 1e-5f);
  // 20 degrees off the axis: inside, scaled by cos^2.
  const float off = 2.0f * std::tan(radians(20.0f));
  const auto inside = spot.sample_li(Vec3(off, 0.0f, 0.0f), {0.5f, 0.5f});
  ASSERT_TRUE(inside);
  const float d = std::sqrt(4.0f + off * off);
  const float cos20 = std::cos(radians(20.0f));
  EXPECT_NEAR(inside->li.r, 4.0f / (1.0f + 0.5f * d + 0.25f * d * d) * cos20 * cos20, 1e-4f);
  // 40 degrees off the axis: outside the cone.
  EXPECT_FALSE(spot.sample_li(Vec3(2.0f * std::tan(radians(40.0f)), 0.0f, 0.0f), {0.5f, 0.5f}));
}

TEST(IntegratorsLights, DirectionalLight) {
  Light l;
  l.type = LightType::kDirectional;
  l.color = Rgb(3.0f);
  l.direction = glm::normalize(Vec3(1.0f, 0.0f, -1.0f));
  const DirectionalLight light(l, 2.0f);
  const auto s = light.sample_li(Vec3(5.0f), {0.1f, 0.2f});
  ASSERT_TRUE(s);
  EXPECT_NEAR(glm::dot(s->wi, -l.direction), 1.0f, 1e-6f);
  EXPECT_TRUE(std::isinf(s->distance));
  EXPECT_EQ(s->li, l.color);
}

Scene scene_with_emitters() {
  Scene scene;
  scene.materials.resize(3);
  scene.materials[0].type = MaterialType::kDiffuse;
  scene.materials[1].type = MaterialType::kEmission;
  scene.materials[1].radiance = Rgb(10.0f);
  scene.materials[2].type = MaterialType::kEmission;
  scene.materials[2].radiance = Rgb(1.0f);
  TriangleMesh wall = tilted_quad();
  wall.material_id = 0;
  TriangleMesh lamp = tilted_quad();
  lamp.material_id = 1;
  scene.geometry.meshes = {wall, lamp};
  scene.geometry.spheres = {Sphere{Vec3(0.0f), 0.1f, 0}, Sphere{Vec3(1.0f), 0.2f, 2}};
  Light proxy;
  proxy.type = LightType::kArea;
  proxy.color = Rgb(10.0f);
  proxy.edge_u = Vec3(1, 0, 0);
  proxy.edge_v = Vec3(0, 1, 0);
  proxy.duplicates_emissive_mesh = true;
  Light point;
  point.type = LightType::kPoint;
  point.color = Rgb(1.0f);
  scene.lights = {proxy, point};
  scene.geometry.finalize();
  return scene;
}

TEST(IntegratorsLights, LightSetCountsEmissiveMeshesOnceAndChoosesByPower) {
  const Scene scene = scene_with_emitters();
  const LightSet set(scene);
  // The point light, the emissive mesh and the emissive sphere; not the duplicate proxy.
  ASSERT_EQ(set.size(), 3u);
  int kinds[5] = {0, 0, 0, 0, 0};
  for (const auto& l : set.lights()) ++kinds[int(l->kind())];
  EXPECT_EQ(kinds[int(LightKind::kDelta)], 1);
  EXPECT_EQ(kinds[int(LightKind::kSurface)], 2);
  EXPECT_EQ(kinds[int(LightKind::kArea)], 0);

  double total = 0.0;
  for (const auto& l : set.lights()) total += luminance(l->power());
  for (size_t i = 0; i < set.size(); ++i) {
    EXPECT_NEAR(set.pmf(i), luminance(set.lights()[i]->power()) / total, 1e-6);
  }
  // Empirical selection frequencies.
  IndependentSampler rng(3);
  std::vector<int> counts(set.size(), 0);
  const int n = 30000;
  for (int i = 0; i < n; ++i) {
    rng.start_pixel_sample({0, 0}, uint32_t(i));
    float pmf = 0.0f;
    const LightSource* light = set.sample(rng.get_1d(), &pmf);
    ASSERT_NE(light, nullptr);
    const size_t index = set.index_of(light);
    ASSERT_LT(index, set.size());
    EXPECT_EQ(pmf, set.pmf(index));
    ++counts[index];
  }
  for (size_t i = 0; i < set.size(); ++i) {
    const double p = set.pmf(i);
    EXPECT_NEAR(double(counts[i]) / n, p, 4.5 * std::sqrt(p * (1 - p) / n) + 1e-9);
  }

  SurfaceInteraction si;
  si.geom_id = 1;
  EXPECT_NE(set.surface_light(si), nullptr);
  si.geom_id = 0;
  EXPECT_EQ(set.surface_light(si), nullptr);
  si.geom_id = scene.geometry.sphere_geom_id();
  si.prim_id = 1;
  EXPECT_NE(set.surface_light(si), nullptr);
  si.prim_id = 0;
  EXPECT_EQ(set.surface_light(si), nullptr);
}

TEST(IntegratorsLights, LightSetLightsTheSceneWithItsEnvironmentMap) {
  Scene scene = scene_with_emitters();
  const size_t without = LightSet(scene).size();
  // Rows 0-1 (the hemisphere around up = +z) red, rows 2-3 blue.
  const Rgb red(2.0f, 0.0f, 0.0f), blue(0.0f, 0.0f, 1.0f);
  SceneEnvironment environment;
  environment.image.width = 8;
  environment.image.height = 4;
  environment.image.channel_names = {"R", "G", "B"};
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 8; ++x) {
      const Rgb c = y < 2 ? red : blue;
      for (int k = 0; k < 3; ++k) environment.image.pixels.push_back(c[k]);
    }
  }
  environment.up = Vec3(0.0f, 0.0f, 1.0f);
  scene.environment = environment;
  const LightSet set(scene);
  ASSERT_EQ(set.size(), without + 1);
  ASSERT_EQ(set.infinite_lights().size(), 1u);
  EXPECT_EQ(set.le_escaped(Vec3(0.0f, 0.0f, 1.0f)), red);
  EXPECT_EQ(set.le_escaped(glm::normalize(Vec3(1.0f, 0.5f, 0.2f))), red);
  EXPECT_EQ(set.le_escaped(glm::normalize(Vec3(-1.0f, 0.5f, -0.2f))), blue);
  // The same map about another up: its poles follow.
  scene.environment->up = Vec3(0.0f, -1.0f, 0.0f);
  const LightSet turned(scene);
  EXPECT_EQ(turned.le_escaped(Vec3(0.0f, -1.0f, 0.0f)), red);
  EXPECT_EQ(turned.le_escaped(Vec3(0.0f, 0.0f, 1.0f) * 0.6f + Vec3(0.0f, 0.8f, 0.0f)), blue);
}

TEST(IntegratorsLights, LightSetHidesAmbientLightsFromEscapingRaysByDefault) {
  Scene scene = scene_with_emitters();
  Light sky;
  sky.type = LightType::kAmbient;
  sky.color = Rgb(0.5f);
  sky.up = Vec3(0.0f, 0.0f, 1.0f);
  scene.lights.push_back(sky);
  const Vec3 up(0.0f, 0.0f, 1.0f);
  const LightSet hidden(scene);
  ASSERT_EQ(hidden.size(), 4u);  // still a light that sample() chooses
  EXPECT_TRUE(hidden.infinite_lights().empty());
  EXPECT_EQ(hidden.le_escaped(up), Rgb(0.0f));
  const LightSet visible(scene, LightOptions{.ambient_visible = true});
  ASSERT_EQ(visible.infinite_lights().size(), 1u);
  EXPECT_EQ(visible.le_escaped(up), sky.color);
  EXPECT_EQ(visible.le_escaped(-up), Rgb(0.0f));
  for (size_t i = 0; i < hidden.size(); ++i) EXPECT_EQ(hidden.pmf(i), visible.pmf(i));
  // Environment maps stay visible whatever the option.
  scene.environment = SceneEnvironment{};
  scene.environment->image.width = 2;
  scene.environment->image.height = 1;
  scene.environment->image.channel_names = {"R", "G", "B"};
  scene.environment->image.pixels.assign(6, 1.0f);
  EXPECT_EQ(LightSet(scene).infinite_lights().size(), 1u);
  EXPECT_EQ(LightSet(scene).le_escaped(-up), Rgb(1.0f));
}

TEST(IntegratorsLights, AreaLightWithoutDuplicateIsKept) {
  Scene scene = scene_with_emitters();
  scene.lights[0].duplicates_emissive_mesh = false;
  const LightSet set(scene);
  EXPECT_EQ(set.size(), 4u);
}

}  // namespace
}  // namespace prism
