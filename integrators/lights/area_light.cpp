#include "integrators/lights/area_light.h"

#include <algorithm>
#include <cmath>

#include "integrators/sampling/frame.h"
#include "integrators/sampling/warp.h"

namespace prism {

float area_to_solid_angle_pdf(float pdf_area, float distance, float cos_light) {
  const float c = std::abs(cos_light);
  if (!(c > 0.0f) || !(distance > 0.0f)) return 0.0f;
  const float pdf = pdf_area * distance * distance / c;
  return std::isfinite(pdf) ? pdf : 0.0f;
}

namespace {

/// Cosine between the emitter's front normal `n` and the unit direction `w_out` leaving it, as
/// far as the emitter emits that way: |cos| when two-sided, else cos clamped to 0 (its back).
float emitting_cos(const Vec3& n, const Vec3& w_out, bool two_sided) {
  const float c = glm::dot(n, w_out);
  return two_sided ? std::abs(c) : std::max(c, 0.0f);
}

/// The sample toward light point `q` with front normal `n` from `p`.
std::optional<LightLiSample> toward_point(const Vec3& p, const Vec3& q, const Vec3& n,
                                          bool two_sided, float pdf_area, const Rgb& radiance) {
  const Vec3 d = q - p;
  const float distance = glm::length(d);
  if (!(distance > 0.0f)) return std::nullopt;
  LightLiSample s;
  s.wi = d * (1.0f / distance);
  const float cos_light = emitting_cos(n, -s.wi, two_sided);
  if (cos_light <= 0.0f) return std::nullopt;  // the back of a one-sided emitter
  s.pdf = area_to_solid_angle_pdf(pdf_area, distance, cos_light);
  if (s.pdf <= 0.0f) return std::nullopt;
  s.distance = distance;
  s.li = radiance;
  return s;
}

/// The light ray leaving `position` (rounding error `error`) of an emitter with front normal
/// `front` and radiance `radiance` there, whose area density is 1 / area: a side (the front, or
/// either for a two-sided emitter, by u.x) and a cosine-distributed direction on it; nothing
/// for a grazing direction that rounding turned into the surface.
std::optional<LightLeSample> leaving_point(const Vec3& position, const Vec3& error,
                                           const Vec3& front, bool two_sided, float area,
                                           const Rgb& radiance, Vec2 u) {
  Vec3 normal = front;
  float side_probability = 1.0f;
  if (two_sided) {
    side_probability = 0.5f;
    if (u.x < 0.5f) {
      u.x = 2.0f * u.x;
    } else {
      u.x = std::min(2.0f * u.x - 1.0f, 0x1.fffffep-1f);
      normal = -front;
    }
  }
  LightLeSample s;
  s.point.position = position;
  s.point.position_error = error;
  s.point.geometric_normal = normal;
  s.point.shading_normal = normal;
  s.direction = glm::normalize(Frame::from_z(normal).to_world(square_to_cosine_hemisphere(u)));
  if (!(glm::dot(s.direction, normal) > 0.0f)) return std::nullopt;  // grazing, rounded below
  // radiance x cos / ((1 / area) x side probability x cos / pi)
  s.beta = radiance * (kPi * area / side_probability);
  return s;
}

/// A conservative bound on the rounding of a point rebuilt on a primitive whose coordinates
/// are at most `magnitude`, including the ray tests' own rounding (Scene::surface_at()'s bound
/// is tighter; this one only has to be large enough for spawn_ray()).
Vec3 emitter_point_error(float magnitude) { return Vec3(rounding_gamma(32) * magnitude); }

}  // namespace

ParallelogramLight::ParallelogramLight(const Light& light, bool two_sided)
    : radiance_(light.color),
      corner_(light.position - 0.5f * (light.edge_u + light.edge_v)),
      edge_u_(light.edge_u),
      edge_v_(light.edge_v),
      normal_(glm::normalize(light.direction)),
      area_(glm::length(glm::cross(light.edge_u, light.edge_v))),
      two_sided_(two_sided) {}

std::optional<LightLiSample> ParallelogramLight::sample_li(const Vec3& p, Vec2 u) const {
  if (!(area_ > 0.0f)) return std::nullopt;
  const Vec3 q = corner_ + u.x * edge_u_ + u.y * edge_v_;
  return toward_point(p, q, normal_, two_sided_, 1.0f / area_, radiance_);
}

Rgb ParallelogramLight::power() const {
  return (two_sided_ ? 2.0f : 1.0f) * kPi * area_ * radiance_;
}

MeshLight::MeshLight(const TriangleMesh& mesh, const Rgb& radiance, bool two_sided,
                     EmissionTexture texture, RectangleSampling rectangle_sampling)
    : mesh_(mesh),
      radiance_(radiance),
      texture_(texture),
      two_sided_(two_sided),
      rectangle_sampling_(rectangle_sampling) {
  std::vector<float> areas(mesh.triangles.size());
  normals_.resize(mesh.triangles.size());
  double total = 0.0;
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    const glm::uvec3 t = mesh.triangles[i];
    const Vec3 c = glm::cross(mesh.positions[t.y] - mesh.positions[t.x],
                              mesh.positions[t.z] - mesh.positions[t.x]);
    const float len = glm::length(c);
    areas[i] = 0.5f * len;
    total += areas[i];
    Vec3 n = len > 0.0f ? c / len : Vec3(0.0f, 0.0f, 1.0f);
    // Same orientation rule as Scene::surface_at(): authored normals decide the side.
    if (!mesh.normals.empty()) {
      const Vec3 ns = mesh.normals[3 * i] + mesh.normals[3 * i + 1] + mesh.normals[3 * i + 2];
      if (glm::dot(ns, n) < 0.0f) n = -n;
    }
    normals_[i] = n;
  }
  area_ = float(total);
  triangles_ = DiscreteDistribution(areas);
  if (mesh.triangles.size() <= kSolidAngleTriangles) {
    for (const glm::uvec3& t : mesh.triangles) {
      const Vec3 p0 = mesh.positions[t.x], p1 = mesh.positions[t.y], p2 = mesh.positions[t.z];
      centroids_.push_back((p0 + p1 + p2) / 3.0f);
      longest_edge2_.push_back(std::max(
          {glm::dot(p1 - p0, p1 - p0), glm::dot(p2 - p1, p2 - p1), glm::dot(p0 - p2, p0 - p2)}));
    }
  }
  if (!texture_) rectangle_ = as_rectangle();
}

