#include "integrators/path_integrator.h"

#include <algorithm>
#include <cmath>

#include "integrators/caustic_tracer.h"
#include "integrators/light_traced_image.h"
#include "integrators/sampling/warp.h"

namespace prism {

PathIntegrator::Settings::Settings(const ParamSet& params)
    : light_transport("path", params),
      max_depth(int(params.get_int("path.max_depth", kDefaultMaxDepth, 0, kMaxDepth))),
      mis(params.get_bool("path.mis", true)),
      accumulate(params.get_bool("path.accumulate", true)),
      russian_roulette(params.get_bool("path.rr", true)),
      rr_probability(float(params.get_float("path.rr_probability", 0.0, 0.0, 1.0))),
      rr_depth(int(params.get_int("path.rr_depth", rr_probability > 0.0f ? 1 : 3, 0, 1 << 20))),
      rr_sqrt(params.get_bool("path.rr_sqrt", true)),
      rr_threshold(float(params.get_float("path.rr_threshold", kDefaultRrThreshold, 1e-6, 1.0))),
      caustics(params.get_bool("path.caustics", true)),
      caustic_paths(params.get_float("path.caustic_paths", kDefaultCausticPaths, 0x1p-20, 64.0)),
      caustic_radius(params.get_float("path.caustic_radius", kDefaultCausticRadius, 0.0, 1.0)),
      caustic_connections(float(params.get_float("path.caustic_connections",
                                                 kDefaultCausticConnections, 0x1p-20, 1.0))) {}

namespace {

/// Draws the sampler values of one light sample, in this order: `u_light` chooses the light (no
/// value, and no sampler dimension, with a single light); `u_point` is the point on it, chained
/// to the pair sampled before it (the direction that led here, or the film position at the first
/// hit): one stratified point for both (Sampler::get_2d_chained()). Into scalars, not a struct:
/// built in memory, one is reloaded in pieces that do not match its stores.
void draw_light_sample(const ShadingContext& shading, Sampler& sampler, float& u_light,
                       Vec2& u_point) {
  u_light = shading.lights.size() > 1 ? sampler.get_1d() : 0.0f;
  u_point = sampler.get_2d_chained();
}

class PathEstimator final : public PixelEstimator {
 public:
  PathEstimator(const RenderContext& context, const PathIntegrator::Settings& settings, int width,
                int height)
      : context_(context),
        settings_(settings),
        shading_(context.scene, settings.light_transport.bsdf, settings.light_transport.lights,
                 texture_filter_of(context)) {
    if (settings.caustics && settings.mis && settings.accumulate &&
        !settings.light_transport.hemisphere && width > 0 && height > 0 &&
        CausticTracer::applies(context, shading_, settings.max_depth)) {
      caustics_ = std::make_unique<CausticTracer>(context, shading_, settings.max_depth,
                                                  settings.caustic_paths, width, height);
      light_traced_ = std::make_unique<LightTracedImage>(
          [tracer = caustics_.get()](uint32_t sample, uint32_t first, uint32_t last,
                                     std::vector<Splat>& out,
                                     std::vector<CausticVertex>& vertices) {
            tracer->trace(sample, first, last, out, vertices);
          },
          caustics_->paths(), width, height);
      const Bounds3 bounds = context.scene.geometry.bounds();
      const float diagonal = glm::length(bounds.upper - bounds.lower);
      connection_radius_ =
          std::isfinite(diagonal) ? float(settings.caustic_radius) * diagonal : 0.0f;
    }
  }

  Rgb li(const Ray& camera_ray, Sampler& sampler, AovSample& aovs) const override {
    return li_paths(camera_ray, sampler, aovs, nullptr);
  }
  Rgb li_with_light(const Ray& camera_ray, Sampler& sampler, AovSample& aovs,
                    const LightTracedSample& light) const override {
    return li_paths(camera_ray, sampler, aovs, &light);
  }
  const LightTracedImage* light_traced_image() const override { return light_traced_.get(); }
  /// An escaping ray sees the infinite lights only.
  bool escaping_rays_are_black() const override {
    return shading_.lights.infinite_lights().empty();
  }

