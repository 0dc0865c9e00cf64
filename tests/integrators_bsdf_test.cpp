// BSDFs: white furnace, chi-square goodness of fit of sampling against pdf, consistency of
// sample() with eval()/pdf(), and the delta lobes' directions and probabilities.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/sampler.h"
#include "integrators/bsdf/bsdf_factory.h"
#include "integrators/bsdf/diffuse_bsdf.h"
#include "integrators/bsdf/fresnel.h"
#include "integrators/bsdf/glass_bsdf.h"
#include "integrators/bsdf/microfacet_bsdf.h"
#include "integrators/bsdf/mirror_bsdf.h"
#include "integrators/light_transport.h"
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

// Every chi-square test in this file and in integrators_light_test.cpp shares one family-wise
// significance of 0.01 (Sidak), over at most this many tests.
constexpr size_t kChiSquareTests = 64;
const double kSignificance = sidak_significance(0.01, kChiSquareTests);

Vec3 direction_at(float theta_deg, float phi_deg = 30.0f) {
  const float t = radians(theta_deg), p = radians(phi_deg);
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

struct NamedBsdf {
  std::string name;
  std::shared_ptr<Bsdf> bsdf;
};

/// Perfect conductor: |k| huge makes the Fresnel term 1 at every angle.
constexpr float kPerfectK = 1e4f;

std::vector<NamedBsdf> glossy_bsdfs() {
  std::vector<NamedBsdf> out;
  out.push_back({"diffuse", std::make_shared<DiffuseBsdf>(Rgb(0.7f))});
  for (MicrofacetModel model : {MicrofacetModel::kBeckmann, MicrofacetModel::kGgx}) {
    for (float alpha : {0.2f, 0.5f, 0.8f}) {
      const std::string name =
          std::string(model == MicrofacetModel::kBeckmann ? "beckmann" : "ggx") +
          " alpha=" + std::to_string(alpha);
      out.push_back({name, std::make_shared<MicrofacetBsdf>(Rgb(0.2f, 0.9f, 1.4f),
                                                            Rgb(3.9f, 2.4f, 2.2f), alpha, model)});
    }
  }
  return out;
}

TEST(IntegratorsBsdf, SamplingMatchesPdfChiSquare) {
  // Incident angles include a grazing one and one below the surface (opaque BSDFs are
  // two-sided).
  const float angles[] = {10.0f, 50.0f, 80.0f, 130.0f};
  size_t tests = 0;
  for (const NamedBsdf& b : glossy_bsdfs()) {
    for (float theta : angles) {
      const Vec3 wo = direction_at(theta);
      const DirectionSampler sampler = [&](float u1, Vec2 u2) -> std::optional<Vec3> {
        const auto s = b.bsdf->sample(wo, u1, u2);
        if (!s) return std::nullopt;
        return s->wi;
      };
      const DirectionPdf pdf = [&](const Vec3& wi) { return double(b.bsdf->pdf(wo, wi)); };
      DirectionalChiSquareOptions options;
      options.seed = 17 + tests;
      const ChiSquareResult r = directional_chi_square(sampler, pdf, options);
      ++tests;
      EXPECT_EQ(r.impossible_observations, 0u) << b.name << " theta_o=" << theta;
      EXPECT_GT(r.p_value, kSignificance) << b.name << " theta_o=" << theta << ": " << r.summary();
    }
  }
  EXPECT_LE(tests, kChiSquareTests / 2);
}

TEST(IntegratorsBsdf, SampleAgreesWithEvalAndPdf) {
  IndependentSampler rng(5);
  for (const NamedBsdf& b : glossy_bsdfs()) {
    for (float theta : {20.0f, 70.0f, 160.0f}) {
      const Vec3 wo = direction_at(theta, 100.0f);
      for (uint32_t i = 0; i < 2000; ++i) {
        rng.start_pixel_sample({0, 0}, i);
        const float u1 = rng.get_1d();
        const auto s = b.bsdf->sample(wo, u1, rng.get_2d());
        if (!s) continue;
        ASSERT_FALSE(s->is_delta());
        ASSERT_NEAR(glm::length(s->wi), 1.0f, 1e-4f);
        const float pdf = b.bsdf->pdf(wo, s->wi);
        ASSERT_NEAR(s->pdf, pdf, 1e-3f * pdf) << b.name;
        const Rgb f = b.bsdf->eval(wo, s->wi);
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(s->f[c], f[c], 1e-3f * f[c] + 1e-7f) << b.name;
        // Reciprocity of the reflection BSDFs.
        const Rgb g = b.bsdf->eval(s->wi, wo);
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(g[c], f[c], 2e-3f * f[c] + 1e-6f) << b.name;
      }
    }
  }
}

/// Mean of f |cos| / pdf over sampled directions, with transmitted samples multiplied by eta^2
/// (the radiance scaling of refraction is not energy lost or gained).
double sampled_albedo(const Bsdf& bsdf, const Vec3& wo, uint32_t n, uint64_t seed,
                      double* max_weight = nullptr) {
  IndependentSampler rng(seed);
  double sum = 0.0, largest = 0.0;
  for (uint32_t i = 0; i < n; ++i) {
    rng.start_pixel_sample({1, 2}, i);
    const float u1 = rng.get_1d();
    const auto s = bsdf.sample(wo, u1, rng.get_2d());
    if (!s) continue;
    double w = double(s->f.g) * std::abs(s->wi.z) / double(s->pdf);
    if (s->is_transmission()) w *= double(s->eta) * double(s->eta);
    sum += w;
    largest = std::max(largest, w);
  }
  if (max_weight) *max_weight = largest;
  return sum / n;
}

// The diffuse lobe's directions: the concentric disk point lifted to the hemisphere, its height
// taken from the map's radius (square_to_cosine_hemisphere()). Known points in each wedge and on
// the diagonals between them, the same disk point as square_to_uniform_disk(), unit length, and
// no jump across a wedge boundary.
TEST(IntegratorsBsdf, CosineHemisphereLiftsTheConcentricDisk) {
  const float h = std::sqrt(0.75f), d = 0.5f * std::sqrt(0.5f);
  const struct {
    Vec2 u;
    Vec3 expected;
  } known[] = {{{0.5f, 0.5f}, {0.0f, 0.0f, 1.0f}},
               {{0.75f, 0.5f}, {0.5f, 0.0f, h}},
               {{0.25f, 0.5f}, {-0.5f, 0.0f, h}},
               {{0.5f, 0.75f}, {0.0f, 0.5f, h}},
               {{0.5f, 0.25f}, {0.0f, -0.5f, h}},
               {{0.75f, 0.75f}, {d, d, h}},
               {{0.25f, 0.75f}, {-d, d, h}},
               {{0.25f, 0.25f}, {-d, -d, h}},
               {{0.75f, 0.25f}, {d, -d, h}},
               {{1.0f, 0.5f}, {1.0f, 0.0f, 0.0f}},
               {{0.75f, 0.625f}, {0.5f * std::cos(kPi / 8.0f), 0.5f * std::sin(kPi / 8.0f), h}}};
  for (const auto& k : known) {
    const Vec3 w = square_to_cosine_hemisphere(k.u);
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(w[a], k.expected[a], 2e-6f) << "u " << k.u.x << " " << k.u.y << " axis " << a;
    }
  }
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (int i = 0; i < 100000; ++i) {
    const Vec2 u(uniform(rng), uniform(rng));
    const Vec3 w = square_to_cosine_hemisphere(u);
    const Vec2 disk = square_to_uniform_disk(u);
    ASSERT_EQ(w.x, disk.x);
    ASSERT_EQ(w.y, disk.y);
    ASSERT_GE(w.z, 0.0f);
    ASSERT_NEAR(glm::length(w), 1.0f, 2e-6f) << "u " << u.x << " " << u.y;
  }
  // Across the diagonal between two wedges, which the map decides by comparing |o.x| and |o.y|.
  for (int i = 1; i < 100; ++i) {
    const float t = 0.5f + 0.5f * float(i) / 100.0f;
    const Vec3 below = square_to_cosine_hemisphere({t, std::nextafter(t, 0.0f)});
    const Vec3 above = square_to_cosine_hemisphere({t, std::nextafter(t, 1.0f)});
    EXPECT_LT(glm::length(above - below), 1e-5f) << "t " << t;
  }
}