std::optional<Rectangle> MeshLight::as_rectangle() const {
  if (mesh_.triangles.size() != 2 || !(area_ > 0.0f)) return std::nullopt;
  if (!(glm::dot(normals_[0], normals_[1]) > 0.99999f)) return std::nullopt;
  // The diagonal is the edge the triangles share: its ends and the two other corners.
  const glm::uvec3 t0 = mesh_.triangles[0], t1 = mesh_.triangles[1];
  const Vec3 a[3] = {mesh_.positions[t0.x], mesh_.positions[t0.y], mesh_.positions[t0.z]};
  const Vec3 b[3] = {mesh_.positions[t1.x], mesh_.positions[t1.y], mesh_.positions[t1.z]};
  int shared = 0, corner = -1, opposite = -1;
  for (int i = 0; i < 3; ++i) {
    const bool in_b = a[i] == b[0] || a[i] == b[1] || a[i] == b[2];
    shared += in_b ? 1 : 0;
    if (!in_b) corner = i;
  }
  for (int j = 0; j < 3; ++j) {
    if (!(b[j] == a[0] || b[j] == a[1] || b[j] == a[2])) opposite = j;
  }
  if (shared != 2 || corner < 0 || opposite < 0) return std::nullopt;
  const Vec3& c = a[corner];
  const Vec3& e1 = a[(corner + 1) % 3];
  const Vec3& e2 = a[(corner + 2) % 3];
  const std::optional<Rectangle> r = rectangle_from_corner(c, e1, e2);
  if (!r) return std::nullopt;
  // The fourth corner completes the rectangle, to the same tolerance.
  const Vec3 diagonal = e1 + e2 - c - b[opposite];
  if (!(glm::length(diagonal) <= kRectangleTolerance * glm::length(e1 - e2))) return std::nullopt;
  return r;
}

bool MeshLight::rectangle_in_solid_angle(const Vec3& p, float side,
                                         std::optional<SphericalRectangle>& spherical) const {
  const Rectangle& r = *rectangle_;
  const float diagonal2 = r.length_x * r.length_x + r.length_y * r.length_y;
  if (!(diagonal2 > side * side)) return false;
  spherical.emplace(r, p);
  const float omega = spherical->solid_angle();
  return omega >= kMinSphericalRectangleSolidAngle && omega <= kMaxSphericalSolidAngle;
}

