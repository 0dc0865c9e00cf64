#pragma once

#include <cstdint>
#include <optional>

#include "core/math.h"
#include "core/scene.h"

namespace prism {

/// How a light can be reached, which decides how integrators combine strategies.
enum class LightKind {
  kDelta,     ///< point, spot, directional: only sample_li() finds them
  kSurface,   ///< emissive scene geometry: also found by rays that hit it
  kArea,      ///< a parallelogram emitter that is not scene geometry: only sample_li() finds it
  kInfinite,  ///< surrounds the scene: also found by rays that escape
  /// surrounds the scene, but rays that escape see nothing of it (an ambient light unless
  /// ambient_visible, see LightOptions): only sample_li() finds it
  kHiddenInfinite,
};

/// How sample_li() draws points on an emitter that is a rectangle (MeshLight; LightOptions).
enum class RectangleSampling {
  /// In proportion to a bilinear fit of the density uniform in solid angle (cos / distance^2 at
  /// the corners, Hart et al. 2020): about the solid angle's variance at the cost of a few
  /// square roots.
  kBilinear,
  /// Uniformly in the spherical rectangle's solid angle near the emitter (Urena et al. 2013),
  /// uniformly in area farther away.
  kSolidAngle,
  /// Uniformly in area.
  kArea,
};

/// A direction toward a light from a reference point, from LightSource::sample_li().
struct LightLiSample {
  Rgb li{0.0f};   ///< radiance (or, for delta lights, intensity-derived irradiance factor)
  Vec3 wi{0.0f};  ///< unit, from the reference point toward the light
  /// Solid-angle density of wi; 1 for delta lights (with li the incident irradiance factor).
  float pdf = 0.0f;
  /// Distance to the light point along wi (kInfinity for directional and infinite lights).
  float distance = kInfinity;
};

/// A ray of light leaving an emitter, from LightSource::sample_le().
struct LightLeSample {
  /// The point on the emitter: position, its error bound and, as geometric and shading normal,
  /// the normal of the side it emits from; ready for spawn_ray().
  SurfaceInteraction point;
  Vec3 direction{0.0f};  ///< unit, leaving the emitter on that side
  /// Emitted radiance x cos / (area density x direction density): the ray's weight in an
  /// estimate of the light sent out (its mean over samples is power() for untextured emitters).
  Rgb beta{0.0f};
};

/// A light source in world space. Immutable after construction; thread-safe.
class LightSource {
 public:
  virtual ~LightSource() = default;
  virtual LightKind kind() const = 0;
  /// Draws a direction toward the light from `p` with u in [0,1)^2. Nothing when that sample
  /// carries no light (back side of a one-sided emitter, outside a spot cone, degenerate).
  /// The caller tests visibility.
  virtual std::optional<LightLiSample> sample_li(const Vec3& p, Vec2 u) const = 0;
  /// Solid-angle density with which sample_li(p) yields the ray from `p` that hit this light's
  /// geometry at `light_hit` (kSurface lights only; 0 otherwise).
  virtual float pdf_li(const Vec3& p, const SurfaceInteraction& light_hit) const { return 0.0f; }
  /// Solid-angle density of sample_li() producing direction `w` (kInfinite and
  /// kHiddenInfinite lights only).
  virtual float pdf_li_escaped(const Vec3& w) const { return 0.0f; }
  /// Radiance leaving `light_hit` toward `wo` (kSurface lights only).
  virtual Rgb le(const SurfaceInteraction& light_hit, const Vec3& wo) const { return Rgb(0.0f); }
  /// Radiance arriving along a ray that escapes the scene in direction `w`, were the light
  /// seen (kInfinite and kHiddenInfinite only; integrators ask only kInfinite lights).
  virtual Rgb le_escaped(const Vec3& w) const { return Rgb(0.0f); }
  /// A point on the light and a direction leaving it, cosine-distributed about the normal of
  /// the emitting side (a side chosen with u_direction.x for two-sided emitters), from u_point
  /// and u_direction in [0,1)^2; for light tracing. kSurface lights only: the others return
  /// nothing (light tracing leaves them out).
  virtual std::optional<LightLeSample> sample_le(Vec2 u_point, Vec2 u_direction) const {
    return std::nullopt;
  }
  /// Total emitted power (or a proxy proportional to it), for choosing lights by power.
  virtual Rgb power() const = 0;

  bool is_delta() const { return kind() == LightKind::kDelta; }
  /// Whether a ray that hits scene geometry or escapes can find this light (so that BSDF
  /// sampling competes with light sampling in MIS).
  bool is_hittable() const {
    return kind() == LightKind::kSurface || kind() == LightKind::kInfinite;
  }
};

}  // namespace prism
