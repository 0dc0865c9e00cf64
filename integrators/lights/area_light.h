#pragma once

#include <vector>

#include "core/light.h"
#include "core/scene.h"
#include "integrators/lights/light_source.h"
#include "integrators/sampling/distribution.h"
#include "integrators/sampling/spherical_rectangle.h"
#include "integrators/surface_textures.h"

namespace prism {

/// A texture that multiplies an emitter's radiance: none when `textures` is null.
struct EmissionTexture {
  uint32_t texture = kNoTexture;
  const SurfaceTextures* textures = nullptr;

  explicit operator bool() const { return textures != nullptr; }
};

/// The CGL area light: a one-sided parallelogram of radiance `color` emitting along
/// `direction` (both ways when `two_sided`), not part of the scene geometry (no ray ever hits
/// it). Sampled uniformly in area.
class ParallelogramLight final : public LightSource {
 public:
  ParallelogramLight(const Light& light, bool two_sided);
  LightKind kind() const override { return LightKind::kArea; }
  std::optional<LightLiSample> sample_li(const Vec3& p, Vec2 u) const override;
  Rgb power() const override;

 private:
  Rgb radiance_;
  Vec3 corner_, edge_u_, edge_v_;
  Vec3 normal_;  ///< emitting side (the front, when two-sided)
  float area_;
  bool two_sided_;
};

/// An emissive triangle mesh as one area light: diffuse emission of `radiance` on the side of
/// each triangle's geometric normal as Scene::surface_at() orients it, or on both sides when
/// `two_sided`. With a `texture`, the radiance at a point is `radiance` times the texture
/// there: filtered where a ray hits the mesh, unfiltered at points light sampling draws; the
/// power is based on the texture's mean. Sampling (not by the texture's brightness):
/// - meshes of at most kSolidAngleTriangles triangles (the quads of Cornell boxes): a triangle
///   is chosen in proportion to an estimate of its solid angle at the reference point (0 for
///   triangles seen from a side that does not emit). A triangle close to the point (its longest
///   edge longer than its plane's distance, Cycles' rule) is weighted by its exact solid angle
///   and sampled uniformly in it (Arvo's spherical triangles), unless that solid angle lies
///   outside [kMinSphericalSolidAngle, kMaxSphericalSolidAngle]; a triangle farther away is
///   weighted by area x cos / distance^2 at its centroid and sampled uniformly in area, which
///   is nearly as good there and much cheaper.
/// - a rectangle of two triangles without a texture (every CS184 light): as one rectangle (the
///   two triangles' choice left out), by `rectangle_sampling`: by default in proportion to a
///   bilinear fit of the density uniform in solid angle (solid_angle_corners()); or as the
///   triangles are, with its diagonal as the longest edge: uniformly in its solid angle
///   (SphericalRectangle) when the point is close and that solid angle is in
///   [kMinSphericalRectangleSolidAngle, kMaxSphericalSolidAngle], uniformly in its area
///   otherwise; or uniformly in its area. The bilinear fit has less variance than the solid
///   angle in the Cornell boxes for about a tenth of the time per sample (docs/PERFORMANCE.md,
///   "bilinear").
/// - larger meshes: a triangle by area and a point uniformly on it.
class MeshLight final : public LightSource {
 public:
  MeshLight(const TriangleMesh& mesh, const Rgb& radiance, bool two_sided,
            EmissionTexture texture = {},
            RectangleSampling rectangle_sampling = RectangleSampling::kBilinear);
  LightKind kind() const override { return LightKind::kSurface; }
  std::optional<LightLiSample> sample_li(const Vec3& p, Vec2 u) const override;
  float pdf_li(const Vec3& p, const SurfaceInteraction& light_hit) const override;
  Rgb le(const SurfaceInteraction& light_hit, const Vec3& wo) const override;
  /// A triangle by area, a point uniformly on it.
  std::optional<LightLeSample> sample_le(Vec2 u_point, Vec2 u_direction) const override;
  Rgb power() const override;
  float area() const { return area_; }
  /// Whether the mesh is sampled as one rectangle (see the class comment).
  bool is_rectangle() const { return rectangle_.has_value(); }