 private:
  /// Light arriving at `sp` from one light chosen by power, MIS-weighted against BSDF
  /// sampling; averaged over light_samples samples.
  Rgb sample_lights_mis(const ShadingPoint& sp, Sampler& sampler) const;
  /// One such sample from its sampler values (draw_light_sample()), as one of light_samples.
  Rgb light_sample_mis(const ShadingPoint& sp, float u_light, Vec2 u_point) const;
  /// The path tracing estimate along `camera_ray`; with `traced` (the light-traced sample of this
  /// camera sample's index), the caustics li() leaves to the light tracer are left out and the
  /// first hit connects to one of its caustic vertices.
  Rgb li_paths(const Ray& camera_ray, Sampler& sampler, AovSample& aovs,
               const LightTracedSample* traced) const;
  /// Light of the caustic vertex `v` of `light` (LightTracedSample::choose_vertex()) reflected
  /// at the camera's first hit `sp` toward the camera, as an estimate of what all of its paths
  /// bring there from vertices at least connection_radius_ away. `bounces`: the camera path's
  /// bounces before `sp` (its specular chain); vertices whose whole path would pass max_depth
  /// bring nothing, as camera paths that long stop first.
  Rgb connect_caustic_vertex(const ShadingPoint& sp, int bounces, const LightTracedSample& light,
                             const CausticVertex& v) const;

