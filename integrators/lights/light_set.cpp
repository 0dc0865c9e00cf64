#include "integrators/lights/light_set.h"

#include <algorithm>

#include "core/error.h"
#include "integrators/lights/area_light.h"
#include "integrators/lights/environment_light.h"
#include "integrators/lights/point_light.h"
#include "integrators/sampling/warp.h"

namespace prism {
namespace {

/// The radiance texture of an emissive material, with the lookups to read it.
EmissionTexture emission_texture(const Material& m, const SurfaceTextures* textures) {
  if (m.radiance_texture == kNoTexture) return {};
  if (!textures) {
    throw Error(ErrorKind::kInternal,
                "material '" + m.name +
                    "' has a radiance texture, but the light set has no texture lookups");
  }
  return {m.radiance_texture, textures};
}

}  // namespace

LightSet::LightSet(const Scene& scene, const LightOptions& options, const SurfaceTextures* textures)
    : scene_(scene) {
  const bool two_sided = options.two_sided_emitters;
  const SceneGeometry& geometry = scene.geometry;
  const Bounds3 bounds = geometry.bounds();
  float radius = 1.0f;
  if (!bounds.empty()) radius = std::max(1e-3f, 0.5f * glm::length(bounds.diagonal()));

  for (const Light& light : scene.lights) {
    switch (light.type) {
      case LightType::kPoint:
      case LightType::kSpot:
        lights_.push_back(std::make_unique<PointLight>(light));
        break;
      case LightType::kDirectional:
        lights_.push_back(std::make_unique<DirectionalLight>(light, radius));
        break;
      case LightType::kAmbient:
        lights_.push_back(std::make_unique<AmbientLight>(light, radius, options.ambient_visible));
        break;
      case LightType::kArea:
        if (!light.duplicates_emissive_mesh) {
          lights_.push_back(std::make_unique<ParallelogramLight>(light, two_sided));
        }
        break;
    }
  }
  if (scene.environment) {
    lights_.push_back(std::make_unique<EnvironmentLight>(scene.environment->image,
                                                         scene.environment->up, radius));
  }
  mesh_light_.assign(geometry.meshes.size(), -1);
  for (size_t i = 0; i < geometry.meshes.size(); ++i) {
    const TriangleMesh& mesh = geometry.meshes[i];
    const Material& m = scene.materials[mesh.material_id];
    if (!m.is_emissive() || max_component(m.radiance) <= 0.0f || mesh.triangles.empty()) continue;
    mesh_light_[i] = int(lights_.size());
    lights_.push_back(std::make_unique<MeshLight>(
        mesh, m.radiance, two_sided, emission_texture(m, textures), options.rectangle_sampling));
  }
  sphere_light_.assign(geometry.spheres.size(), -1);
  for (size_t i = 0; i < geometry.spheres.size(); ++i) {
    const Sphere& sphere = geometry.spheres[i];
    const Material& m = scene.materials[sphere.material_id];
    if (!m.is_emissive() || max_component(m.radiance) <= 0.0f) continue;
    sphere_light_[i] = int(lights_.size());
    lights_.push_back(std::make_unique<SphereLight>(sphere, m.radiance, two_sided,
                                                    emission_texture(m, textures)));
  }
  std::vector<float> weights;
  weights.reserve(lights_.size());
  for (const auto& light : lights_) {
    weights.push_back(std::max(0.0f, luminance(light->power())));
    if (light->kind() == LightKind::kInfinite) infinite_.push_back(light.get());
  }
  selection_ = DiscreteDistribution(weights);
}

const LightSource* LightSet::sample(float u, float* pmf) const {
  if (lights_.empty()) return nullptr;
  return lights_[selection_.sample(u, pmf)].get();
}

size_t LightSet::index_of(const LightSource* light) const {
  for (size_t i = 0; i < lights_.size(); ++i) {
    if (lights_[i].get() == light) return i;
  }
  return lights_.size();
}

const LightSource* LightSet::surface_light(const SurfaceInteraction& si) const {
  int index = -1;
  if (scene_.geometry.is_sphere(si.geom_id)) {
    if (si.prim_id < sphere_light_.size()) index = sphere_light_[si.prim_id];
  } else if (si.geom_id < mesh_light_.size()) {
    index = mesh_light_[si.geom_id];
  }
  return index >= 0 ? lights_[size_t(index)].get() : nullptr;
}

Rgb LightSet::le_escaped(const Vec3& w) const {
  Rgb sum(0.0f);
  for (const LightSource* light : infinite_) sum += light->le_escaped(w);
  return sum;
}

}  // namespace prism