TEST(IntegratorsBsdf, WhiteFurnaceLosslessBsdfs) {
  const DiffuseBsdf diffuse(Rgb(1.0f));
  const MirrorBsdf mirror(Rgb(1.0f));
  const GlassBsdf glass(Rgb(1.0f), Rgb(1.0f), 1.5f);
  const RefractionBsdf refraction(Rgb(1.0f), 1.5f);
  for (float theta : {0.0f, 30.0f, 60.0f, 85.0f, 120.0f, 175.0f}) {
    const Vec3 wo = direction_at(theta);
    for (const Bsdf* b : {static_cast<const Bsdf*>(&diffuse), static_cast<const Bsdf*>(&mirror),
                          static_cast<const Bsdf*>(&glass)}) {
      const double albedo = sampled_albedo(*b, wo, 20000, 3);
      EXPECT_GE(albedo, 0.99) << "theta_o=" << theta;
      EXPECT_LE(albedo, 1.01) << "theta_o=" << theta;
    }
    // Refraction only loses exactly the totally internally reflected directions (from inside,
    // beyond the critical angle of asin(1/1.5) = 41.8 degrees off the -z axis).
    const double albedo = sampled_albedo(refraction, wo, 20000, 3);
    const bool tir = theta > 90.0f && (180.0f - theta) > 41.9f;
    EXPECT_NEAR(albedo, tir ? 0.0 : 1.0, 0.01) << "theta_o=" << theta;
  }
}

