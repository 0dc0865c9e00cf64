#pragma once

#include <memory>
#include <vector>

#include "core/scene.h"
#include "integrators/lights/light_source.h"
#include "integrators/sampling/distribution.h"

namespace prism {

/// Every light of a scene, built once per render: the scene's point, spot, directional,
/// ambient and CGL area lights, its environment map if any (Scene::environment, an
/// EnvironmentLight with its pole along the map's `up`), plus one area light per emissive mesh
/// and per emissive sphere. An area light marked `duplicates_emissive_mesh` is left out: its
/// emissive mesh is the light (visible to rays, sampled by area), so the energy is counted once.
/// Chooses lights in proportion to power. Keeps references into `scene`, which must outlive it.
/// Thread-safe.
class LightSet {
 public:
  explicit LightSet(const Scene& scene);

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
  /// The kInfinite lights, which rays that escape see.
  const std::vector<const LightSource*>& infinite_lights() const { return infinite_; }
  /// Sum of le_escaped(w) over the infinite lights.
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
