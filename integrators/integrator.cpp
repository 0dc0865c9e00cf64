#include "integrators/integrator.h"

#include <cmath>

#include "core/parallel.h"
#include "integrators/bsdf/bsdf_factory.h"
#include "integrators/sampling/warp.h"

namespace prism {
namespace {

constexpr int kTileSize = 16;

}  // namespace

uint64_t Integrator::progress_total(int width, int height, int spp) const {
  return uint64_t(height);
}

uint64_t PixelIntegrator::progress_total(int width, int height, int spp) const {
  return uint64_t(width) * uint64_t(height);
}

AovSample hit_aovs(const Scene& scene, const Ray& ray, const Hit& hit,
                   const SurfaceInteraction& si) {
  AovSample aovs;
  aovs.normal = si.shading_normal;
  aovs.depth = hit.t * glm::length(ray.direction);
  if (si.material_id < scene.materials.size()) {
    aovs.albedo = material_albedo(scene.materials[si.material_id]);
  }
  return aovs;
}

void PixelIntegrator::render(const RenderContext& context, Film& film) const {
  const std::unique_ptr<const PixelEstimator> estimator = prepare(context);
  const glm::vec2 film_size(film.width(), film.height());
  const int spp = std::max(1, context.spp);
  const int batch = context.adaptive_batch;
  const float tolerance = context.adaptive_tolerance;
  parallel_for_tiles(film.width(), film.height(), kTileSize, [&](const Tile& tile) {
    // One sampler per tile: cheap to clone, and its values depend only on (pixel, index).
    const std::unique_ptr<Sampler> sampler = context.sampler_prototype.clone();
    // Adaptive sampling may stop after any batch: the sampler stratifies each batch of samples
    // on its own, so that every prefix the stopping rule can choose is well distributed.
    sampler->set_sample_count(batch > 0 ? std::min(batch, spp) : spp);
    for (int y = tile.begin.y; y < tile.end.y; ++y) {
      for (int x = tile.begin.x; x < tile.end.x; ++x) {
        const glm::ivec2 pixel{x, y};
        // Illuminance sums for adaptive sampling, in double: thousands of samples.
        double s1 = 0.0, s2 = 0.0;
        for (int s = 0; s < spp; ++s) {
          sampler->start_pixel_sample(pixel, uint32_t(s));
          const Vec2 film_position = (Vec2(pixel) + sampler->get_2d()) / film_size;
          const Vec2 lens = sampler->get_2d();
          const Ray ray = context.camera.generate_ray(film_position, lens);
          AovSample aovs;
          const Rgb radiance = estimator->li(ray, *sampler, aovs);
          film.add_sample(pixel, radiance, aovs);
          if (batch <= 0) continue;
          const double illuminance = is_finite(radiance) ? double(luminance(radiance)) : 0.0;
          s1 += illuminance;
          s2 += illuminance * illuminance;
          const int n = s + 1;
          if (n % batch != 0 || n < 2) continue;
          const double mean = s1 / n;
          const double variance = std::max(0.0, (s2 - s1 * s1 / n) / (n - 1));
          if (1.96 * std::sqrt(variance / n) <= double(tolerance) * mean) break;
        }
      }
    }
    if (context.progress) {
      context.progress->update(uint64_t(tile.end.x - tile.begin.x) * (tile.end.y - tile.begin.y));
    }
  });
}

}  // namespace prism