float MeshLight::triangle_weights(const Vec3& p, float* weights, bool* spherical) const {
  float total = 0.0f;
  for (size_t i = 0; i < mesh_.triangles.size(); ++i) {
    const glm::uvec3 t = mesh_.triangles[i];
    weights[i] = 0.0f;
    spherical[i] = false;
    const Vec3 a = mesh_.positions[t.x] - p;
    // From the back of a one-sided emitter (or in its plane) the triangle sends nothing.
    const float side = -glm::dot(normals_[i], a);
    if (two_sided_ ? side == 0.0f : !(side > 0.0f)) continue;
    if (longest_edge2_[i] > side * side) {
      weights[i] = triangle_solid_angle(a, mesh_.positions[t.y] - p, mesh_.positions[t.z] - p);
      spherical[i] = weights[i] >= kMinSphericalSolidAngle && weights[i] <= kMaxSphericalSolidAngle;
    } else {
      // area x cos / distance^2 at the centroid, cos = |side| / distance.
      const Vec3 c = centroids_[i] - p;
      const float d2 = glm::dot(c, c);
      const float w = triangles_.pmf(i) * area_ * std::abs(side) / (d2 * std::sqrt(d2));
      weights[i] = std::isfinite(w) ? w : 0.0f;
    }
    total += weights[i];
  }
  return total;
}

Rgb MeshLight::radiance_at(size_t i, Vec2 b) const {
  if (!texture_) return radiance_;
  // The uv of the point as Scene::surface_at() interpolates it (barycentrics without uvs).
  Vec2 uv = b;
  if (!mesh_.uvs.empty()) {
    uv = (1.0f - b.x - b.y) * mesh_.uvs[3 * i] + b.x * mesh_.uvs[3 * i + 1] +
         b.y * mesh_.uvs[3 * i + 2];
  }
  return radiance_ * glm::max(texture_.textures->at_uv(texture_.texture, uv), Rgb(0.0f));
}

std::optional<LightLiSample> MeshLight::toward_triangle_point(const Vec3& p, size_t i,
                                                              const Vec3& q, Vec2 b, float pdf_area,
                                                              float pdf_solid_angle) const {
  std::optional<LightLiSample> s =
      toward_point(p, q, normals_[i], two_sided_, pdf_area, radiance_at(i, b));
  if (s && pdf_solid_angle > 0.0f) s->pdf = pdf_solid_angle;
  return s;
}

std::optional<LightLiSample> MeshLight::sample_li(const Vec3& p, Vec2 u) const {
  if (!(area_ > 0.0f) || triangles_.empty()) return std::nullopt;
  if (rectangle_) {
    // From the back of a one-sided emitter (or in its plane) the rectangle sends nothing.
    const float side = -glm::dot(normals_[0], rectangle_->corner - p);
    if (two_sided_ ? side == 0.0f : !(side > 0.0f)) return std::nullopt;
    if (rectangle_sampling_ == RectangleSampling::kBilinear) {
      const BilinearCorners w = solid_angle_corners(*rectangle_, p);
      const Vec2 uv = sample_bilinear(u, w);
      return toward_point(p, rectangle_->point_at(uv), normals_[0], two_sided_,
                          bilinear_pdf(uv, w) / area_, radiance_);
    }
    std::optional<SphericalRectangle> spherical;
    if (rectangle_sampling_ == RectangleSampling::kSolidAngle &&
        rectangle_in_solid_angle(p, side, spherical)) {
      const std::optional<Vec3> q = spherical->sample(u);
      if (!q) return std::nullopt;
      std::optional<LightLiSample> s =
          toward_point(p, *q, normals_[0], two_sided_, 1.0f / area_, radiance_);
      if (s) s->pdf = 1.0f / spherical->solid_angle();
      return s;
    }
    return toward_point(p, rectangle_->point_at(u), normals_[0], two_sided_, 1.0f / area_,
                        radiance_);
  }
  const size_t n = mesh_.triangles.size();
  if (n <= kSolidAngleTriangles) {
    float omega[kSolidAngleTriangles];
    bool spherical[kSolidAngleTriangles];
    const float total = triangle_weights(p, omega, spherical);
    if (!(total > 0.0f)) return std::nullopt;
    // The triangle in proportion to its solid angle, u.x rescaled to [0,1) within it.
    size_t i = 0;
    float below = 0.0f;
    const float target = u.x * total;
    while (i + 1 < n && (omega[i] <= 0.0f || below + omega[i] <= target)) below += omega[i++];
    if (!(omega[i] > 0.0f)) return std::nullopt;
    const Vec2 v(std::clamp((target - below) / omega[i], 0.0f, 0x1.fffffep-1f), u.y);
    const float pmf = omega[i] / total;
    const glm::uvec3 t = mesh_.triangles[i];
    const Vec3 p0 = mesh_.positions[t.x], p1 = mesh_.positions[t.y], p2 = mesh_.positions[t.z];
    if (!spherical[i]) {
      const Vec2 b = square_to_uniform_triangle(v);
      const Vec3 q = (1.0f - b.x - b.y) * p0 + b.x * p1 + b.y * p2;
      return toward_triangle_point(p, i, q, b, pmf / triangles_.pmf(i) / area_, 0.0f);
    }
    const std::optional<Vec3> w = sample_spherical_triangle(
        glm::normalize(p0 - p), glm::normalize(p1 - p), glm::normalize(p2 - p), omega[i], v);
    if (!w) return std::nullopt;
    // The point where w meets the triangle's plane, and its barycentrics.
    const Vec3 e1 = p1 - p0, e2 = p2 - p0;
    const Vec3 pv = glm::cross(*w, e2);
    const float det = glm::dot(e1, pv);
    if (!(std::abs(det) > 0.0f)) return std::nullopt;
    const Vec3 o = p - p0;
    const Vec3 qv = glm::cross(o, e1);
    const float inverse_det = 1.0f / det;
    const float distance = glm::dot(e2, qv) * inverse_det;
    if (!(distance > 0.0f)) return std::nullopt;
    const Vec2 b(std::clamp(glm::dot(o, pv) * inverse_det, 0.0f, 1.0f),
                 std::clamp(glm::dot(*w, qv) * inverse_det, 0.0f, 1.0f));
    std::optional<LightLiSample> s =
        toward_triangle_point(p, i, p + distance * *w, b, 1.0f / area_, 1.0f / total);
    if (s) s->wi = *w;
    return s;
  }
  float u_remapped = 0.0f;
  const size_t i = triangles_.sample(u.x, nullptr, &u_remapped);
  const Vec2 b = square_to_uniform_triangle({u_remapped, u.y});
  const glm::uvec3 t = mesh_.triangles[i];
  const Vec3 q = (1.0f - b.x - b.y) * mesh_.positions[t.x] + b.x * mesh_.positions[t.y] +
                 b.y * mesh_.positions[t.z];
  return toward_triangle_point(p, i, q, b, 1.0f / area_, 0.0f);
}

