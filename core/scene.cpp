#include "core/scene.h"

#include <cmath>
#include <string>

#include "core/error.h"

namespace prism {

SurfaceInteraction Scene::surface_at(const Ray& ray, const Hit& hit) const {
  SurfaceInteraction si;
  si.t = hit.t;
  si.geom_id = hit.geom_id;
  si.prim_id = hit.prim_id;
  if (geometry.is_sphere(hit.geom_id)) {
    const Sphere& s = geometry.spheres[hit.prim_id];
    const float phi = hit.u * 2.0f * kPi;
    const float theta = hit.v * kPi;
    const Vec3 n{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
    si.position = s.center + s.radius * n;
    si.geometric_normal = n;
    si.shading_normal = n;
    si.uv = Vec2(hit.u, hit.v);
    si.material_id = s.material_id;
    return si;
  }
  const TriangleMesh& mesh = geometry.meshes[hit.geom_id];
  const glm::uvec3 tri = mesh.triangles[hit.prim_id];
  const Vec3& p0 = mesh.positions[tri.x];
  const Vec3& p1 = mesh.positions[tri.y];
  const Vec3& p2 = mesh.positions[tri.z];
  const float w = 1.0f - hit.u - hit.v;
  si.position = w * p0 + hit.u * p1 + hit.v * p2;
  Vec3 ng = glm::cross(p1 - p0, p2 - p0);
  const float ng_length = glm::length(ng);
  ng = ng_length > 0.0f ? ng / ng_length : -glm::normalize(ray.direction);
  si.geometric_normal = ng;
  si.shading_normal = ng;
  if (!mesh.normals.empty()) {
    const size_t c = 3 * size_t(hit.prim_id);
    const Vec3 ns = w * mesh.normals[c] + hit.u * mesh.normals[c + 1] + hit.v * mesh.normals[c + 2];
    const float ns_length = glm::length(ns);
    if (ns_length > 0.0f && std::isfinite(ns_length)) {
      si.shading_normal = ns / ns_length;
      // Files whose winding disagrees with their normals (the CS184 Cornell floor): trust the
      // authored normal and turn the geometric one to its side.
      if (glm::dot(si.shading_normal, ng) < 0.0f) si.geometric_normal = -ng;
    }
  }
  if (!mesh.uvs.empty()) {
    const size_t c = 3 * size_t(hit.prim_id);
    si.uv = w * mesh.uvs[c] + hit.u * mesh.uvs[c + 1] + hit.v * mesh.uvs[c + 2];
  } else {
    si.uv = Vec2(hit.u, hit.v);
  }
  si.material_id = mesh.material_id;
  return si;
}

void Scene::validate() const {
  geometry.validate();
  camera.validate();
  const auto check_material = [&](uint32_t id, const std::string& what) {
    if (id >= materials.size()) {
      throw Error(ErrorKind::kInput, "material index " + std::to_string(id) + " out of range",
                  {{}, 0, what});
    }
  };
  for (const Material& m : materials) {
    for (const uint32_t t : {m.reflectance_texture, m.radiance_texture}) {
      if (t != kNoTexture && t >= textures.size()) {
        throw Error(ErrorKind::kInput, "texture index " + std::to_string(t) + " out of range",
                    {{}, 0, "material '" + m.name + "'"});
      }
    }
  }
  for (const auto& m : geometry.meshes) check_material(m.material_id, "mesh '" + m.name + "'");
  for (size_t i = 0; i < geometry.spheres.size(); ++i) {
    check_material(geometry.spheres[i].material_id, "sphere " + std::to_string(i));
  }
}

Vec3 offset_ray_origin(const Vec3& p, const Vec3& geometric_normal, const Vec3& toward) {
  // Offset proportional to the largest coordinate magnitude: a few ulps of float error in the
  // rebuilt hit point, with margin (pbrt-v4's error-bound idea, with a conservative bound).
  const float magnitude = max_component(glm::abs(p));
  const float offset = 1e-4f * std::max(1.0f, magnitude);
  const Vec3 n = glm::dot(geometric_normal, toward) >= 0.0f ? geometric_normal : -geometric_normal;
  return p + offset * n;
}

}  // namespace prism
