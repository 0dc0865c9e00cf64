#pragma once

#include <memory>
#include <vector>

#include "integrators/light_traced_image.h"
#include "integrators/light_transport.h"

namespace prism {

/// Light tracing of caustics seen directly: paths leave an emitter, take one or more bounces off
/// purely specular (delta) surfaces, and at the first surface that is not purely specular
/// connect to a pinhole camera, depositing what that surface reflects toward it on the pixel it
/// falls on. A camera path finds the same light only when a BSDF-sampled ray from its first hit
/// happens to pass through the specular chain into the light: the fireflies of a caustic. The
/// path tracer leaves exactly those paths to this tracer (PathIntegrator, `path.caustics`):
/// camera -> first hit whose sampled lobe is not delta -> only purely specular surfaces ->
/// an emitter that covers() (emissive meshes and spheres) -> at most max_depth bounces in all.
///
/// Only paths that meet a specular surface first count, so light paths leave their emitter
/// toward bounding spheres of the specular meshes and spheres (uniform in the cones they
/// subtend, kMaxTargets of them at most, else one around them all) rather than in all
/// directions: the same estimate without the paths that would end on their first hit.
///
/// Its caustic vertices (where those paths land) also serve camera paths: the path tracer
/// connects its first hit to one of them (PathIntegrator) and leaves out the paths that
/// connection carries: camera -> first hit -> a surface at least the connection radius away
/// (sampled lobes not delta at both) -> only purely specular surfaces -> a covered emitter.
///
/// The estimate of sample index s for a pixel is (1 / M) x the sum of the deposits of the M
/// paths of index s on it; each path's sample values are the sampler's for "pixel"
/// (-1 - path % 65536, -1 - path / 65536) at index s, so the estimate is a pure function of s
/// (threads, tiles, crops, resumed and merged renders see the same bits).
class CausticTracer {
 public:
  /// For the render `context` (whose camera and scene must outlive the tracer), shading with
  /// `shading`; paths of at most `max_depth` bounces counted as the path tracer counts them;
  /// `paths_per_pixel` x width x height paths per sample index, at most
  /// LightTracedImage::max_paths(spp) (so that every sample index of the render can stay cached).
  CausticTracer(const RenderContext& context, const ShadingContext& shading, int max_depth,
                double paths_per_pixel, int width, int height);

  /// Whether light tracing can find anything in this render: a pinhole camera, a light that
  /// covers(), a material whose BSDF is purely specular, max_depth >= 2.
  static bool applies(const RenderContext& context, const ShadingContext& shading, int max_depth);
  /// Whether paths ending on `light` are this tracer's (the lights it traces from).
  static bool covers(const LightSource& light) { return light.kind() == LightKind::kSurface; }

  static constexpr size_t kMaxTargets = 32;

  /// Paths per sample index.
  uint32_t paths() const { return paths_; }
  /// Traces paths [first, last) of sample index `sample` and appends their deposits on the
  /// camera and their caustic vertices (those whose light a camera path could still reach with
  /// one more bounce within max_depth).
  void trace(uint32_t sample, uint32_t first, uint32_t last, std::vector<Splat>& out,
             std::vector<CausticVertex>& vertices) const;

 private:
  /// The deposit on the camera of the light path arriving at `si` (not purely specular) along
  /// `ray` with throughput `beta`, if the camera sees si.
  void connect(const SurfaceInteraction& si, const Bsdf& bsdf, const Ray& ray, const Rgb& beta,
               uint32_t path, std::vector<Splat>& out) const;

  /// A sphere around specular geometry: light paths leave the lights toward these only.
  struct Target {
    Vec3 center{0.0f};
    float radius = 0.0f;
  };
  /// A direction from `p` toward the targets, uniform in the cone of one of them (chosen in
  /// proportion to its solid angle, from u_choice; every direction if p is inside), and its
  /// density: (cones containing it) / (their solid angles' sum). Nothing without targets.
  std::optional<std::pair<Vec3, float>> sample_toward_targets(const Vec3& p, float u_choice,
                                                              Vec2 u) const;

  const RenderContext& context_;
  const ShadingContext& shading_;
  const CameraRayGenerator camera_;
  int max_specular_bounces_;
  int width_, height_;
  uint32_t paths_;
  float pixel_area_;
  std::vector<const LightSource*> lights_;  ///< the lights covered, chosen by power
  std::vector<Target> targets_;             ///< around every purely specular mesh and sphere
  DiscreteDistribution selection_;
  std::unique_ptr<Sampler> sampler_prototype_;
};

}  // namespace prism
