#pragma once

#include <cstdint>
#include <optional>

#include "core/math.h"

namespace prism {

/// Kinds of scattering a BSDF has, combined as bit flags.
enum BsdfLobe : uint32_t {
  kLobeNone = 0,
  kLobeReflection = 1u << 0,
  kLobeTransmission = 1u << 1,
  kLobeDiffuse = 1u << 2,
  kLobeGlossy = 1u << 3,
  kLobeSpecular = 1u << 4,  ///< a Dirac delta lobe: eval() and pdf() never see it
};

/// One direction drawn by Bsdf::sample().
struct BsdfSample {
  /// The BSDF value. For a delta lobe it is the lobe's weight divided by |cos theta_i|, so that
  /// f * |wi.z| / pdf is the path throughput factor in every case.
  Rgb f{0.0f};
  Vec3 wi{0.0f, 0.0f, 1.0f};  ///< local frame, unit, pointing away from the surface
  /// Solid-angle density of wi; for a delta lobe, the discrete probability of choosing it.
  float pdf = 0.0f;
  uint32_t lobe = kLobeNone;  ///< the one lobe that produced wi
  /// Relative index of refraction crossed by a transmitted direction (eta of the side of wi over
  /// eta of the side of wo); 1 for reflection. Transmitted radiance is divided by eta^2.
  float eta = 1.0f;

  bool is_delta() const { return (lobe & kLobeSpecular) != 0; }
  bool is_transmission() const { return (lobe & kLobeTransmission) != 0; }
};

/// A BSDF in its local shading frame: z is the shading normal, wo and wi point away from the
/// surface (wo toward the viewer, wi toward the light). Both hemispheres are meaningful: an
/// opaque BSDF reflects on whichever side wo is. Values are radiance-transport BSDFs (the
/// 1 / eta^2 scaling of transmitted radiance is included). Immutable and thread-safe.
class Bsdf {
 public:
  /// Which BSDF this is, where callers take one kind's functions inline (ShadingPoint does for
  /// the Lambertian BSDF of most surfaces, without a virtual call at every bounce).
  enum class Kind : uint8_t { kDiffuse, kOther };

  virtual ~Bsdf() = default;
  /// f(wo, wi) of the non-delta lobes; zero for delta lobes and impossible pairs.
  virtual Rgb eval(const Vec3& wo, const Vec3& wi) const = 0;
  /// Draws wi given wo from `u_lobe` in [0,1) (lobe choice) and `u` in [0,1)^2. Nothing when
  /// no direction carries energy (total internal reflection of a refraction-only BSDF, grazing
  /// wo, an emitter).
  virtual std::optional<BsdfSample> sample(const Vec3& wo, float u_lobe, Vec2 u) const = 0;
  /// Solid-angle density with which sample() draws wi given wo (non-delta lobes only).
  virtual float pdf(const Vec3& wo, const Vec3& wi) const = 0;
  /// The lobes present. Fixed per BSDF (a member, not a virtual call: paths ask at every bounce).
  uint32_t lobes() const { return lobes_; }
  /// Whether sample() reads `u_lobe` (a choice between lobes). When it does not, a caller may
  /// skip that sampler dimension instead of computing a value nobody reads.
  bool reads_lobe_sample() const { return reads_lobe_sample_; }
  /// What this BSDF is (as_diffuse() reads it).
  Kind kind() const { return kind_; }
  /// A colour in [0,1]^3 that describes the surface (the albedo AOV).
  virtual Rgb albedo() const = 0;

  /// True when every lobe is a delta: light sampling cannot help, only sample() can.
  bool is_delta() const {
    const uint32_t l = lobes();
    return l != kLobeNone && (l & (kLobeDiffuse | kLobeGlossy)) == 0;
  }
  /// True when there is no scattering at all (emitters).
  bool is_black() const { return lobes() == kLobeNone; }

 protected:
  Bsdf(uint32_t lobes, bool reads_lobe_sample, Kind kind = Kind::kOther)
      : lobes_(lobes), reads_lobe_sample_(reads_lobe_sample), kind_(kind) {}

 private:
  uint32_t lobes_;
  bool reads_lobe_sample_;
  Kind kind_;
};

inline bool same_hemisphere(const Vec3& a, const Vec3& b) { return a.z * b.z > 0.0f; }
inline float abs_cos_theta(const Vec3& w) { return std::abs(w.z); }

/// Mirror direction of `wo` about the local z axis.
inline Vec3 reflect_z(const Vec3& wo) { return {-wo.x, -wo.y, wo.z}; }
/// Mirror direction of `wo` about the unit vector `n`.
inline Vec3 reflect_about(const Vec3& wo, const Vec3& n) { return 2.0f * glm::dot(wo, n) * n - wo; }

/// Refracts `wi` (pointing away from the surface, on the side of the unit normal `n`) into the
/// other medium; `eta` is eta of the other side over eta of wi's side. False on total internal
/// reflection.
bool refract(const Vec3& wi, const Vec3& n, float eta, Vec3* wt);

}  // namespace prism
