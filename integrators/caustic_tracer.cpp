#include "integrators/caustic_tracer.h"

#include <algorithm>
#include <cmath>

#include "integrators/sampling/warp.h"

namespace prism {
namespace {

/// The factor that makes a BSDF written for radiance transport (with shading normal ns and
/// geometric normal ng) carry importance: |wo.ns| |wi.ng| / (|wo.ng| |wi.ns|) (Veach 1997,
/// 5.3), 1 where ns == ng; 0 where a grazing geometric cosine would make it blow up.
float shading_normal_correction(const SurfaceInteraction& si, const Vec3& wo, const Vec3& wi) {
  const float denominator =
      std::abs(glm::dot(wo, si.geometric_normal)) * std::abs(glm::dot(wi, si.shading_normal));
  if (!(denominator > 0.0f)) return 0.0f;
  const float numerator =
      std::abs(glm::dot(wo, si.shading_normal)) * std::abs(glm::dot(wi, si.geometric_normal));
  return numerator / denominator;
}

}  // namespace

CausticTracer::CausticTracer(const RenderContext& context, const ShadingContext& shading,
                             int max_depth, double paths_per_pixel, int width, int height)
    : context_(context),
      shading_(shading),
      camera_(context.camera),
      max_specular_bounces_(max_depth - 1),
      width_(width),
      height_(height),
      paths_(uint32_t(std::clamp(std::llround(paths_per_pixel * double(width) * double(height)),
                                 1LL, (1LL << 31)))),
      pixel_area_(camera_.pixel_area(width, height)),
      sampler_prototype_(context.sampler_prototype.clone()) {
  std::vector<float> powers;
  for (const std::unique_ptr<LightSource>& light : shading.lights.lights()) {
    if (!covers(*light)) continue;
    lights_.push_back(light.get());
    powers.push_back(std::max(0.0f, luminance(light->power())));
  }
  selection_ = DiscreteDistribution(powers);
  sampler_prototype_->set_sample_count(std::max(1, context.spp));
}

bool CausticTracer::applies(const RenderContext& context, const ShadingContext& shading,
                            int max_depth) {
  if (max_depth < 2 || context.camera.lens_radius > 0.0f) return false;
  const bool specular = std::any_of(shading.bsdfs.begin(), shading.bsdfs.end(),
                                    [](const auto& bsdf) { return bsdf && bsdf->is_delta(); });
  const bool light =
      std::any_of(shading.lights.lights().begin(), shading.lights.lights().end(),
                  [](const auto& l) { return covers(*l) && luminance(l->power()) > 0; });
  return specular && light;
}

void CausticTracer::trace(uint32_t sample, uint32_t first, uint32_t last,
                          std::vector<Splat>& out) const {
  if (selection_.empty() || !(selection_.total() > 0.0)) return;
  const std::unique_ptr<Sampler> sampler = sampler_prototype_->clone();
  for (uint32_t path = first; path < last; ++path) {
    sampler->start_pixel_sample({-1 - int(path % 65536u), -1 - int(path / 65536u)}, sample);
    const float u_light = lights_.size() > 1 ? sampler->get_1d() : 0.0f;
    const Vec2 u_point = sampler->get_2d();
    const Vec2 u_direction = sampler->get_2d();
    float pmf = 0.0f;
    const LightSource& light = *lights_[selection_.sample(u_light, &pmf)];
    const std::optional<LightLeSample> le = light.sample_le(u_point, u_direction);
    if (!le || !(pmf > 0.0f)) continue;
    Rgb beta = le->beta / pmf;
    Ray ray = spawn_ray(le->point, le->direction);
    for (int bounces = 0;; ++bounces) {
      const std::optional<Hit> hit = context_.accel.intersect(ray);
      if (!hit) break;
      const SurfaceInteraction si = context_.scene.surface_at(ray, *hit);
      BsdfStorage storage;
      const Bsdf& bsdf = shading_.bsdf_at(si, storage);
      if (bsdf.is_black()) break;
      if (!bsdf.is_delta()) {
        // Light that reaches a surface directly is the path tracer's (light sampling).
        if (bounces > 0) connect(si, bsdf, ray, beta, path, out);
        break;
      }
      if (bounces == max_specular_bounces_) break;
      const ShadingPoint sp(si, ray, bsdf);
      const std::optional<BsdfSample> bs = sp.sample(sampler->get_1d(), sampler->get_2d());
      if (!bs) break;
      // Importance, not radiance, flows along this path: a refraction does not scale it by
      // 1 / eta^2 as the BSDF does for radiance, and shading normals count the other way.
      beta *= bs->f * (std::abs(glm::dot(bs->wi, si.shading_normal)) / bs->pdf) *
              shading_normal_correction(si, sp.wo_world, bs->wi);
      if (bs->is_transmission()) beta *= bs->eta * bs->eta;
      if (!is_finite(beta) || max_component(beta) <= 0.0f) break;
      ray = sp.spawn(bs->wi);
    }
  }
}

void CausticTracer::connect(const SurfaceInteraction& si, const Bsdf& bsdf, const Ray& ray,
                            const Rgb& beta, uint32_t path, std::vector<Splat>& out) const {
  const std::optional<FilmProjection> seen = camera_.project(si.position);
  if (!seen) return;
  // The surface as the camera's ray meets it: wo toward the camera, wi toward the light.
  Ray camera_ray;
  camera_ray.origin = context_.camera.position;
  camera_ray.direction = -seen->to_camera;
  const ShadingPoint sp(si, camera_ray, bsdf);
  const Vec3 to_light = -glm::normalize(ray.direction);
  const Rgb f_cos = sp.eval_cos(to_light);  // f(to camera, to light) |to_light . ns|
  if (max_component(f_cos) <= 0.0f) return;
  const float cos_light_geometric = std::abs(glm::dot(to_light, si.geometric_normal));
  const float cos_camera_geometric = std::abs(glm::dot(seen->to_camera, si.geometric_normal));
  if (!(cos_light_geometric > 0.0f)) return;
  // Camera rays start at the near plane: what lies nearer does not hide the surface.
  if (context_.accel.occluded(spawn_ray_to(si, seen->near_point))) return;
  // Importance of the pixel: 1 / (pixel area x cos^4) per unit film area; with the camera's
  // cos and 1 / distance^2 of the connection it leaves cos^3 (pbrt's PerspectiveCamera::We).
  const float c = seen->cos_view;
  const float weight =
      cos_camera_geometric / (cos_light_geometric * seen->distance * seen->distance * pixel_area_ *
                              c * c * c * float(paths_));
  const Rgb radiance = beta * f_cos * weight;
  if (!is_finite(radiance) || max_component(radiance) <= 0.0f) return;
  const int x = std::min(width_ - 1, int(seen->film.x * float(width_)));
  const int y = std::min(height_ - 1, int(seen->film.y * float(height_)));
  out.push_back(Splat{uint32_t(y) * uint32_t(width_) + uint32_t(x), path, radiance});
}

}  // namespace prism
