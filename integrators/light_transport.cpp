#include "integrators/light_transport.h"

#include <cmath>

#include "core/error.h"
#include "integrators/sampling/warp.h"

namespace prism {

LightTransportSettings::LightTransportSettings(const std::string& name, const ParamSet& params)
    : light_samples(
          int(params.get_int(name + ".light_samples", kDefaultLightSamples, 1, kMaxLightSamples))),
      hemisphere(params.get_bool(name + ".hemisphere", false)) {
  lights.ambient_visible = params.get_bool(name + ".ambient_visible", false);
  lights.two_sided_emitters = params.get_bool(name + ".two_sided_emitters", false);
  const std::string rectangles = params.get_string(name + ".rectangle_sampling", "bilinear");
  if (rectangles == "bilinear") {
    lights.rectangle_sampling = RectangleSampling::kBilinear;
  } else if (rectangles == "solid_angle") {
    lights.rectangle_sampling = RectangleSampling::kSolidAngle;
  } else if (rectangles == "area") {
    lights.rectangle_sampling = RectangleSampling::kArea;
  } else {
    throw Error(ErrorKind::kUsage,
                "bad value '" + rectangles + "' for " + name +
                    ".rectangle_sampling; expected bilinear, solid_angle or area");
  }
  const std::string model = params.get_string(name + ".microfacet", "beckmann");
  if (model == "beckmann") {
    bsdf.microfacet = MicrofacetModel::kBeckmann;
  } else if (model == "ggx") {
    bsdf.microfacet = MicrofacetModel::kGgx;
  } else {
    throw Error(ErrorKind::kUsage,
                "bad value '" + model + "' for " + name + ".microfacet; expected beckmann or ggx");
  }
}

ShadingContext::ShadingContext(const Scene& scene_in, const BsdfOptions& bsdf_options_in,
                               const LightOptions& light_options, const TextureFilter& filter)
    : scene(scene_in),
      bsdf_options(bsdf_options_in),
      textures(scene_in, filter),
      bsdfs(make_bsdfs(scene_in.materials, bsdf_options_in)),
      lights(scene_in, light_options, &textures) {}

const Bsdf& ShadingContext::bsdf_at(const SurfaceInteraction& si, BsdfStorage& storage) const {
  const Material& material = scene.materials[si.material_id];
  if (material.reflectance_texture == kNoTexture) return *bsdfs[si.material_id];
  return make_bsdf_with_reflectance(material, textures.reflectance(material, si), bsdf_options,
                                    storage);
}

TextureFilter texture_filter_of(const RenderContext& context) {
  return camera_texture_filter(context.camera, context.image_height, context.spp);
}

float ShadingPoint::lobe_sample(Sampler& sampler) const {
  if (bsdf->reads_lobe_sample()) return sampler.get_1d();
  sampler.skip_dimensions(1);
  return 0.0f;
}

Ray ShadingPoint::spawn(const Vec3& wi_world) const { return spawn_ray(si, wi_world); }

bool ShadingPoint::unoccluded(const Accelerator& accel, const Vec3& wi_world,
                              float distance) const {
  if (!std::isfinite(distance)) return !accel.occluded(spawn_ray(si, wi_world));
  // Aim at the light point itself from the offset origin and stop just short of it.
  return !accel.occluded(spawn_ray_to(si, si.position + distance * wi_world));
}

Rgb emitted_radiance(const SurfaceInteraction& si, const Ray& ray, const ShadingContext& shading) {
  const LightSource* light = shading.lights.surface_light(si);
  if (!light) return Rgb(0.0f);
  return light->le(si, -glm::normalize(ray.direction));
}

Rgb estimate_direct_lights(const ShadingPoint& sp, Sampler& sampler, const RenderContext& context,
                           const ShadingContext& shading, int light_samples) {
  Rgb sum(0.0f);
  const int area_samples = std::max(1, light_samples);
  for (const auto& light : shading.lights.lights()) {
    const int n = light->is_delta() ? 1 : area_samples;
    Rgb light_sum(0.0f);
    for (int i = 0; i < n; ++i) {
      const Vec2 u = sampler.get_2d();
      const std::optional<LightLiSample> ls = light->sample_li(sp.si.position, u);
      if (!ls || !(ls->pdf > 0.0f)) continue;
      const Rgb f = sp.eval_cos(ls->wi);
      if (max_component(f) <= 0.0f) continue;
      if (!sp.unoccluded(context.accel, ls->wi, ls->distance)) continue;
      light_sum += f * ls->li / ls->pdf;
    }
    sum += light_sum / float(n);
  }
  return sum;
}

Rgb estimate_direct_hemisphere(const ShadingPoint& sp, Sampler& sampler,
                               const RenderContext& context, const ShadingContext& shading,
                               int light_samples) {
  const int n = std::max(1, light_samples) * std::max<int>(1, int(shading.lights.size()));
  const float side = sp.wo.z < 0.0f ? -1.0f : 1.0f;
  Rgb sum(0.0f);
  for (int i = 0; i < n; ++i) {
    Vec3 wi = square_to_uniform_hemisphere(sampler.get_2d());
    wi.z *= side;
    const Vec3 wi_world = glm::normalize(sp.frame.to_world(wi));
    const Rgb f = sp.eval_cos(wi_world);
    if (max_component(f) <= 0.0f) continue;
    const Ray ray = sp.spawn(wi_world);
    const std::optional<Hit> hit = context.accel.intersect(ray);
    Rgb le(0.0f);
    if (hit) {
      le = emitted_radiance(context.scene.surface_at(ray, *hit), ray, shading);
    } else {
      le = shading.lights.le_escaped(wi_world);
    }
    sum += f * le / uniform_hemisphere_pdf();
  }
  return sum / float(n);
}

}  // namespace prism
