#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/param_set.h"
#include "integrators/bsdf/bsdf.h"
#include "integrators/bsdf/bsdf_factory.h"
#include "integrators/bsdf/diffuse_bsdf.h"
#include "integrators/integrator.h"
#include "integrators/integrator_defaults.h"
#include "integrators/lights/light_set.h"
#include "integrators/sampling/frame.h"
#include "integrators/surface_textures.h"

namespace prism {

/// The settings every light-transport integrator reads from its parameters (prefix `<name>.`):
/// - microfacet: beckmann (default) or ggx;
/// - light_samples (default kDefaultLightSamples, in [1, kMaxLightSamples]; -l): samples per
///   non-delta light of the one-bounce estimators, or hemisphere rays per light;
/// - hemisphere (default false; -H): the one-bounce estimate by uniform hemisphere sampling;
/// - ambient_visible (default false): ambient lights are a sky that escaping rays see (camera
///   rays and bounces, MIS-weighted), not only lights found by light sampling (LightOptions);
/// - two_sided_emitters (default false; --two-sided-emitters): emitters lit on both sides;
/// - rectangle_sampling (default bilinear; solid_angle or area): how points are drawn on
///   rectangular emitters (RectangleSampling).
struct LightTransportSettings {
  /// Throws Error(kUsage) naming the key on a bad value.
  LightTransportSettings(const std::string& name, const ParamSet& params);
  BsdfOptions bsdf;
  LightOptions lights;
  int light_samples;
  bool hemisphere;
};

/// Per-render shading state of the light-transport integrators: one BSDF per material, the
/// texture lookups and the scene's lights. Built once per render from the Scene (which must
/// outlive it), read-only afterwards. `filter` says how wide a pixel is for texture filtering
/// (camera_texture_filter(); the default filters nothing).
struct ShadingContext {
  ShadingContext(const Scene& scene, const BsdfOptions& bsdf_options,
                 const LightOptions& light_options, const TextureFilter& filter = {});
  /// The BSDF at `si`: its material's shared one, or for a material with a reflectance
  /// texture one built in `storage` from the texture there (untextured materials cost nothing
  /// more than before). Valid as long as `storage` and this context.
  const Bsdf& bsdf_at(const SurfaceInteraction& si, BsdfStorage& storage) const;

  const Scene& scene;
  BsdfOptions bsdf_options;
  SurfaceTextures textures;
  std::vector<std::unique_ptr<Bsdf>> bsdfs;  ///< per material
  LightSet lights;
};

/// The filter of the render `context` describes (camera_texture_filter()).
TextureFilter texture_filter_of(const RenderContext& context);

/// A surface hit ready for shading: the shading frame from the shading normal, the BSDF, and
/// wo. World-space helpers apply the leak check with the geometric normal: a direction pair is
/// treated as reflection or transmission by its sides of the geometric surface, and a BSDF
/// lobe that disagrees contributes nothing.
struct ShadingPoint {
  /// `surface` must outlive the shading point, which refers to it rather than copying it (a copy
  /// of the surface just returned by Scene::surface_at() reloads it in blocks that do not match
  /// the stores that wrote it: a store-forwarding stall at every vertex).
  ShadingPoint(const SurfaceInteraction& surface, const Ray& ray, const Bsdf& scattering)
      : si(surface),
        frame(Frame::from_z(surface.shading_normal)),
        bsdf(&scattering),
        wo_world(-glm::normalize(ray.direction)),
        wo(frame.to_local(wo_world)) {}
  ShadingPoint(SurfaceInteraction&&, const Ray&, const Bsdf&) = delete;

  const SurfaceInteraction& si;
  Frame frame;
  const Bsdf* bsdf;
  Vec3 wo_world;  ///< unit, toward the previous vertex
  Vec3 wo;        ///< wo_world in the shading frame

  // eval_cos(), pdf() and sample() run at every vertex of every path: defined below, inline,
  // and with the Lambertian BSDF's functions inline too (as_diffuse()), not by virtual calls.