TEST(IntegratorsBsdf, WhiteFurnaceDiffuseByUniformSampling) {
  // eval() alone, integrated by uniform sphere sampling (not the BSDF's own sampler).
  const DiffuseBsdf diffuse(Rgb(1.0f));
  IndependentSampler rng(9);
  for (float theta : {10.0f, 70.0f, 150.0f}) {
    const Vec3 wo = direction_at(theta);
    double sum = 0.0;
    const uint32_t n = 200000;
    for (uint32_t i = 0; i < n; ++i) {
      rng.start_pixel_sample({0, 1}, i);
      const Vec3 wi = square_to_uniform_sphere(rng.get_2d());
      sum += diffuse.eval(wo, wi).g * std::abs(wi.z) / uniform_sphere_pdf();
    }
    EXPECT_NEAR(sum / n, 1.0, 0.01) << "theta_o=" << theta;
  }
}

TEST(IntegratorsBsdf, WhiteFurnaceMicrofacetNeverGainsEnergy) {
  for (MicrofacetModel model : {MicrofacetModel::kBeckmann, MicrofacetModel::kGgx}) {
    for (float alpha : {0.05f, 0.2f, 0.5f, 1.0f}) {
      const MicrofacetBsdf conductor(Rgb(1.0f), Rgb(kPerfectK), alpha, model);
      for (float theta : {0.0f, 30.0f, 60.0f, 80.0f, 89.0f, 150.0f}) {
        const Vec3 wo = direction_at(theta);
        const double albedo = sampled_albedo(conductor, wo, 20000, 11);
        EXPECT_LE(albedo, 1.01) << "alpha=" << alpha << " theta_o=" << theta;
        // Single scattering loses little energy on smooth surfaces seen from above (GGX's
        // long tail loses ~5% already at alpha = 0.2: its facets reflect below the horizon).
        const float smooth = model == MicrofacetModel::kBeckmann ? 0.2f : 0.05f;
        if (alpha <= smooth && (theta <= 60.0f || theta >= 120.0f)) {
          EXPECT_GE(albedo, 0.95) << "alpha=" << alpha << " theta_o=" << theta;
        }
      }
    }
  }
}

TEST(IntegratorsBsdf, MirrorReflectsExactly) {
  const MirrorBsdf mirror(Rgb(0.5f, 0.6f, 0.7f));
  const Vec3 wo = direction_at(40.0f);
  const auto s = mirror.sample(wo, 0.3f, {0.1f, 0.9f});
  ASSERT_TRUE(s);
  EXPECT_TRUE(s->is_delta());
  EXPECT_NEAR(s->wi.x, -wo.x, 1e-6f);
  EXPECT_NEAR(s->wi.y, -wo.y, 1e-6f);
  EXPECT_NEAR(s->wi.z, wo.z, 1e-6f);
  EXPECT_NEAR(s->f.b * std::abs(s->wi.z) / s->pdf, 0.7f, 1e-6f);
  EXPECT_EQ(mirror.eval(wo, s->wi), Rgb(0.0f));
  EXPECT_EQ(mirror.pdf(wo, s->wi), 0.0f);
  EXPECT_TRUE(mirror.is_delta());
}

