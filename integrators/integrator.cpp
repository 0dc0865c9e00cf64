#include "integrators/integrator.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/camera_coverage.h"
#include "core/parallel.h"
#include "integrators/bsdf/bsdf_factory.h"
#include "integrators/light_traced_image.h"
#include "integrators/sampling/warp.h"

namespace prism {
namespace {

/// The tile loop of PixelIntegrator around one estimator.
class PixelTileRenderer final : public TileRenderer {
 public:
  PixelTileRenderer(const RenderContext& context, std::unique_ptr<const PixelEstimator> estimator)
      : context_(context),
        estimator_(std::move(estimator)),
        skip_unseen_(context.skip_unseen_pixels && estimator_->escaping_rays_are_black()),
        scene_bounds_(skip_unseen_ ? context.scene.geometry.bounds() : Bounds3{}) {}

  void render_tile(const Tile& tile, SampleRange range, Film& film) const override;

 private:
  const RenderContext& context_;
  std::unique_ptr<const PixelEstimator> estimator_;
  /// Whether pixels whose camera rays cannot reach scene_bounds_ take their samples untraced.
  const bool skip_unseen_;
  const Bounds3 scene_bounds_;
};

void PixelTileRenderer::render_tile(const Tile& tile, SampleRange range, Film& film) const {
  const RenderContext& context = context_;
  const glm::vec2 film_size(film.width(), film.height());
  const int spp = std::max(1, context.spp);
  const int batch = context.adaptive_batch;
  const double tolerance = context.adaptive_tolerance;
  // One sampler per tile: cheap to clone, and its values depend only on (pixel, index).
  const std::unique_ptr<Sampler> sampler = context.sampler_prototype.clone();
  const CameraRayGenerator camera(context.camera);
  // Adaptive sampling may stop after any batch: the sampler stratifies each batch of samples
  // on its own, so that every prefix the stopping rule can choose is well distributed.
  sampler->set_sample_count(batch > 0 ? std::min(batch, spp) : spp);
  // A pinhole camera reads no lens sample: its two dimensions are skipped, not computed (the
  // path's dimensions stay where they are with a lens).
  const bool lens_sampled = context.camera.uses_lens();
  // The light-traced images of this range's sample indices, fetched when first needed (each
  // pixel of the tile runs through the range).
  const LightTracedImage* light_traced = estimator_->light_traced_image();
  std::vector<std::shared_ptr<const LightTracedSample>> light_images;
  // Where each image's lookups are along the current row (at_in_row()).
  std::vector<LightTracedSample::RowPosition> light_rows;
  if (light_traced && range.last > range.first) {
    light_images.resize(range.last - range.first);
    light_rows.resize(range.last - range.first);
  }
  const auto light_image = [&](uint32_t s) {
    std::shared_ptr<const LightTracedSample>& image = light_images[s - range.first];
    if (!image) image = light_traced->sample(s, range.count());
    return image.get();
  };
  // The samples of one pixel, traced or (outside `seeing`) empty but for the light tracer's.
  const auto take_samples = [&](glm::ivec2 pixel, bool traced, FilmPixel& state) {
    for (uint32_t s = std::max(range.first, state.progress); s < range.last && !state.converged;
         ++s) {
      AovSample aovs;
      Rgb radiance(0.0f);
      const LightTracedSample* light = light_traced ? light_image(s) : nullptr;
      if (traced) {
        sampler->start_pixel_sample(pixel, s);
        const Vec2 film_position = (Vec2(pixel) + sampler->get_2d()) / film_size;
        Vec2 lens(0.0f);
        if (lens_sampled) {
          lens = sampler->get_2d();
        } else {
          sampler->skip_dimensions(2);
        }
        const Ray ray = camera.generate_ray(film_position, lens);
        radiance = light ? estimator_->li_with_light(ray, *sampler, aovs, *light)
                         : estimator_->li(ray, *sampler, aovs);
      }
      if (light) radiance += light->at_in_row(pixel, light_rows[s - range.first]);
      film.add_sample(pixel, radiance, aovs);
      if (batch <= 0) continue;
      // Illuminance sums in double, in sample order: thousands of samples.
      const double illuminance = is_finite(radiance) ? double(luminance(radiance)) : 0.0;
      state.illuminance += illuminance;
      state.illuminance_squared += illuminance * illuminance;
      const uint32_t n = state.samples;
      if (n % uint32_t(batch) != 0 || n < 2) continue;
      const double mean = state.illuminance / n;
      const double variance =
          std::max(0.0, (state.illuminance_squared - state.illuminance * mean) / (n - 1));
      if (1.96 * std::sqrt(variance / n) <= tolerance * mean) state.converged = 1;
    }
    state.progress = std::max(state.progress, range.last);
  };
  // The untraced pixels x0 <= x < x1 of row y. Without adaptive sampling, and when no light
  // path left anything on them, all their samples are empty: they are only counted, as
  // add_sample() counts an empty sample, without a loop over the samples or a look at the
  // rest of their film state (most of the frame at the CS184 framing, every pass).
  const auto take_unseen_samples = [&](int y, int x0, int x1) {
    for (int x = x0; x < x1; ++x) film.prefetch_counts({x, y});
    std::optional<bool> empty;  // found out at the first pixel with samples to take
    for (int x = x0; x < x1; ++x) {
      FilmPixel& state = film.pixel({x, y});
      const uint32_t first = std::max(range.first, state.progress);
      if (first < range.last && !state.converged) {
        if (!empty) {
          empty = batch <= 0;
          for (uint32_t s = range.first; *empty && light_traced && s < range.last; ++s) {
            *empty = light_image(s)->row_is_empty(y, x0, x1);
          }
        }
        if (!*empty) {
          take_samples({x, y}, false, state);
          continue;
        }
        state.samples += range.last - first;
      }
      state.progress = std::max(state.progress, range.last);
    }
  };
  // The pixels whose rays may reach the scene; the others' samples are known without tracing:
  // no radiance (but the light tracer's, which never reaches them either) and no AOVs.
  const PixelRect seeing = skip_unseen_ ? pixels_seeing_bounds(context.camera, scene_bounds_,
                                                               film.width(), film.height())
                                        : PixelRect{{0, 0}, {film.width(), film.height()}};
  for (int y = tile.begin.y; y < tile.end.y; ++y) {
    // The row's traced pixels [traced_begin, traced_end), between untraced ones.
    const bool row_seen = y >= seeing.begin.y && y < seeing.end.y;
    const int traced_begin =
        row_seen ? std::clamp(seeing.begin.x, tile.begin.x, tile.end.x) : tile.end.x;
    const int traced_end =
        row_seen ? std::clamp(seeing.end.x, traced_begin, tile.end.x) : tile.end.x;
    take_unseen_samples(y, tile.begin.x, traced_begin);
    for (int x = traced_begin; x < traced_end; ++x) {
      // With few samples per pass (4 at the default of 64 spp) the next pixel's film state is
      // cold.
      if (x + 1 < traced_end) film.prefetch({x + 1, y});
      take_samples({x, y}, true, film.pixel({x, y}));
    }
    take_unseen_samples(y, traced_end, tile.end.x);
  }
}

}  // namespace

AovSample hit_aovs(const Scene& scene, const Ray& ray, const Hit& hit,
                   const SurfaceInteraction& si) {
  AovSample aovs;
  aovs.normal = si.shading_normal;
  aovs.depth = hit.t * glm::length(ray.direction);
  if (si.material_id < scene.materials.size()) {
    const Material& material = scene.materials[si.material_id];
    aovs.albedo = material_albedo(material);
    if (material.reflectance_texture != kNoTexture && scene.texture_lookup) {
      // Unfiltered: these AOVs belong to the integrators that do not shade.
      const Rgb texel =
          scene.texture_lookup->lookup(material.reflectance_texture, si.uv, Vec2(0.0f), Vec2(0.0f));
      aovs.albedo = glm::clamp(material.reflectance * texel, Rgb(0.0f), Rgb(1.0f));
    }
  }
  return aovs;
}

std::unique_ptr<TileRenderer> PixelIntegrator::start(const RenderContext& context) const {
  return std::make_unique<PixelTileRenderer>(context, prepare(context));
}

void Integrator::render(const RenderContext& context, Film& film) const {
  const std::unique_ptr<const TileRenderer> renderer = start(context);
  const SampleRange all{0, uint32_t(std::max(1, context.spp))};
  const PixelRect& w = film.window();
  parallel_for_tiles(w.width(), w.height(), RenderSchedule::kTileSize, [&](const Tile& local) {
    const Tile tile{local.begin + w.begin, local.end + w.begin};
    renderer->render_tile(tile, all, film);
    if (context.progress) {
      context.progress->update(uint64_t(tile.end.x - tile.begin.x) * (tile.end.y - tile.begin.y));
    }
  });
}

}  // namespace prism
