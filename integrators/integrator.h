#pragma once

#include <cstdint>
#include <memory>
#include <string_view>

#include "accel/accelerator.h"
#include "core/camera.h"
#include "core/film.h"
#include "core/progress.h"
#include "core/registry.h"
#include "core/render_schedule.h"
#include "core/sampler.h"
#include "core/scene.h"

namespace prism {

class LightTracedImage;
class LightTracedSample;

/// Everything an integrator reads while rendering, besides its own parameters. All references
/// outlive the render.
struct RenderContext {
  const Scene& scene;        ///< with its environment map, if any
  const Accelerator& accel;  ///< built over scene.geometry
  const Camera& camera;      ///< already fitted to the image's aspect ratio
  const Sampler& sampler_prototype;
  /// Camera rays per pixel of the whole render (-s): samplers stratify over it, whichever
  /// part of the sample range one call renders.
  int spp = 1;
  /// Height of the whole image in pixels, which with the camera's field of view says how wide
  /// a pixel is for texture filtering; 0: textures are looked up without filtering.
  int image_height = 0;
  /// Width of the whole image in pixels (light tracers splat onto it); 0: unknown, no light
  /// tracing.
  int image_width = 0;
  int adaptive_batch = 0;                ///< adaptive sampling batch size, 0 = off (-a B tol)
  float adaptive_tolerance = 0.05f;      ///< adaptive sampling tolerance (-a B tol)
  ProgressReporter* progress = nullptr;  ///< may be null; Integrator::render() advances it
  /// Whether the tile loop fills the pixels whose camera rays cannot reach the scene's bounds
  /// (pixels_seeing_bounds()) with the empty samples they would take, without tracing them,
  /// when the estimator's escaping rays are black: the film is the same bit for bit either
  /// way (tests render both).
  bool skip_unseen_pixels = true;
};

/// The per-render state of an integrator (lights, BSDFs, distances derived from the scene)
/// and the rendering of one unit of work with it. Built once per render by Integrator::start(),
/// read-only afterwards: render_tile() runs concurrently on different tiles.
class TileRenderer {
 public:
  virtual ~TileRenderer() = default;
  /// Takes the samples [range.first, range.last) of every pixel of `tile` (inside
  /// film.window()) in sample order and adds them to `film`. Samples below a pixel's
  /// FilmPixel::progress are already in the film and are skipped, as are pixels adaptive
  /// sampling stopped; every pixel's progress ends at least at range.last. So the film's
  /// content depends only on which samples were taken, never on how the work was cut, ordered,
  /// threaded or resumed.
  virtual void render_tile(const Tile& tile, SampleRange range, Film& film) const = 0;
};

/// Produces an image of a scene. Implementations are chosen by name from integrator_registry()
/// and hold only the settings read from their parameters: every render builds its own
/// per-render state (start()), so one instance may render concurrently with itself.
class Integrator {
 public:
  virtual ~Integrator() = default;
  virtual std::string_view name() const = 0;
  /// The per-render state for `context` (which outlives it), ready to render tiles.
  virtual std::unique_ptr<TileRenderer> start(const RenderContext& context) const = 0;
  /// Renders every sample [0, context.spp) of every pixel of film.window() in one pass of
  /// parallel tiles, advancing context.progress by pixels. Deterministic: the result does not
  /// depend on the number of threads. (`prism render` schedules passes itself.)
  void render(const RenderContext& context, Film& film) const;
};

/// The per-render state of a PixelIntegrator and the radiance estimate that reads it. Built
/// once per render by PixelIntegrator::prepare(); li() is called concurrently from many
/// threads.
class PixelEstimator {
 public:
  virtual ~PixelEstimator() = default;
  /// Radiance arriving along the camera ray `ray`; sets `aovs` (given default-initialised) to
  /// the AOVs of the ray's first hit, left as they are where the ray escapes.
  virtual Rgb li(const Ray& ray, Sampler& sampler, AovSample& aovs) const = 0;
  /// Radiance traced from the lights for this render, added to every camera sample of the
  /// same pixel and sample index (light paths li() leaves to it); null: none.
  virtual const LightTracedImage* light_traced_image() const { return nullptr; }
  /// Whether li() (and li_with_light()) of a camera ray that hits nothing returns exactly 0 and
  /// leaves `aovs` as given, whatever the sampler: then the tile loop need not trace camera rays
  /// that cannot hit the scene. False (the safe default) when something is seen in the
  /// background, such as an environment map.
  virtual bool escaping_rays_are_black() const { return false; }
  /// li() for a camera sample of a render with a light_traced_image(): `light` is that image's
  /// sample of the camera sample's index, whose caustic vertices li() may connect to. The
  /// default ignores it.
  virtual Rgb li_with_light(const Ray& ray, Sampler& sampler, AovSample& aovs,
                            const LightTracedSample& light) const {
    return li(ray, sampler, aovs);
  }
};

/// Integrators that estimate radiance independently per camera ray: the tile loop, per-tile
/// sampler clones and the camera-ray generation live here; subclasses build the
/// PixelEstimator whose li() is called once per camera ray.
/// The tile loop also runs adaptive sampling (RenderContext::adaptive_batch > 0): after every
/// batch of B samples of a pixel it stops the pixel once 1.96 sigma / sqrt(n) <= tolerance * mu
/// for the illuminance (luminance) of the samples taken.
class PixelIntegrator : public Integrator {
 public:
  std::unique_ptr<TileRenderer> start(const RenderContext& context) const final;

 protected:
  /// The estimator of one render, with its per-render state built from `context` (which
  /// outlives it). Called once per start() on the calling thread.
  virtual std::unique_ptr<PixelEstimator> prepare(const RenderContext& context) const = 0;
};

/// The AOVs (albedo, shading normal, depth) of the hit `hit` of `ray`, whose surface is `si`.
AovSample hit_aovs(const Scene& scene, const Ray& ray, const Hit& hit,
                   const SurfaceInteraction& si);

/// The table of integrators. Parameters use the integrator's name as prefix.
const Registry<Integrator>& integrator_registry();

}  // namespace prism