TEST(IntegratorsBsdf, GlassChoosesLobesByFresnelAndObeysSnell) {
  const float ior = 1.5f;
  const GlassBsdf glass(Rgb(1.0f), Rgb(1.0f), ior);
  IndependentSampler rng(21);
  for (float theta : {0.0f, 45.0f, 80.0f, 150.0f, 170.0f}) {
    const Vec3 wo = direction_at(theta);
    const double fresnel = fresnel_dielectric(wo.z, ior);
    const uint32_t n = 20000;
    uint32_t reflected = 0;
    for (uint32_t i = 0; i < n; ++i) {
      rng.start_pixel_sample({3, 3}, i);
      const float u1 = rng.get_1d();
      const auto s = glass.sample(wo, u1, rng.get_2d());
      ASSERT_TRUE(s);
      ASSERT_TRUE(s->is_delta());
      if (!s->is_transmission()) {
        ++reflected;
        ASSERT_NEAR(s->wi.z, wo.z, 1e-5f);
        continue;
      }
      ASSERT_LT(s->wi.z * wo.z, 0.0f);
      // Snell: eta_o sin(theta_o) = eta_i sin(theta_i).
      const float eta_o = wo.z > 0.0f ? 1.0f : ior;
      const float eta_i = wo.z > 0.0f ? ior : 1.0f;
      const float sin_o = std::sqrt(std::max(0.0f, 1.0f - wo.z * wo.z));
      const float sin_i = std::sqrt(std::max(0.0f, 1.0f - s->wi.z * s->wi.z));
      ASSERT_NEAR(eta_o * sin_o, eta_i * sin_i, 1e-4f);
      ASSERT_NEAR(s->eta, eta_i / eta_o, 1e-6f);
      // Tangential directions are opposite (the refracted ray continues through).
      ASSERT_LE(s->wi.x * wo.x + s->wi.y * wo.y, 1e-6f);
    }
    // Binomial z test of the reflection frequency against F.
    const double p = double(reflected) / n;
    const double sigma = std::sqrt(std::max(fresnel * (1.0 - fresnel), 1e-12) / n);
    EXPECT_LT(std::abs(p - fresnel), 4.5 * sigma + 1e-9) << "theta_o=" << theta << " F=" << fresnel;
  }
}

TEST(IntegratorsBsdf, TotalInternalReflection) {
  const GlassBsdf glass(Rgb(1.0f), Rgb(1.0f), 1.5f);
  const RefractionBsdf refraction(Rgb(1.0f), 1.5f);
  const Vec3 wo = direction_at(180.0f - 60.0f);  // inside, 60 degrees off the normal
  EXPECT_EQ(fresnel_dielectric(wo.z, 1.5f), 1.0f);
  for (float u : {0.0f, 0.5f, 0.999f}) {
    const auto s = glass.sample(wo, u, {0.5f, 0.5f});
    ASSERT_TRUE(s);
    EXPECT_FALSE(s->is_transmission());
    EXPECT_FALSE(refraction.sample(wo, u, {0.5f, 0.5f}).has_value());
  }
}

TEST(IntegratorsBsdf, FresnelLimits) {
  // Normal incidence on glass: ((1 - 1.5) / (1 + 1.5))^2 = 0.04.
  EXPECT_NEAR(fresnel_dielectric(1.0f, 1.5f), 0.04f, 1e-6f);
  EXPECT_NEAR(fresnel_dielectric(0.0f, 1.5f), 1.0f, 1e-6f);
  // A conductor with k = 0 is a dielectric.
  EXPECT_NEAR(fresnel_conductor(0.7f, Rgb(1.5f), Rgb(0.0f)).r, fresnel_dielectric(0.7f, 1.5f),
              1e-5f);
  // Gold-like values at normal incidence: ((n-1)^2 + k^2) / ((n+1)^2 + k^2).
  const float n = 0.2f, k = 3.0f;
  const float expected = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
  EXPECT_NEAR(fresnel_conductor(1.0f, Rgb(n), Rgb(k)).r, expected, 1e-5f);
}

TEST(IntegratorsBsdf, MicrofacetDistributionsAreNormalised) {
  // Integral of D(h) cos(theta_h) over the hemisphere is 1, and Smith G is in [0, 1].
  for (MicrofacetModel model : {MicrofacetModel::kBeckmann, MicrofacetModel::kGgx}) {
    for (float alpha : {0.1f, 0.4f, 0.9f}) {
      const MicrofacetDistribution d(model, alpha);
      double sum = 0.0;
      const int n = 2000;
      for (int i = 0; i < n; ++i) {
        // Midpoint rule in (cos theta, phi); isotropic, so phi integrates to 2 pi.
        const double z = (i + 0.5) / n;
        const Vec3 h(float(std::sqrt(1.0 - z * z)), 0.0f, float(z));
        sum += double(d.d(h)) * z * (1.0 / n) * 2.0 * 3.141592653589793;
      }
      // GGX has a heavy tail near the horizon: allow for the midpoint rule's error there.
      EXPECT_NEAR(sum, 1.0, 0.01) << int(model) << " alpha=" << alpha;
      for (float theta : {0.0f, 45.0f, 89.0f}) {
        const float g = d.g(direction_at(theta), direction_at(30.0f, 200.0f));
        EXPECT_GE(g, 0.0f);
        EXPECT_LE(g, 1.0f);
      }
    }
  }
}

