#pragma once

#include <memory>
#include <vector>

#include "core/scene.h"
#include "integrators/lights/light_source.h"
#include "integrators/sampling/distribution.h"
#include "integrators/surface_textures.h"

namespace prism {

/// How the scene's emitters behave where the scene files leave it open (the light-transport
/// integrators' parameters `<name>.ambient_visible` and `<name>.two_sided_emitters`).
struct LightOptions {
  /// Ambient lights are a visible sky: rays that escape upward see them, and light sampling
  /// is MIS-weighted against BSDF sampling for them. False (the default, as in the CS184
  /// homework): they light surfaces through light sampling alone, escaping rays find black.
  bool ambient_visible = false;
  /// Emissive meshes and spheres and CGL area lights emit the same radiance from both sides,
  /// as Blender's emission does. False (the default, as the homework's light sampling): from
  /// the front only.
  bool two_sided_emitters = false;
  /// How rectangular emitters are sampled (`<name>.rectangle_sampling`: bilinear, the default,
  /// solid_angle or area; docs/PERFORMANCE.md, "bilinear").
  RectangleSampling rectangle_sampling = RectangleSampling::kBilinear;
};

/// Every light of a scene, built once per render: the scene's point, spot, directional,
/// ambient and CGL area lights, its environment map if any (Scene::environment, an
/// EnvironmentLight with its pole along the map's `up`), plus one area light per emissive mesh
/// and per emissive sphere (Material::is_emissive(), with a radiance other than black; a
/// radiance texture is looked up through `textures`, which must then be given and outlive the
/// set). An area light marked `duplicates_emissive_mesh` is left out: its
/// emissive mesh is the light (visible to rays, sampled by area), so the energy is counted once.
/// `options` decide whether ambient lights are seen and emitters lit on both sides.
/// Chooses lights in proportion to power. Keeps references into `scene`, which must outlive it.
/// Thread-safe.
class LightSet {
 public:
  explicit LightSet(const Scene& scene, const LightOptions& options = {},
                    const SurfaceTextures* textures = nullptr);

  const std::vector<std::unique_ptr<LightSource>>& lights() const { return lights_; }
  bool empty() const { return lights_.empty(); }
  size_t size() const { return lights_.size(); }

  /// A light chosen with probability proportional to its power, from u in [0,1); `pmf`
  /// receives that probability. Null when there are no lights.
  const LightSource* sample(float u, float* pmf) const;
  /// Probability that sample() returns light `index`.
  float pmf(size_t index) const { return selection_.pmf(index); }
  /// Index of `light` in lights().
  size_t index_of(const LightSource* light) const;

  /// The emissive-surface light whose geometry `si` lies on, or null.
  const LightSource* surface_light(const SurfaceInteraction& si) const;
  /// The kInfinite lights, which rays that escape see (not the kHiddenInfinite ones).
  const std::vector<const LightSource*>& infinite_lights() const { return infinite_; }
  /// Sum of le_escaped(w) over infinite_lights(): what a ray escaping along w sees.
  Rgb le_escaped(const Vec3& w) const;

 private:
  const Scene& scene_;
  std::vector<std::unique_ptr<LightSource>> lights_;
  std::vector<const LightSource*> infinite_;
  std::vector<int> mesh_light_;    ///< per mesh: index into lights_, or -1
  std::vector<int> sphere_light_;  ///< per sphere: index into lights_, or -1
  DiscreteDistribution selection_;
};

}  // namespace prism
