#include "integrators/integrator.h"

#include "core/parallel.h"

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

void PixelIntegrator::render(const RenderContext& context, Film& film) const {
  const glm::vec2 film_size(film.width(), film.height());
  parallel_for_tiles(film.width(), film.height(), kTileSize, [&](const Tile& tile) {
    // One sampler per tile: cheap to clone, and its values depend only on (pixel, index).
    const std::unique_ptr<Sampler> sampler = context.sampler_prototype.clone();
    for (int y = tile.begin.y; y < tile.end.y; ++y) {
      for (int x = tile.begin.x; x < tile.end.x; ++x) {
        const glm::ivec2 pixel{x, y};
        for (int s = 0; s < context.spp; ++s) {
          sampler->start_pixel_sample(pixel, uint32_t(s));
          const Vec2 film_position = (Vec2(pixel) + sampler->get_2d()) / film_size;
          const Vec2 lens = sampler->get_2d();
          const Ray ray = context.camera.generate_ray(film_position, lens);
          film.add_sample(pixel, li(ray, *sampler, context));
        }
      }
    }
    if (context.progress) {
      context.progress->update(uint64_t(tile.end.x - tile.begin.x) * (tile.end.y - tile.begin.y));
    }
  });
}

}  // namespace prism
