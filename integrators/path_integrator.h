#pragma once

#include "integrators/light_transport.h"

namespace prism {

/// Unidirectional path tracing with next-event estimation. Parameters (prefix "path."):
/// - max_depth (default kDefaultMaxDepth, in [0, kMaxDepth]; -m): the most bounces a path
///   takes.
/// - mis (default true): light sampling and BSDF sampling combined by multiple importance
///   sampling (power heuristic), lights chosen by power, light_samples NEE samples per vertex;
///   false gives the estimator without MIS: at every vertex the one-bounce estimate of
///   every light (or by hemisphere sampling with hemisphere=true), emission found by
///   BSDF-sampled rays counted only after specular bounces.
/// - accumulate (default true): the sum of bounces 0..max_depth; false gives only bounce
///   max_depth (light that scattered exactly max_depth times).
/// - rr (default true), rr_depth (default 3, or 1 with rr_probability), rr_probability
///   (default 0: continuation probability from the path throughput; in (0,1]: that fixed
///   continuation probability), rr_threshold (default kDefaultRrThreshold, in [1e-6, 1]) and
///   rr_sqrt (default true): the continuation probability from the throughput is
///   min(1, sqrt(max component / rr_threshold)), so no path ends while its throughput is at
///   least rr_threshold (rr_threshold 1 is Cycles' rule); rr_sqrt false: min(1, max component /
///   rr_threshold), which ends more paths. Ending fewer costs work and saves variance; the
///   defaults are the most efficient measured on the Cornell boxes (docs/PERFORMANCE.md).
/// - caustics (default true): caustics seen directly (light from an emissive mesh or sphere,
///   off one or more purely specular surfaces, onto the camera's first hit) are light-traced
///   (CausticTracer) instead of left to the rare BSDF-sampled camera path that finds them;
///   applies with mis, accumulate and without hemisphere, to pinhole cameras of scenes with a
///   specular material, max_depth >= 2.
/// - caustic_paths (default kDefaultCausticPaths, in [2^-20, 64]): light paths per pixel of the
///   whole image per sample index (at most LightTracedImage::max_paths(spp), so that a render's
///   light-traced samples fit 1 GiB).
/// - caustic_radius (default kDefaultCausticRadius, in [0, 1], a fraction of the diagonal of
///   the scene's bounds): with caustics, the camera's first hit also connects to one caustic
///   vertex of its sample index (where a light path landed after specular bounces) at least
///   this far away, and the camera paths that would find that light through a second surface
///   that far away are left out; nearer pairs stay with the camera paths (a connection's
///   1 / distance^2 would make fireflies of them).
/// - caustic_connections (default kDefaultCausticConnections, in [2^-20, 1]): the probability
///   that a first hit makes that connection (weighted by its inverse; the paths it covers stay
///   left out either way): each connection costs a shadow ray and two BSDF evaluations, and
///   CBspheres' error barely depends on how many are made (docs/PERFORMANCE.md).
/// - microfacet, light_samples, hemisphere, ambient_visible, two_sided_emitters: see
///   LightTransportSettings.
class PathIntegrator final : public PixelIntegrator {
 public:
  /// Everything the estimator reads from the parameters.
  struct Settings {
    explicit Settings(const ParamSet& params);
    LightTransportSettings light_transport;
    int max_depth;
    bool mis;
    bool accumulate;
    bool russian_roulette;
    float rr_probability;
    int rr_depth;
    bool rr_sqrt;
    float rr_threshold;
    bool caustics;
    double caustic_paths;
    double caustic_radius;
    float caustic_connections;
  };

  static constexpr double kDefaultCausticPaths = 0.02;
  static constexpr double kDefaultRrThreshold = 0.25;
  static constexpr double kDefaultCausticRadius = 0.05;
  static constexpr double kDefaultCausticConnections = 0.25;

  explicit PathIntegrator(const ParamSet& params);
  std::string_view name() const override { return "path"; }

 protected:
  std::unique_ptr<PixelEstimator> prepare(const RenderContext& context) const override;

 private:
  Settings settings_;
};

}  // namespace prism