  /// f(wo, wi) |cos theta_i| for a unit world direction wi (0 where the leak check fails).
  Rgb eval_cos(const Vec3& wi_world) const;
  /// BSDF sampling density of the unit world direction wi.
  float pdf(const Vec3& wi_world) const;
  /// A BSDF sample with wi in world space (unit to within 1e-6); nothing when it fails or fails
  /// the leak check.
  std::optional<BsdfSample> sample(float u_lobe, Vec2 u) const;
  /// Whether the world-space pair (wo, wi) is a reflection with respect to the geometric normal
  /// and agrees with the same classification in the shading frame (wi_local: wi_world there).
  bool sides_agree(const Vec3& wi_world, const Vec3& wi_local) const;
  /// The next value of `sampler` for sample()'s u_lobe when the BSDF reads it; otherwise its
  /// dimension is skipped, not computed (later dimensions keep their values) and 0 returned.
  float lobe_sample(Sampler& sampler) const;
  /// A ray leaving the surface along the unit world direction `wi`.
  Ray spawn(const Vec3& wi_world) const;
  /// Whether nothing blocks the segment to the point `distance` along wi (kInfinity: the ray
  /// escapes the scene).
  bool unoccluded(const Accelerator& accel, const Vec3& wi_world, float distance) const;
};

inline bool ShadingPoint::sides_agree(const Vec3& wi_world, const Vec3& wi_local) const {
  const float geometric =
      glm::dot(wo_world, si.geometric_normal) * glm::dot(wi_world, si.geometric_normal);
  const float shading = wo.z * wi_local.z;
  return (geometric > 0.0f) == (shading > 0.0f) && geometric != 0.0f && shading != 0.0f;
}

inline Rgb ShadingPoint::eval_cos(const Vec3& wi_world) const {
  const Vec3 wi = frame.to_local(wi_world);
  if (!sides_agree(wi_world, wi)) return Rgb(0.0f);
  const DiffuseBsdf* diffuse = as_diffuse(*bsdf);
  return (diffuse ? diffuse->eval(wo, wi) : bsdf->eval(wo, wi)) * std::abs(wi.z);
}

inline float ShadingPoint::pdf(const Vec3& wi_world) const {
  const Vec3 wi = frame.to_local(wi_world);
  if (!sides_agree(wi_world, wi)) return 0.0f;
  const DiffuseBsdf* diffuse = as_diffuse(*bsdf);
  return diffuse ? diffuse->pdf(wo, wi) : bsdf->pdf(wo, wi);
}

inline std::optional<BsdfSample> ShadingPoint::sample(float u_lobe, Vec2 u) const {
  // One object returned on every path (built where the caller wants it), filled field by field:
  // a copy of `s` with wi replaced is made in 16-byte blocks straight after the new wi is stored
  // in pieces, and each such load would wait until the stores it spans have reached the cache
  // (no store-to-load forwarding).
  std::optional<BsdfSample> out;
  const DiffuseBsdf* diffuse = as_diffuse(*bsdf);
  const std::optional<BsdfSample> s =
      diffuse ? diffuse->sample(wo, u_lobe, u) : bsdf->sample(wo, u_lobe, u);
  if (s && s->pdf > 0.0f) {
    // Unit to within a few ulps (a unit local direction in an orthonormal frame), so not
    // normalised again: that square root and division sat on each bounce's chain of dependent
    // operations, which the next ray waits for.
    const Vec3 wi_world = frame.to_world(s->wi);
    if (sides_agree(wi_world, s->wi)) {
      out.emplace();
      out->f = s->f;
      out->wi = wi_world;
      out->pdf = s->pdf;
      out->lobe = s->lobe;
      out->eta = s->eta;
    }
  }
  return out;
}

/// Light arriving at `sp` directly from the lights, by light importance sampling: every light,
/// `light_samples` samples for each non-delta light and one for each delta light.
Rgb estimate_direct_lights(const ShadingPoint& sp, Sampler& sampler, const RenderContext& context,
                           const ShadingContext& shading, int light_samples);

/// Light arriving at `sp` directly from emitters, by uniform hemisphere sampling (on wo's side):
/// light_samples x (number of lights, at least 1) rays; light arrives only from emissive
/// geometry hit and, on escape, from the infinite lights escaping rays see (so not from delta,
/// CGL area or hidden ambient lights, as in the homework's hemisphere estimator).
Rgb estimate_direct_hemisphere(const ShadingPoint& sp, Sampler& sampler,
                               const RenderContext& context, const ShadingContext& shading,
                               int light_samples);

/// Radiance emitted toward the previous vertex by the surface at `si` hit by `ray` (0 unless
/// it is an emissive-surface light).
Rgb emitted_radiance(const SurfaceInteraction& si, const Ray& ray, const ShadingContext& shading);

}  // namespace prism