float MeshLight::pdf_li(const Vec3& p, const SurfaceInteraction& light_hit) const {
  if (!(area_ > 0.0f)) return 0.0f;
  const Vec3 d = light_hit.position - p;
  const float distance = glm::length(d);
  if (!(distance > 0.0f)) return 0.0f;
  // sample_li() never returns points seen from a side that does not emit: their density is 0.
  const float cos_light = emitting_cos(light_hit.geometric_normal, -d / distance, two_sided_);
  if (cos_light <= 0.0f) return 0.0f;
  if (rectangle_) {
    if (rectangle_sampling_ == RectangleSampling::kBilinear) {
      const float pdf_area = bilinear_pdf(rectangle_->extent_of(light_hit.position),
                                          solid_angle_corners(*rectangle_, p));
      return area_to_solid_angle_pdf(pdf_area / area_, distance, cos_light);
    }
    const float side = -glm::dot(normals_[0], rectangle_->corner - p);
    std::optional<SphericalRectangle> spherical;
    if (rectangle_sampling_ == RectangleSampling::kSolidAngle &&
        rectangle_in_solid_angle(p, side, spherical)) {
      return 1.0f / spherical->solid_angle();
    }
    return area_to_solid_angle_pdf(1.0f / area_, distance, cos_light);
  }
  const size_t n = mesh_.triangles.size();
  if (n <= kSolidAngleTriangles) {
    const size_t i = light_hit.prim_id;
    if (i >= n) return 0.0f;
    float omega[kSolidAngleTriangles];
    bool spherical[kSolidAngleTriangles];
    const float total = triangle_weights(p, omega, spherical);
    if (!(total > 0.0f) || !(omega[i] > 0.0f)) return 0.0f;
    if (spherical[i]) return 1.0f / total;
    return area_to_solid_angle_pdf(omega[i] / total / triangles_.pmf(i) / area_, distance,
                                   cos_light);
  }
  return area_to_solid_angle_pdf(1.0f / area_, distance, cos_light);
}

Rgb MeshLight::le(const SurfaceInteraction& light_hit, const Vec3& wo) const {
  if (emitting_cos(light_hit.geometric_normal, wo, two_sided_) <= 0.0f) return Rgb(0.0f);
  if (!texture_) return radiance_;
  return radiance_ * glm::max(texture_.textures->at(texture_.texture, light_hit), Rgb(0.0f));
}