TEST(IntegratorsBsdf, FactoryBuildsEveryMaterialType) {
  Material m;
  for (MaterialType t :
       {MaterialType::kDiffuse, MaterialType::kMirror, MaterialType::kGlass,
        MaterialType::kRefraction, MaterialType::kMicrofacet, MaterialType::kEmission}) {
    m.type = t;
    const auto b = make_bsdf(m);
    ASSERT_TRUE(b);
    EXPECT_EQ(b->is_black(), t == MaterialType::kEmission);
    EXPECT_EQ(b->is_delta(), t == MaterialType::kMirror || t == MaterialType::kGlass ||
                                 t == MaterialType::kRefraction);
    const Rgb a = material_albedo(m);
    EXPECT_EQ(a, b->albedo());
    // Shading takes the Lambertian BSDF's functions inline by its kind tag: the tag must name
    // the class, or a static_cast would read another class as a DiffuseBsdf.
    EXPECT_EQ(as_diffuse(*b) != nullptr, dynamic_cast<const DiffuseBsdf*>(b.get()) != nullptr);
    EXPECT_EQ(as_diffuse(*b) != nullptr, t == MaterialType::kDiffuse);
  }
  m.type = MaterialType::kGlass;
  m.ior = -1.0f;
  EXPECT_THROW(make_bsdf(m), Error);
}

/// The Lambertian BSDF behind a BSDF of another kind: ShadingPoint reaches it by virtual calls.
class DiffuseByVirtualCalls final : public Bsdf {
 public:
  explicit DiffuseByVirtualCalls(const Rgb& r)
      : Bsdf(kLobeReflection | kLobeDiffuse, false), diffuse_(r) {}
  Rgb eval(const Vec3& wo, const Vec3& wi) const override { return inner().eval(wo, wi); }
  std::optional<BsdfSample> sample(const Vec3& wo, float u_lobe, Vec2 u) const override {
    return inner().sample(wo, u_lobe, u);
  }
  float pdf(const Vec3& wo, const Vec3& wi) const override { return inner().pdf(wo, wi); }
  Rgb albedo() const override { return inner().albedo(); }

 private:
  const Bsdf& inner() const { return diffuse_; }
  DiffuseBsdf diffuse_;
};

TEST(IntegratorsBsdf, ShadingPointTakesTheLambertianBsdfInlineWithTheSameResults) {
  const DiffuseBsdf inline_diffuse(Rgb(0.6f, 0.5f, 0.4f));
  const DiffuseByVirtualCalls virtual_diffuse(Rgb(0.6f, 0.5f, 0.4f));
  ASSERT_TRUE(as_diffuse(inline_diffuse));
  ASSERT_FALSE(as_diffuse(virtual_diffuse));
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (int i = 0; i < 2000; ++i) {
    SurfaceInteraction si;
    si.position = Vec3(unit(rng), unit(rng), unit(rng));
    si.shading_normal = glm::normalize(Vec3(unit(rng), unit(rng), unit(rng)));
    // Geometric normal near the shading one, on its side.
    si.geometric_normal = glm::normalize(si.shading_normal + 0.2f * Vec3(unit(rng), unit(rng), 0));
    Ray ray;
    ray.origin = si.position + glm::normalize(Vec3(unit(rng), unit(rng), unit(rng)));
    ray.direction = si.position - ray.origin;
    const ShadingPoint fast(si, ray, inline_diffuse);
    const ShadingPoint slow(si, ray, virtual_diffuse);
    const Vec2 u(0.5f * (unit(rng) + 1.0f), 0.5f * (unit(rng) + 1.0f));
    const auto a = fast.sample(0.0f, u);
    const auto b = slow.sample(0.0f, u);
    ASSERT_EQ(a.has_value(), b.has_value()) << i;
    const Vec3 w = glm::normalize(Vec3(unit(rng), unit(rng), unit(rng)));
    EXPECT_EQ(fast.eval_cos(w), slow.eval_cos(w)) << i;
    EXPECT_EQ(fast.pdf(w), slow.pdf(w)) << i;
    if (!a) continue;
    EXPECT_EQ(a->f, b->f);
    EXPECT_EQ(a->wi, b->wi);
    EXPECT_EQ(a->pdf, b->pdf);
    EXPECT_EQ(a->lobe, b->lobe);
    EXPECT_EQ(a->eta, b->eta);
    EXPECT_EQ(fast.eval_cos(a->wi), slow.eval_cos(a->wi));
  }
}

