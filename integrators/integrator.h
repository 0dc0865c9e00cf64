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

/// Everything an integrator reads while rendering, besides its own parameters. All references
/// outlive render().
struct RenderContext {
  const Scene& scene;  ///< with its environment map, if any
  const Accelerator& accel;
  const Camera& camera;  ///< already fitted to the film's aspect ratio
  const Sampler& sampler_prototype;
  int spp = 1;                           ///< camera rays per pixel (-s)
  int adaptive_batch = 0;                ///< adaptive sampling batch size, 0 = off (-a B tol)
  float adaptive_tolerance = 0.05f;      ///< adaptive sampling tolerance (-a B tol)
  ProgressReporter* progress = nullptr;  ///< may be null; advanced as progress_total() says
};

/// Produces an image of a scene. Implementations are chosen by name from integrator_registry()
/// and hold only the settings read from their parameters: every call of render() builds its
/// own per-render state, so render() of one instance may run concurrently with itself.
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

/// The per-render state of a PixelIntegrator (lights, BSDFs, distances derived from the scene)
/// and the radiance estimate that reads it. Built once per render() by
/// PixelIntegrator::prepare(), read-only while the tiles render: li() is called concurrently
/// from many threads.
class PixelEstimator {
 public:
  virtual ~PixelEstimator() = default;
  /// Radiance arriving along the camera ray `ray`; sets `aovs` (given default-initialised) to
  /// the AOVs of the ray's first hit, left as they are where the ray escapes.
  virtual Rgb li(const Ray& ray, Sampler& sampler, AovSample& aovs) const = 0;
};

/// Integrators that estimate radiance independently per camera ray: the parallel tile loop,
/// per-thread sampler clones and the camera-ray generation live here; subclasses build the
/// PixelEstimator whose li() is called once per camera ray.
/// The tile loop also runs adaptive sampling (RenderContext::adaptive_batch > 0): after every
/// batch of B samples of a pixel it stops once 1.96 sigma / sqrt(n) <= tolerance * mu for the
/// illuminance (luminance) of the samples taken.
class PixelIntegrator : public Integrator {
 public:
  void render(const RenderContext& context, Film& film) const final;
  uint64_t progress_total(int width, int height, int spp) const override;

 protected:
  /// The estimator of one render, with its per-render state built from `context` (which
  /// outlives it). Called once per render() on the calling thread, before the first sample.
  virtual std::unique_ptr<PixelEstimator> prepare(const RenderContext& context) const = 0;
};

/// The AOVs (albedo, shading normal, depth) of the hit `hit` of `ray`, whose surface is `si`.
AovSample hit_aovs(const Scene& scene, const Ray& ray, const Hit& hit,
                   const SurfaceInteraction& si);

/// The table of integrators. Parameters use the integrator's name as prefix.
const Registry<Integrator>& integrator_registry();

}  // namespace prism