  const RenderContext& context_;
  const PathIntegrator::Settings settings_;
  const ShadingContext shading_;
  std::unique_ptr<CausticTracer> caustics_;  ///< null when light tracing does not apply
  std::unique_ptr<LightTracedImage> light_traced_;
  float connection_radius_ = 0.0f;  ///< world units
};

Rgb PathEstimator::sample_lights_mis(const ShadingPoint& sp, Sampler& sampler) const {
  const int n = std::max(1, settings_.light_transport.light_samples);
  Rgb sum(0.0f);
  for (int i = 0; i < n; ++i) {
    float u_light;
    Vec2 u_point;
    draw_light_sample(shading_, sampler, u_light, u_point);
    sum += light_sample_mis(sp, u_light, u_point);
  }
  return sum / float(n);
}

Rgb PathEstimator::light_sample_mis(const ShadingPoint& sp, float u_light, Vec2 u_point) const {
  const float n = float(std::max(1, settings_.light_transport.light_samples));
  float pmf = 0.0f;
  const LightSource* light = shading_.lights.sample(u_light, &pmf);
  if (!light || !(pmf > 0.0f)) return Rgb(0.0f);
  const std::optional<LightLiSample> ls = light->sample_li(sp.si.position, u_point);
  if (!ls || !(ls->pdf > 0.0f)) return Rgb(0.0f);
  const Rgb f = sp.eval_cos(ls->wi);
  if (max_component(f) <= 0.0f) return Rgb(0.0f);
  if (!sp.unoccluded(context_.accel, ls->wi, ls->distance)) return Rgb(0.0f);
  const float light_pdf = pmf * ls->pdf;
  // Only lights that BSDF-sampled rays can find compete with BSDF sampling.
  const float weight =
      light->is_hittable() ? power_heuristic(n, light_pdf, 1.0f, sp.pdf(ls->wi)) : 1.0f;
  return f * ls->li * (weight / light_pdf);
}

Rgb PathEstimator::connect_caustic_vertex(const ShadingPoint& sp, int bounces,
                                          const LightTracedSample& light,
                                          const CausticVertex& v) const {
  // The camera path would find the light after bounces + 2 + v.specular_bounces bounces (the
  // light tracer keeps only vertices within max_depth for bounces = 0).
  if (bounces + 2 + v.specular_bounces > settings_.max_depth) return Rgb(0.0f);
  const Vec3 d = v.si.position - sp.si.position;
  const float distance = glm::length(d);
  // Nearer pairs are the camera paths' (li_paths()).
  if (!(distance >= connection_radius_) || !(distance > 0.0f)) return Rgb(0.0f);
  const Vec3 w = d / distance;
  const Rgb f_here = sp.eval_cos(w);  // f(to camera, w) |w . ns|
  if (max_component(f_here) <= 0.0f) return Rgb(0.0f);
  // The vertex's surface as seen from here: wo toward here, wi toward its light.
  BsdfStorage storage;
  const Bsdf& bsdf = shading_.bsdf_at(v.si, storage);
  Ray arriving;
  arriving.origin = sp.si.position;
  arriving.direction = w;
  const ShadingPoint there(v.si, arriving, bsdf);
  const Rgb f_there = there.eval_cos(v.to_light);  // f(-w, to light) |to_light . ns|
  if (max_component(f_there) <= 0.0f) return Rgb(0.0f);
  const float cos_light_geometric = std::abs(glm::dot(v.to_light, v.si.geometric_normal));
  if (!(cos_light_geometric > 0.0f)) return Rgb(0.0f);
  // Importance flows into the vertex: |w . ng| / |to_light . ng| replaces the shading cosine
  // of its BSDF (the adjoint's shading-normal correction, as CausticTracer).
  const float geometry =
      std::abs(glm::dot(w, v.si.geometric_normal)) / (cos_light_geometric * distance * distance);
  const Vec3 target =
      offset_ray_origin(v.si.position, v.si.position_error, v.si.geometric_normal, -w);
  if (context_.accel.occluded(spawn_ray_to(sp.si, target))) return Rgb(0.0f);
  // One of the n vertices of light.paths() paths, chosen uniformly: x n / paths.
  const float pick = float(light.vertices().size()) / float(light.paths());
  const Rgb contribution = v.beta * f_here * f_there * (geometry * pick);
  return is_finite(contribution) ? contribution : Rgb(0.0f);
}

Rgb PathEstimator::li_paths(const Ray& camera_ray, Sampler& sampler, AovSample& aovs,
                            const LightTracedSample* traced) const {
  const RenderContext& context = context_;
  const ShadingContext& shading = shading_;
  const int light_samples = settings_.light_transport.light_samples;
  const bool accumulate = settings_.accumulate;
  const int max_depth = std::max(0, settings_.max_depth);
  const float nee_samples = float(std::max(1, light_samples));
  Rgb radiance(0.0f);
  // Adds light that scattered `bounces` times before reaching the camera.
  const auto add = [&](const Rgb& contribution, int bounces) {
    if (accumulate || bounces == max_depth) radiance += contribution;
  };

  Ray ray = camera_ray;
  Rgb beta(1.0f);
  float eta_scale = 1.0f;  // radiance scaling by refraction, undone for Russian roulette
  bool specular = true;    // the camera "bounce" counts as specular: emission seen in full
  float bsdf_pdf = 0.0f;
  Vec3 previous_position = ray.origin;
  // How far the path follows what the light tracer carries (with `traced`): kNone; from a first
  // hit whose sampled lobe is not delta (kFromFirstHit) through one or more purely specular
  // surfaces only (kCaustic: the caustic seen directly); or from such a first hit to a second
  // surface at least connection_radius_ away whose sampled lobe is not delta
  // (kFromSecondHit), then through purely specular surfaces only (kConnectedCaustic: the
  // connection to a caustic vertex). Emitters it covers, found in kCaustic or
  // kConnectedCaustic, are its. The "first hit" is the first surface whose BSDF is not purely
  // specular: one seen in a mirror or through glass connects to caustic vertices too (its
  // connection carries the specular chain's throughput), but the caustic seen directly there
  // stays the camera path's, since the light tracer reaches the camera only in a straight line.
  enum class Caustic {
    kNone,
    kFromFirstHit,
    kCaustic,
    kFromSecondHit,
    kConnectedCaustic
  } caustic = Caustic::kNone;
  Vec3 first_hit{0.0f};
  // Bounces before the first hit: -1 until it is found, above 0 when it is seen in a mirror or
  // through glass.
  int first_hit_bounces = -1;
  for (int bounces = 0;; ++bounces) {
    const std::optional<Hit> hit = context.accel.intersect(ray);
    if (!hit) {
      const auto& infinite_lights = shading.lights.infinite_lights();
      if (infinite_lights.empty()) break;
      const Vec3 w = glm::normalize(ray.direction);
      for (const LightSource* light : infinite_lights) {
        const Rgb le = light->le_escaped(w);
        if (max_component(le) <= 0.0f) continue;
        if (specular) {
          add(beta * le, bounces);
        } else if (settings_.mis) {
          const float light_pdf =
              shading.lights.pmf(shading.lights.index_of(light)) * light->pdf_li_escaped(w);
          add(beta * le * power_heuristic(1.0f, bsdf_pdf, nee_samples, light_pdf), bounces);
        }
      }
      break;
    }
    const SurfaceInteraction si = context.scene.surface_at(ray, *hit);
    BsdfStorage bsdf_storage;
    const Bsdf& bsdf = shading.bsdf_at(si, bsdf_storage);
    if (bounces == 0) {
      aovs.albedo = bsdf.albedo();
      aovs.normal = si.shading_normal;
      aovs.depth = hit->t * glm::length(ray.direction);
    }
    if (const LightSource* emitter = shading.lights.surface_light(si);
        emitter && !((caustic == Caustic::kCaustic || caustic == Caustic::kConnectedCaustic) &&
                     CausticTracer::covers(*emitter))) {
      const Rgb le = emitter->le(si, -glm::normalize(ray.direction));
      if (max_component(le) > 0.0f) {
        if (specular) {
          add(beta * le, bounces);
        } else if (settings_.mis) {
          const float light_pdf = shading.lights.pmf(shading.lights.index_of(emitter)) *
                                  emitter->pdf_li(previous_position, si);
          add(beta * le * power_heuristic(1.0f, bsdf_pdf, nee_samples, light_pdf), bounces);
        }
      }
    }
    if (bounces >= max_depth || bsdf.is_black()) break;

    const ShadingPoint sp(si, ray, bsdf);
    // Light sampling (next-event estimation) at this vertex, then the next direction by BSDF
    // sampling, whose sampler values follow the light sample's.
    const bool nee = !bsdf.is_delta() && (accumulate || bounces + 1 == max_depth);
    // One light sample (the default): its values drawn, then the BSDF sample taken before the
    // light's is evaluated, so that the two chains of dependent square roots and divisions
    // overlap in the processor instead of the BSDF's waiting for the shadow ray. The same values
    // and operations: the same image.
    const bool one_light_sample = nee && settings_.mis && light_samples <= 1;
    Rgb direct(0.0f);
    float u_light = 0.0f;
    Vec2 u_light_point(0.0f);
    // The caustic vertex the first hit connects to, chosen first so that it loads meanwhile.
    // Made with probability caustic_connections: the same sampler value decides and, rescaled,
    // chooses the vertex.
    const CausticVertex* vertex = nullptr;
    if (nee) {
      if (traced && first_hit_bounces < 0) {
        const float u = sampler.get_1d();
        const float p = settings_.caustic_connections;
        if (u < p) vertex = traced->choose_vertex(std::min(u / p, 0x1.fffffep-1f));
      }
      if (one_light_sample) {
        draw_light_sample(shading, sampler, u_light, u_light_point);
      } else if (settings_.mis) {
        direct = sample_lights_mis(sp, sampler);
      } else if (settings_.light_transport.hemisphere) {
        direct = estimate_direct_hemisphere(sp, sampler, context, shading, light_samples);
      } else {
        direct = estimate_direct_lights(sp, sampler, context, shading, light_samples);
      }
    }
    // The first vertex's direction begins a fresh point (chained to the film position it
    // measured worse: relMSE +12% on CBbunny); later ones continue the path's chain. Built in
    // place, not assigned: a copy of the sample is made in 16-byte blocks straight after its
    // fields are stored one by one, and each such load waits for the stores it spans (no
    // store-to-load forwarding).
    const float u_lobe = sp.lobe_sample(sampler);
    const std::optional<BsdfSample> bs =
        sp.sample(u_lobe, bounces == 0 ? sampler.get_2d() : sampler.get_2d_chained());
    if (nee) {
      if (one_light_sample) direct = light_sample_mis(sp, u_light, u_light_point);
      add(beta * direct, bounces + 1);
      if (vertex) {
        add(beta * connect_caustic_vertex(sp, bounces, *traced, *vertex) *
                (1.0f / settings_.caustic_connections),
            bounces + 2);
      }
    }

    if (!bs) break;
    beta *= bs->f * (std::abs(glm::dot(bs->wi, si.shading_normal)) / bs->pdf);
    if (bs->is_transmission()) eta_scale *= bs->eta * bs->eta;
    specular = bs->is_delta();
    if (traced) {
      if (first_hit_bounces < 0) {
        if (!bsdf.is_delta()) {  // else still before the first hit
          caustic = specular ? Caustic::kNone : Caustic::kFromFirstHit;
          first_hit = si.position;
          first_hit_bounces = bounces;
        }
      } else if (bsdf.is_delta()) {
        if (caustic == Caustic::kFromFirstHit) {
          caustic = first_hit_bounces > 0 ? Caustic::kNone : Caustic::kCaustic;
        }
        if (caustic == Caustic::kFromSecondHit) caustic = Caustic::kConnectedCaustic;
      } else if (caustic == Caustic::kFromFirstHit && bounces == first_hit_bounces + 1 &&
                 !specular && glm::length(si.position - first_hit) >= connection_radius_) {
        caustic = Caustic::kFromSecondHit;
      } else {
        caustic = Caustic::kNone;
      }
    }
    bsdf_pdf = bs->pdf;
    previous_position = si.position;
    ray = sp.spawn(bs->wi);
    if (!is_finite(beta) || max_component(beta) <= 0.0f) break;

    if (settings_.russian_roulette && bounces + 1 >= settings_.rr_depth) {
      float q = settings_.rr_probability;
      if (!(q > 0.0f)) {
        const float m = max_component(beta * eta_scale) / settings_.rr_threshold;
        q = std::min(1.0f, settings_.rr_sqrt ? std::sqrt(m) : m);
      }
      if (q < 1.0f) {
        if (sampler.get_1d() >= q) break;
        beta /= q;
      }
    }
  }
  return radiance;
}

}  // namespace

PathIntegrator::PathIntegrator(const ParamSet& params) : settings_(params) {}

std::unique_ptr<PixelEstimator> PathIntegrator::prepare(const RenderContext& context) const {
  return std::make_unique<PathEstimator>(context, settings_, context.image_width,
                                         context.image_height);
}

}  // namespace prism
