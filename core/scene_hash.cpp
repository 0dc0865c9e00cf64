#include "core/scene_hash.h"

#include <span>
#include <type_traits>
#include <vector>

#include "core/hash.h"

namespace prism {
namespace {

/// Feeds values into one FNV-1a hash.
class Hasher {
 public:
  template <typename T>
  void add(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    hash_ = fnv1a64(std::as_bytes(std::span<const T>(&value, 1)), hash_);
  }
  template <typename T, typename Allocator>
  void add_all(const std::vector<T, Allocator>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    add(uint64_t(values.size()));
    hash_ = fnv1a64(std::as_bytes(std::span<const T>(values)), hash_);
  }
  uint64_t value() const { return hash_; }

 private:
  uint64_t hash_ = kFnvOffset;
};

template <typename T>
void add_optional(Hasher& h, const std::optional<T>& value) {
  h.add(value.has_value());
  if (value) h.add(*value);
}

}  // namespace

uint64_t scene_hash(const Scene& scene) {
  Hasher h;
  h.add(uint64_t(scene.geometry.meshes.size()));
  for (const TriangleMesh& m : scene.geometry.meshes) {
    h.add_all(m.positions);
    h.add_all(m.triangles);
    h.add_all(m.normals);
    h.add_all(m.uvs);
    h.add(m.material_id);
  }
  h.add(uint64_t(scene.geometry.spheres.size()));
  for (const Sphere& s : scene.geometry.spheres) {
    h.add(s.center);
    h.add(s.radius);
    h.add(s.material_id);
  }
  h.add(uint64_t(scene.materials.size()));
  for (const Material& m : scene.materials) {
    h.add(m.type);
    h.add(m.reflectance);
    h.add(m.transmittance);
    h.add(m.roughness);
    h.add(m.ior);
    h.add(m.alpha);
    h.add(m.eta);
    h.add(m.k);
    h.add(m.radiance);
    h.add(m.reflectance_texture);
    h.add(m.radiance_texture);
  }
  // Textures by their pixels once loaded (converted to the working space), not by file names,
  // which change with the folder a render starts in.
  h.add(uint64_t(scene.textures.size()));
  h.add(scene.texture_lookup != nullptr);
  if (scene.texture_lookup) h.add(scene.texture_lookup->content_hash());
  h.add(uint64_t(scene.lights.size()));
  for (const Light& l : scene.lights) {
    h.add(l.type);
    h.add(l.color);
    h.add(l.position);
    h.add(l.direction);
    h.add(l.up);
    h.add(l.constant_attenuation);
    h.add(l.linear_attenuation);
    h.add(l.quadratic_attenuation);
    h.add(l.falloff_angle_deg);
    h.add(l.falloff_exponent);
    h.add(l.edge_u);
    h.add(l.edge_v);
    h.add(l.duplicates_emissive_mesh);
  }
  const Camera& c = scene.camera;
  for (const Vec3& v : {c.position, c.target, c.up}) h.add(v);
  for (const float f : {c.hfov_deg, c.vfov_deg, c.znear, c.zfar, c.lens_radius, c.focal_distance}) {
    h.add(f);
  }
  const SceneRenderSettings& s = scene.settings;
  add_optional(h, s.width);
  add_optional(h, s.height);
  add_optional(h, s.spp);
  add_optional(h, s.max_depth);
  add_optional(h, s.seed);
  h.add(s.integrator.has_value());
  if (s.integrator) h.add_all(std::vector<char>(s.integrator->begin(), s.integrator->end()));
  h.add(scene.environment.has_value());
  if (scene.environment) {
    h.add(scene.environment->image.width);
    h.add(scene.environment->image.height);
    h.add_all(scene.environment->image.pixels);
    h.add(scene.environment->up);
  }
  return h.value();
}

}  // namespace prism
