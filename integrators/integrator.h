#pragma once

#include <cstdint>
#include <memory>
#include <string_view>

#include "accel/accelerator.h"
#include "core/camera.h"
#include "core/film.h"
#include "core/progress.h"
#include "core/registry.h"
#include "core/sampler.h"
#include "core/scene.h"

namespace prism {

/// Everything an integrator reads while rendering. All references outlive render().
struct RenderContext {
  const Scene& scene;  ///< with its environment map, if any
  const Accelerator& accel;
  const Camera& camera;  ///< already fitted to the film's aspect ratio
  const Sampler& sampler_prototype;
  int spp = 1;                           ///< camera rays per pixel (-s)
  int light_samples = 1;                 ///< samples per area light (-l)
  int max_depth = 5;                     ///< maximum ray depth (-m)
  bool hemisphere_sampling = false;      ///< direct light by uniform hemisphere sampling (-H)
  int adaptive_batch = 0;                ///< adaptive sampling batch size, 0 = off (-a B tol)
  float adaptive_tolerance = 0.05f;      ///< adaptive sampling tolerance (-a B tol)
  ProgressReporter* progress = nullptr;  ///< may be null; advanced as progress_total() says
};

/// Produces an image of a scene. Implementations are chosen by name from integrator_registry().
class Integrator {
 public:
  virtual ~Integrator() = default;
  virtual std::string_view name() const = 0;
  /// Renders into `film` (whose size is the output resolution). Deterministic for a given
  /// context: the result does not depend on the number of threads.
  virtual void render(const RenderContext& context, Film& film) const = 0;
  /// Units of progress render() reports for a film of this size (for ProgressReporter).
  virtual uint64_t progress_total(int width, int height, int spp) const;
};

/// Integrators that estimate radiance independently per camera ray: the parallel tile loop,
/// per-thread sampler clones and the camera-ray generation live here; subclasses implement li().
/// The tile loop also runs adaptive sampling (RenderContext::adaptive_batch > 0): after every
/// batch of B samples of a pixel it stops once 1.96 sigma / sqrt(n) <= tolerance * mu for the
/// illuminance (luminance) of the samples taken, as the homework defines it.
class PixelIntegrator : public Integrator {
 public:
  void render(const RenderContext& context, Film& film) const override;
  uint64_t progress_total(int width, int height, int spp) const override;

 protected:
  /// Radiance arriving along `ray` (a camera ray). Called concurrently from many threads.
  virtual Rgb li(const Ray& ray, Sampler& sampler, const RenderContext& context) const = 0;
  /// li() plus the AOVs of the ray's first hit. The default calls li() and traces the ray once
  /// more for the AOVs; integrators that find the first hit anyway override it.
  virtual Rgb li_aov(const Ray& ray, Sampler& sampler, const RenderContext& context,
                     AovSample& aovs) const;
  /// Called by render() on the calling thread before the first li() and after the last one:
  /// subclasses build and drop per-render state there (lights, BSDFs). render() of one
  /// instance must therefore not run concurrently with itself.
  virtual void begin_render(const RenderContext& context) const {}
  virtual void end_render() const {}
};

/// The AOVs (albedo, shading normal, depth) of the first hit of `ray`, by one intersect().
AovSample first_hit_aovs(const Ray& ray, const RenderContext& context);

/// The table of integrators. Parameters use the integrator's name as prefix.
const Registry<Integrator>& integrator_registry();

}  // namespace prism
