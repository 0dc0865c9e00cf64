#include "integrators/bsdf/microfacet_bsdf.h"

#include "integrators/bsdf/fresnel.h"

namespace prism {
namespace {

/// wo and wi flipped to the upper hemisphere together: the conductor is two-sided.
Vec3 to_upper(const Vec3& w, bool flip) { return flip ? Vec3(w.x, w.y, -w.z) : w; }

}  // namespace

MicrofacetBsdf::MicrofacetBsdf(const Rgb& eta, const Rgb& k, float alpha, MicrofacetModel model)
    : Bsdf(kLobeReflection | kLobeGlossy, false),
      eta_(eta),
      k_(k),
      distribution_(model, alpha),
      normal_reflectance_(glm::clamp(fresnel_conductor(1.0f, eta, k), Rgb(0.0f), Rgb(1.0f))) {}

Rgb MicrofacetBsdf::eval(const Vec3& wo_in, const Vec3& wi_in) const {
  if (!same_hemisphere(wo_in, wi_in)) return Rgb(0.0f);
  const bool flip = wo_in.z < 0.0f;
  const Vec3 wo = to_upper(wo_in, flip), wi = to_upper(wi_in, flip);
  Vec3 h = wo + wi;
  const float h_length = glm::length(h);
  if (h_length == 0.0f) return Rgb(0.0f);
  h /= h_length;
  const float d = distribution_.d(h);
  if (d == 0.0f) return Rgb(0.0f);
  const Rgb fresnel = fresnel_conductor(glm::dot(wo, h), eta_, k_);
  return fresnel * (d * distribution_.g(wo, wi) / (4.0f * wo.z * wi.z));
}

std::optional<BsdfSample> MicrofacetBsdf::sample(const Vec3& wo_in, float u_lobe, Vec2 u) const {
  if (wo_in.z == 0.0f) return std::nullopt;
  const bool flip = wo_in.z < 0.0f;
  const Vec3 wo = to_upper(wo_in, flip);
  const Vec3 h = distribution_.sample_h(u);
  const float wo_dot_h = glm::dot(wo, h);
  if (wo_dot_h <= 0.0f) return std::nullopt;
  const Vec3 wi = reflect_about(wo, h);
  if (wi.z <= 0.0f) return std::nullopt;
  BsdfSample s;
  s.wi = to_upper(wi, flip);
  s.pdf = distribution_.pdf_h(h) / (4.0f * wo_dot_h);
  if (!(s.pdf > 0.0f)) return std::nullopt;
  s.f = eval(wo_in, s.wi);
  s.lobe = kLobeReflection | kLobeGlossy;
  return s;
}

float MicrofacetBsdf::pdf(const Vec3& wo_in, const Vec3& wi_in) const {
  if (!same_hemisphere(wo_in, wi_in)) return 0.0f;
  const bool flip = wo_in.z < 0.0f;
  const Vec3 wo = to_upper(wo_in, flip), wi = to_upper(wi_in, flip);
  Vec3 h = wo + wi;
  const float h_length = glm::length(h);
  if (h_length == 0.0f) return 0.0f;
  h /= h_length;
  const float wo_dot_h = glm::dot(wo, h);
  if (wo_dot_h <= 0.0f) return 0.0f;
  return distribution_.pdf_h(h) / (4.0f * wo_dot_h);
}

}  // namespace prism