std::optional<LightLeSample> MeshLight::sample_le(Vec2 u_point, Vec2 u_direction) const {
  if (!(area_ > 0.0f) || triangles_.empty()) return std::nullopt;
  float u_remapped = 0.0f;
  const size_t i = triangles_.sample(u_point.x, nullptr, &u_remapped);
  const Vec2 b = square_to_uniform_triangle({u_remapped, u_point.y});
  const glm::uvec3 t = mesh_.triangles[i];
  const Vec3 p0 = mesh_.positions[t.x], p1 = mesh_.positions[t.y], p2 = mesh_.positions[t.z];
  // In double, as Scene::surface_at() rebuilds a hit point: one rounding off the plane.
  const DVec3 d0(p0);
  const Vec3 q(d0 + double(b.x) * (DVec3(p1) - d0) + double(b.y) * (DVec3(p2) - d0));
  const Vec3 error = emitter_point_error(
      max_component(abs_components(p0) + abs_components(p1) + abs_components(p2)));
  return leaving_point(q, error, normals_[i], two_sided_, area_, radiance_at(i, b), u_direction);
}

Rgb MeshLight::power() const {
  const Rgb mean =
      texture_ ? glm::max(texture_.textures->average(texture_.texture), Rgb(0.0f)) : Rgb(1.0f);
  return (two_sided_ ? 2.0f : 1.0f) * kPi * area_ * radiance_ * mean;
}

SphereLight::SphereLight(const Sphere& sphere, const Rgb& radiance, bool two_sided,
                         EmissionTexture texture)
    : sphere_(sphere), radiance_(radiance), texture_(texture), two_sided_(two_sided) {}

std::optional<LightLiSample> SphereLight::sample_li(const Vec3& p, Vec2 u) const {
  const float area = 4.0f * kPi * sphere_.radius * sphere_.radius;
  if (!(area > 0.0f)) return std::nullopt;
  const Vec3 n = square_to_uniform_sphere(u);
  return toward_point(p, sphere_.center + sphere_.radius * n, n, two_sided_, 1.0f / area,
                      radiance_at(n));
}

Rgb SphereLight::radiance_at(const Vec3& n) const {
  if (!texture_) return radiance_;
  // The uv of the point as Scene::surface_at() parameterises spheres.
  float phi = std::atan2(n.y, n.x);
  if (phi < 0.0f) phi += 2.0f * kPi;
  const Vec2 uv(phi / (2.0f * kPi), std::acos(std::clamp(n.z, -1.0f, 1.0f)) / kPi);
  return radiance_ * glm::max(texture_.textures->at_uv(texture_.texture, uv), Rgb(0.0f));
}

std::optional<LightLeSample> SphereLight::sample_le(Vec2 u_point, Vec2 u_direction) const {
  const float area = 4.0f * kPi * sphere_.radius * sphere_.radius;
  if (!(area > 0.0f)) return std::nullopt;
  const Vec3 n = square_to_uniform_sphere(u_point);
  const Vec3 q(DVec3(sphere_.center) + double(sphere_.radius) * DVec3(n));
  const Vec3 error =
      emitter_point_error(max_component(abs_components(sphere_.center)) + sphere_.radius);
  return leaving_point(q, error, n, two_sided_, area, radiance_at(n), u_direction);
}

float SphereLight::pdf_li(const Vec3& p, const SurfaceInteraction& light_hit) const {
  const float area = 4.0f * kPi * sphere_.radius * sphere_.radius;
  if (!(area > 0.0f)) return 0.0f;
  const Vec3 d = light_hit.position - p;
  const float distance = glm::length(d);
  if (!(distance > 0.0f)) return 0.0f;
  const float cos_light = emitting_cos(light_hit.geometric_normal, -d / distance, two_sided_);
  if (cos_light <= 0.0f) return 0.0f;
  return area_to_solid_angle_pdf(1.0f / area, distance, cos_light);
}

Rgb SphereLight::le(const SurfaceInteraction& light_hit, const Vec3& wo) const {
  if (emitting_cos(light_hit.geometric_normal, wo, two_sided_) <= 0.0f) return Rgb(0.0f);
  if (!texture_) return radiance_;
  return radiance_ * glm::max(texture_.textures->at(texture_.texture, light_hit), Rgb(0.0f));
}

Rgb SphereLight::power() const {
  const Rgb mean =
      texture_ ? glm::max(texture_.textures->average(texture_.texture), Rgb(0.0f)) : Rgb(1.0f);
  return (two_sided_ ? 2.0f : 1.0f) * kPi * 4.0f * kPi * sphere_.radius * sphere_.radius *
         radiance_ * mean;
}

}  // namespace prism