  static constexpr size_t kSolidAngleTriangles = 8;
  static constexpr float kMinSphericalSolidAngle = 3e-4f;
  static constexpr float kMaxSphericalSolidAngle = 6.22f;
  /// A rectangle's solid angle is a sum of four angles less 2 pi, within 6.4e-7 of the exact
  /// value in float (IntegratorsSphericalRectangle.SolidAngleIsTheTwoTrianglesSum): from this
  /// size on, its relative error is below 0.07%; smaller ones are sampled in area.
  static constexpr float kMinSphericalRectangleSolidAngle = 1e-3f;

 private:
  /// Per triangle, its weight in the choice of a triangle from `p` (small meshes, see the
  /// class comment), and in `spherical` whether it is sampled in solid angle (its weight is
  /// then its solid angle); returns the sum of the weights.
  float triangle_weights(const Vec3& p, float* weights, bool* spherical) const;
  /// The two triangles of `mesh_` as one rectangle (see the class comment), or nothing.
  std::optional<Rectangle> as_rectangle() const;
  /// Whether the rectangle is sampled in solid angle from `p`, at a distance `side` from its
  /// plane: then `spherical` is set up and its solid angle is in the spherical range.
  bool rectangle_in_solid_angle(const Vec3& p, float side,
                                std::optional<SphericalRectangle>& spherical) const;
  /// The radiance at barycentrics `b` of triangle `i` (the texture looked up unfiltered).
  Rgb radiance_at(size_t i, Vec2 b) const;

  /// The sample toward point `q` (barycentrics `b`) of triangle `i`, with area density pdf_area
  /// there, or an explicit solid-angle density `pdf_solid_angle` when that is > 0.
  std::optional<LightLiSample> toward_triangle_point(const Vec3& p, size_t i, const Vec3& q, Vec2 b,
                                                     float pdf_area, float pdf_solid_angle) const;

  const TriangleMesh& mesh_;
  Rgb radiance_;
  EmissionTexture texture_;
  DiscreteDistribution triangles_;
  std::vector<Vec3> normals_;           ///< per triangle: unit emitting-side normal (the front)
  std::vector<Vec3> centroids_;         ///< per triangle (small meshes)
  std::vector<float> longest_edge2_;    ///< per triangle: squared longest edge (small meshes)
  std::optional<Rectangle> rectangle_;  ///< the mesh as one rectangle, when it is one
  float area_ = 0.0f;
  bool two_sided_;
  RectangleSampling rectangle_sampling_;
};

/// An emissive sphere as an area light emitting outward (and inward when `two_sided`);
/// sampled uniformly in area. A `texture` works as MeshLight's does, in the sphere's uv
/// parameterisation.
class SphereLight final : public LightSource {
 public:
  SphereLight(const Sphere& sphere, const Rgb& radiance, bool two_sided,
              EmissionTexture texture = {});
  LightKind kind() const override { return LightKind::kSurface; }
  std::optional<LightLiSample> sample_li(const Vec3& p, Vec2 u) const override;
  float pdf_li(const Vec3& p, const SurfaceInteraction& light_hit) const override;
  Rgb le(const SurfaceInteraction& light_hit, const Vec3& wo) const override;
  /// A point uniformly on the sphere.
  std::optional<LightLeSample> sample_le(Vec2 u_point, Vec2 u_direction) const override;
  Rgb power() const override;

 private:
  /// The radiance at the point of unit normal `n` (the texture looked up unfiltered).
  Rgb radiance_at(const Vec3& n) const;

  Sphere sphere_;
  Rgb radiance_;
  EmissionTexture texture_;
  bool two_sided_;
};

/// Converts an area density at a light point (distance `d`, |cos| at the light `cos_light`)
/// to a solid-angle density at the reference point; 0 when the conversion is degenerate.
float area_to_solid_angle_pdf(float pdf_area, float distance, float cos_light);

}  // namespace prism
