#include "integrators/caustic_tracer.h"

#include <algorithm>
#include <cmath>

#include "integrators/sampling/frame.h"
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
      paths_(uint32_t(
          std::clamp(std::llround(paths_per_pixel * double(width) * double(height)), 1LL,
                     (long long)LightTracedImage::max_paths(uint32_t(std::max(1, context.spp)))))),
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
  // Spheres around the specular geometry, a little enlarged against rounding.
  const SceneGeometry& geometry = context.scene.geometry;
  const auto specular = [&](uint32_t material) {
    return material < shading.bsdfs.size() && shading.bsdfs[material] &&
           shading.bsdfs[material]->is_delta();
  };
  Bounds3 all;
  for (const TriangleMesh& mesh : geometry.meshes) {
    if (!specular(mesh.material_id) || mesh.triangles.empty()) continue;
    const Bounds3 b = mesh.bounds();
    targets_.push_back({0.5f * (b.lower + b.upper), 0.5f * glm::length(b.upper - b.lower)});
    all.extend(b);
  }
  for (const Sphere& sphere : geometry.spheres) {
    if (!specular(sphere.material_id)) continue;
    targets_.push_back({sphere.center, sphere.radius});
    all.extend(sphere.bounds());
  }
  if (targets_.size() > kMaxTargets) {
    targets_ = {{0.5f * (all.lower + all.upper), 0.5f * glm::length(all.upper - all.lower)}};
  }
  for (Target& t : targets_) {
    t.radius = t.radius * 1.001f + 1e-4f * max_component(abs_components(t.center));
  }
}

std::optional<std::pair<Vec3, float>> CausticTracer::sample_toward_targets(const Vec3& p,
                                                                           float u_choice,
                                                                           Vec2 u) const {
  float cos_max[kMaxTargets];
  float solid_angle[kMaxTargets];
  Vec3 axis[kMaxTargets];
  float total = 0.0f;
  const size_t n = targets_.size();
  for (size_t k = 0; k < n; ++k) {
    const Vec3 v = targets_[k].center - p;
    const float d2 = glm::dot(v, v);
    const float r2 = targets_[k].radius * targets_[k].radius;
    if (d2 <= r2 || !(d2 > 0.0f)) {
      cos_max[k] = -1.0f;  // inside: every direction
      axis[k] = Vec3(0.0f, 0.0f, 1.0f);
    } else {
      cos_max[k] = std::sqrt(std::max(0.0f, 1.0f - r2 / d2));
      axis[k] = v / std::sqrt(d2);
    }
    solid_angle[k] = 2.0f * kPi * (1.0f - cos_max[k]);
    total += solid_angle[k];
  }
  if (!(total > 0.0f)) return std::nullopt;
  size_t k = 0;
  for (float below = 0.0f; k + 1 < n && below + solid_angle[k] <= u_choice * total; ++k) {
    below += solid_angle[k];
  }
  if (!(solid_angle[k] > 0.0f)) return std::nullopt;
  const float cos_theta = 1.0f - u.x * (1.0f - cos_max[k]);
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  const float phi = 2.0f * kPi * u.y;
  const Vec3 w = glm::normalize(Frame::from_z(axis[k]).to_world(
      Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta)));
  int containing = 0;
  for (size_t j = 0; j < n; ++j) containing += glm::dot(w, axis[j]) >= cos_max[j] ? 1 : 0;
  if (containing == 0) return std::nullopt;  // rounding at a cone's rim
  return std::make_pair(w, float(containing) / total);
}

bool CausticTracer::applies(const RenderContext& context, const ShadingContext& shading,
                            int max_depth) {
  if (max_depth < 2 || context.camera.uses_lens()) return false;
  const bool specular = std::any_of(shading.bsdfs.begin(), shading.bsdfs.end(),
                                    [](const auto& bsdf) { return bsdf && bsdf->is_delta(); });
  const bool light =
      std::any_of(shading.lights.lights().begin(), shading.lights.lights().end(),
                  [](const auto& l) { return covers(*l) && luminance(l->power()) > 0; });
  return specular && light;
}

void CausticTracer::trace(uint32_t sample, uint32_t first, uint32_t last, std::vector<Splat>& out,
                          std::vector<CausticVertex>& vertices) const {
  if (selection_.empty() || !(selection_.total() > 0.0)) return;
  const std::unique_ptr<Sampler> sampler = sampler_prototype_->clone();
  for (uint32_t path = first; path < last; ++path) {
    sampler->start_pixel_sample({-1 - int(path % 65536u), -1 - int(path / 65536u)}, sample);
    const float u_light = lights_.size() > 1 ? sampler->get_1d() : 0.0f;
    const Vec2 u_point = sampler->get_2d();
    const Vec2 u_direction = sampler->get_2d();
    const Vec2 u_side_and_target = sampler->get_2d();
    float pmf = 0.0f;
    const LightSource& light = *lights_[selection_.sample(u_light, &pmf)];
    // The emitter's point and side; its cosine-distributed direction is replaced by one toward
    // the targets: beta = Le cos / (pdf_area pdf_direction), and sample_le()'s beta is
    // Le pi / pdf_area.
    const std::optional<LightLeSample> le =
        light.sample_le(u_point, Vec2(u_side_and_target.x, 0.5f));
    if (!le || !(pmf > 0.0f)) continue;
    const auto toward = sample_toward_targets(le->point.position, u_side_and_target.y, u_direction);
    if (!toward) continue;
    const float cos_light = glm::dot(toward->first, le->point.geometric_normal);
    if (!(cos_light > 0.0f)) continue;
    Rgb beta = le->beta * (cos_light / (kPi * toward->second * pmf));
    Ray ray = spawn_ray(le->point, toward->first);
    for (int bounces = 0;; ++bounces) {
      const std::optional<Hit> hit = context_.accel.intersect(ray);
      if (!hit) break;
      const SurfaceInteraction si = context_.scene.surface_at(ray, *hit);
      BsdfStorage storage;
      const Bsdf& bsdf = shading_.bsdf_at(si, storage);
      if (bsdf.is_black()) break;
      if (!bsdf.is_delta()) {
        // Light that reaches a surface directly is the path tracer's (light sampling).
        if (bounces > 0) {
          connect(si, bsdf, ray, beta, path, out);
          // Camera paths reach it with one bounce more: within max_depth?
          if (bounces < max_specular_bounces_) {
            vertices.push_back(CausticVertex{si, -glm::normalize(ray.direction), beta, bounces});
          }
        }
        break;
      }
      if (bounces == max_specular_bounces_) break;
      const ShadingPoint sp(si, ray, bsdf);
      const std::optional<BsdfSample> bs = sp.sample(sp.lobe_sample(*sampler), sampler->get_2d());
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