TEST(IntegratorsBsdf, ShadingPointSamplesAreUnitDirectionsInTheWorld) {
  // ShadingPoint::sample() does not normalise the world direction again: the BSDFs' local
  // directions and the shading frame must keep it unit to within rounding.
  std::vector<NamedBsdf> bsdfs = glossy_bsdfs();
  bsdfs.push_back({"mirror", std::make_shared<MirrorBsdf>(Rgb(0.9f))});
  bsdfs.push_back({"glass", std::make_shared<GlassBsdf>(Rgb(1.0f), Rgb(1.0f), 1.5f)});
  bsdfs.push_back({"refraction", std::make_shared<RefractionBsdf>(Rgb(1.0f), 1.33f)});
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_real_distribution<float> u01(0.0f, 0x1.fffffep-1f);
  for (const NamedBsdf& b : bsdfs) {
    int sampled = 0;
    for (int i = 0; i < 5000; ++i) {
      SurfaceInteraction si;
      si.shading_normal = glm::normalize(Vec3(unit(rng), unit(rng), unit(rng)));
      si.geometric_normal = si.shading_normal;
      Ray ray;
      ray.direction = glm::normalize(Vec3(unit(rng), unit(rng), unit(rng)));
      const ShadingPoint sp(si, ray, *b.bsdf);
      const auto s = sp.sample(u01(rng), {u01(rng), u01(rng)});
      if (!s) continue;
      ++sampled;
      ASSERT_NEAR(glm::length(s->wi), 1.0f, 1e-6f) << b.name << " " << i;
    }
    EXPECT_GT(sampled, 1000) << b.name;
  }
}

TEST(IntegratorsBsdf, OnlyBsdfsThatReadTheLobeSampleSayTheyDo) {
  // The path integrator skips u_lobe's sampler dimension for a BSDF that does not read it: its
  // samples must then be the same for every u_lobe. Glass, which reads it, must change lobe.
  Material m;
  m.type = MaterialType::kMicrofacet;  // from the factory, as renders build them
  std::vector<NamedBsdf> bsdfs = glossy_bsdfs();
  bsdfs.push_back({"factory microfacet", make_bsdf(m)});
  bsdfs.push_back({"mirror", std::make_shared<MirrorBsdf>(Rgb(0.9f))});
  bsdfs.push_back({"refraction", std::make_shared<RefractionBsdf>(Rgb(1.0f), 1.5f)});
  m.type = MaterialType::kEmission;
  bsdfs.push_back({"emission", make_bsdf(m)});
  for (const NamedBsdf& b : bsdfs) {
    SCOPED_TRACE(b.name);
    EXPECT_FALSE(b.bsdf->reads_lobe_sample());
    for (float theta : {5.0f, 40.0f, 80.0f, 130.0f}) {
      for (Vec2 u : {Vec2(0.1f, 0.7f), Vec2(0.6f, 0.2f), Vec2(0.93f, 0.45f)}) {
        const auto a = b.bsdf->sample(direction_at(theta), 0.05f, u);
        const auto c = b.bsdf->sample(direction_at(theta), 0.95f, u);
        ASSERT_EQ(a.has_value(), c.has_value()) << theta;
        if (!a) continue;
        EXPECT_EQ(a->wi, c->wi) << theta;
        EXPECT_EQ(a->f, c->f) << theta;
        EXPECT_EQ(a->pdf, c->pdf) << theta;
      }
    }
  }
  const GlassBsdf glass(Rgb(1.0f), Rgb(1.0f), 1.5f);
  EXPECT_TRUE(glass.reads_lobe_sample());
  const auto reflected = glass.sample(direction_at(30.0f), 0.0f, Vec2(0.5f));
  const auto refracted = glass.sample(direction_at(30.0f), 0.99f, Vec2(0.5f));
  ASSERT_TRUE(reflected && refracted);
  EXPECT_NE(reflected->lobe, refracted->lobe);
}

}  // namespace
}  // namespace prism
