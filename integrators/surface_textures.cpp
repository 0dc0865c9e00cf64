#include "integrators/surface_textures.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace prism {
namespace {

/// The footprint stretches by 1 / |cos| along the view direction, up to this factor.
constexpr float kMaxStretch = 20.0f;

/// uv offset of the position offset `dp` (in the surface's plane) on a triangle with corners
/// p0, p1, p2 and uvs uv0, uv1, uv2: dp as barycentric offsets (least squares on the two edges),
/// then as uv. Zero on a degenerate triangle.
Vec2 triangle_duv(const Vec3 p[3], const Vec2 uv[3], const Vec3& dp) {
  const Vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
  const float a = glm::dot(e1, e1), b = glm::dot(e1, e2), c = glm::dot(e2, e2);
  const float det = a * c - b * b;
  if (!(det > 1e-12f * a * c) || !std::isfinite(det)) return Vec2(0.0f);
  const float r1 = glm::dot(dp, e1), r2 = glm::dot(dp, e2);
  const float b1 = (c * r1 - b * r2) / det;
  const float b2 = (a * r2 - b * r1) / det;
  return b1 * (uv[1] - uv[0]) + b2 * (uv[2] - uv[0]);
}

/// uv offset of `dp` at uv `uv` on a sphere of radius r, parameterised as Scene::surface_at
/// does (u = phi / 2 pi, v = theta / pi): the two partial derivatives are orthogonal.
Vec2 sphere_duv(float radius, Vec2 uv, const Vec3& dp) {
  const float phi = uv.x * 2.0f * kPi, theta = uv.y * kPi;
  const Vec3 dpdu = 2.0f * kPi * radius *
                    Vec3(-std::sin(theta) * std::sin(phi), std::sin(theta) * std::cos(phi), 0.0f);
  const Vec3 dpdv =
      kPi * radius *
      Vec3(std::cos(theta) * std::cos(phi), std::cos(theta) * std::sin(phi), -std::sin(theta));
  const float uu = glm::dot(dpdu, dpdu), vv = glm::dot(dpdv, dpdv);
  return Vec2(uu > 1e-12f ? glm::dot(dp, dpdu) / uu : 0.0f,
              vv > 1e-12f ? glm::dot(dp, dpdv) / vv : 0.0f);
}

}  // namespace

TextureFilter camera_texture_filter(const Camera& camera, int image_height, int spp) {
  TextureFilter filter;
  filter.eye = camera.position;
  if (image_height <= 0) return filter;
  const float pixel = 2.0f * std::tan(radians(camera.vfov_deg) * 0.5f) / float(image_height);
  const float supersampling = std::max(0.125f, 1.0f / std::sqrt(float(std::max(1, spp))));
  filter.spread = std::isfinite(pixel) ? pixel * supersampling : 0.0f;
  return filter;
}

SurfaceTextures::SurfaceTextures(const Scene& scene, const TextureFilter& filter)
    : scene_(scene), filter_(filter), lookup_(scene.texture_lookup.get()) {
  for (const Material& m : scene.materials) {
    if (!m.is_textured()) continue;
    if (!lookup_ || lookup_->size() != scene.textures.size()) {
      throw Error(ErrorKind::kInternal,
                  "material '" + m.name +
                      "' has a texture, but the scene's textures were not loaded "
                      "(load_scene_textures)");
    }
  }
}

void SurfaceTextures::footprint(const SurfaceInteraction& si, Vec2& duv_dx, Vec2& duv_dy) const {
  duv_dx = duv_dy = Vec2(0.0f);
  const Vec3 to_hit = si.position - filter_.eye;
  const float distance = glm::length(to_hit);
  if (!(filter_.spread > 0.0f) || !(distance > 0.0f)) return;
  const float width = distance * filter_.spread;
  const Vec3 view = to_hit / distance;
  const Vec3& n = si.geometric_normal;
  const float cos_view = std::max(std::abs(glm::dot(view, n)), 1.0f / kMaxStretch);
  // Axes of the footprint on the surface: across the view direction, and along it.
  Vec3 across = glm::cross(n, view);
  const float across_length = glm::length(across);
  if (across_length > 1e-6f) {
    across /= across_length;
  } else {
    // Seen head-on: any direction in the plane.
    across = std::abs(n.x) < 0.9f ? glm::normalize(glm::cross(n, Vec3(1, 0, 0)))
                                  : glm::normalize(glm::cross(n, Vec3(0, 1, 0)));
  }
  const Vec3 along = glm::cross(n, across);
  const Vec3 dp_x = width * across;
  const Vec3 dp_y = (width / cos_view) * along;
  const SceneGeometry& geometry = scene_.geometry;
  if (geometry.is_sphere(si.geom_id)) {
    const float radius = geometry.spheres[si.prim_id].radius;
    duv_dx = sphere_duv(radius, si.uv, dp_x);
    duv_dy = sphere_duv(radius, si.uv, dp_y);
    return;
  }
  const TriangleMesh& mesh = geometry.meshes[si.geom_id];
  const glm::uvec3 t = mesh.triangles[si.prim_id];
  const Vec3 p[3] = {mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]};
  Vec2 uv[3] = {Vec2(0.0f), Vec2(1.0f, 0.0f), Vec2(0.0f, 1.0f)};  // barycentric without uvs
  if (!mesh.uvs.empty()) {
    const size_t c = 3 * size_t(si.prim_id);
    uv[0] = mesh.uvs[c];
    uv[1] = mesh.uvs[c + 1];
    uv[2] = mesh.uvs[c + 2];
  }
  duv_dx = triangle_duv(p, uv, dp_x);
  duv_dy = triangle_duv(p, uv, dp_y);
}

Rgb SurfaceTextures::at(uint32_t texture, const SurfaceInteraction& si) const {
  Vec2 dx, dy;
  footprint(si, dx, dy);
  return lookup_->lookup(texture, si.uv, dx, dy);
}

Rgb SurfaceTextures::at_uv(uint32_t texture, Vec2 uv) const {
  return lookup_->lookup(texture, uv, Vec2(0.0f), Vec2(0.0f));
}

Rgb SurfaceTextures::average(uint32_t texture) const { return lookup_->average(texture); }

Rgb SurfaceTextures::reflectance(const Material& material, const SurfaceInteraction& si) const {
  Rgb r = material.reflectance;
  if (material.reflectance_texture != kNoTexture) r *= at(material.reflectance_texture, si);
  return glm::clamp(r, Rgb(0.0f), Rgb(1.0f));
}

Rgb SurfaceTextures::radiance(const Material& material, const SurfaceInteraction& si) const {
  Rgb l = material.radiance;
  if (material.radiance_texture != kNoTexture) l *= at(material.radiance_texture, si);
  return glm::max(l, Rgb(0.0f));
}

}  // namespace prism
