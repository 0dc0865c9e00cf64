#include "core/scene.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"

namespace prism {
namespace {

// Widening of the rebuilt point's error bound for the ray tests (see docs/RELIABILITY.md,
// "Geometric robustness"). The watertight triangle test and Embree's take the vertices relative
// to the ray origin and shear them: their rounding moves the triangle's plane by up to ~6 u of
// the origin's distance to the farthest vertex, at any angle, even for a plane through the world
// origin whose rebuilt point has no error at all. The sphere test squares |o - c| and compares
// it with r^2, which loses ~4 u r. Both are taken twice over.
const float kTriangleTestGamma = rounding_gamma(12);
const float kSphereTestGamma = rounding_gamma(8);
// The ends of a shadow ray: the target is rebuilt from a light point, a distance and a
// direction, with about 9 u of the largest coordinate of either end.
const float kTargetGamma = rounding_gamma(16);
// The wide BVH's padding of the box of a triangle of size s around a point p (core/ray.h), for a
// ray from p: kBoxOriginPaddingUlps of |p|, kBoxCoordinatePaddingUlps of the box's coordinates
// (|p| + s at most for a box holding the triangle alone), kBoxSizePaddingUlps of s, and up to
// one more ulp of the coordinate from rounding the widened planes outward.
constexpr float kBoxSizeGap = (kBoxSizePaddingUlps + kBoxCoordinatePaddingUlps) / (1 << 24);
constexpr float kBoxCoordinateGap =
    (kBoxOriginPaddingUlps + kBoxCoordinatePaddingUlps + 2.0f) / (1 << 24);
// A quarter to spare for the origin's own move and rounding.
constexpr float kBoxGapMargin = 1.25f;
// Far from the world origin the coordinate's share outgrows small triangles: the offset never
// grows to more than this fraction of the triangle's size for the clearance.
constexpr float kMaxGapOfSize = 1.0f / 256.0f;

/// A triangle point's error bound `error` widened to the wide BVH's padding of the triangle's
/// own box on the axes where that box is flatter than its padding: a ray leaving a triangle in
/// an axis-aligned plane (a wall, a floor, a box's face) then starts outside the padded, flat box
/// of the triangle's leaf instead of inside it, and the BVH does not test that leaf again for a
/// hit the offset already rules out (docs/RELIABILITY.md, "Geometric robustness";
/// docs/PERFORMANCE.md, "Rays leaving large flat triangles"). A ray leaving a tilted triangle
/// starts inside its box whatever the offset, so its bound is left as it is, and so is that of
/// a triangle so small for its coordinates that the padding exceeds kMaxGapOfSize of its size.
/// A leaf whose largest triangle is larger than this one is padded more and may still be
/// entered.
Lanes3 with_box_clearance(Lanes3 p, Lanes3 error, Lanes3 extent) {
  const float size = max_component(extent);
  const float gap =
      kBoxGapMargin * (kBoxSizeGap * size + kBoxCoordinateGap * max_component(abs_components(p)));
  if (!(gap <= kMaxGapOfSize * size)) return error;
  const Lanes3 gaps = lanes_of(gap);
  return extent < gaps ? component_max(error, gaps) : error;
}

/// The error of a float point rounded once from a double computation on inputs whose
/// magnitudes sum to `inputs` per component: half an ulp of the result plus the double's error.
Lanes3 rebuilt_point_error(Lanes3 p, Lanes3 inputs) {
  return lanes_of(rounding_gamma(1)) * abs_components(p) + lanes_of(0x1p-48f) * inputs;
}

}  // namespace

SurfaceInteraction Scene::surface_at(const Ray& ray, const Hit& hit) const {
  SurfaceInteraction si;
  si.t = hit.t;
  si.geom_id = hit.geom_id;
  si.prim_id = hit.prim_id;
  if (geometry.is_sphere(hit.geom_id)) {
    const Sphere& s = geometry.spheres[hit.prim_id];
    // The ray's point at t, reprojected onto the sphere in double, so the float point is one
    // rounding off it (no trigonometry: the hit's (u, v) are kept only as the uv).
    const DVec3 along = DVec3(ray.origin) + double(hit.t) * DVec3(ray.direction) - DVec3(s.center);
    const double along_length = glm::length(along);
    const DVec3 unit = along_length > 0.0 ? along / along_length : DVec3(0.0, 0.0, 1.0);
    const Vec3 n(unit);
    si.position = Vec3(DVec3(s.center) + unit * double(s.radius));
    si.position_error =
        vec3_of(rebuilt_point_error(lanes_of(si.position),
                                    abs_components(lanes_of(s.center)) + lanes_of(s.radius)) +
                lanes_of(kSphereTestGamma * s.radius));
    // The sphere's normal at the float point: far from the world origin the point's rounding
    // turns it visibly from n, and sides must be judged where the point is.
    const DVec3 radial = DVec3(si.position) - DVec3(s.center);
    const double radial_length = glm::length(radial);
    si.geometric_normal = radial_length > 0.0 ? Vec3(radial / radial_length) : n;
    si.shading_normal = si.geometric_normal;
    si.uv = Vec2(hit.u, hit.v);
    si.material_id = s.material_id;
    return si;
  }
  const TriangleMesh& mesh = geometry.meshes[hit.geom_id];
  Lanes3 a, b, c;
  if (const float* q = hit.vertex_lanes) {
    a = Lanes3{q[0], q[4], q[8], 0.0f};
    b = Lanes3{q[12], q[16], q[20], 0.0f};
    c = Lanes3{q[24], q[28], q[32], 0.0f};
  } else {
    const glm::uvec3 tri = mesh.triangles[hit.prim_id];
    a = lanes_of(mesh.positions[tri.x]);
    b = lanes_of(mesh.positions[tri.y]);
    c = lanes_of(mesh.positions[tri.z]);
  }
  const float w = 1.0f - hit.u - hit.v;
  // Each component in vector lanes (core/lanes3.h), by glm's operations: the same bits. The point
  // in double, as p0 + u (p1 - p0) + v (p2 - p0): the float point is one rounding off the
  // triangle's plane (a float 1 - u - v would move it off by a rounding of |p0| near edge p1 p2).
  const DoubleLanes3 da = __builtin_convertvector(a, DoubleLanes3);
  const DoubleLanes3 db = __builtin_convertvector(b, DoubleLanes3);
  const DoubleLanes3 dc = __builtin_convertvector(c, DoubleLanes3);
  const Lanes3 p =
      __builtin_convertvector(da + double(hit.u) * (db - da) + double(hit.v) * (dc - da), Lanes3);
  si.position = vec3_of(p);
  const Lanes3 reach = component_max(abs_components(a - p),
                                     component_max(abs_components(b - p), abs_components(c - p)));
  const float test_error = kTriangleTestGamma * max_component(reach);
  si.position_error = vec3_of(with_box_clearance(
      p,
      rebuilt_point_error(p, abs_components(a) + abs_components(b) + abs_components(c)) +
          lanes_of(test_error),
      triangle_extent(a, b, c)));
  const Lanes3 ng = cross(b - a, c - a);
  const float ng_length = std::sqrt(dot(ng, ng));
  const Lanes3 unit_ng =
      ng_length > 0.0f ? ng / lanes_of(ng_length) : lanes_of(-glm::normalize(ray.direction));
  si.geometric_normal = vec3_of(unit_ng);
  si.shading_normal = si.geometric_normal;
  if (!mesh.normals.empty()) {
    const size_t corner = 3 * size_t(hit.prim_id);
    const Lanes3 ns = lanes_of(w) * lanes_of(mesh.normals[corner]) +
                      lanes_of(hit.u) * lanes_of(mesh.normals[corner + 1]) +
                      lanes_of(hit.v) * lanes_of(mesh.normals[corner + 2]);
    const float ns_length = std::sqrt(dot(ns, ns));
    if (ns_length > 0.0f && std::isfinite(ns_length)) {
      const Lanes3 unit_ns = ns / lanes_of(ns_length);
      si.shading_normal = vec3_of(unit_ns);
      // Files whose winding disagrees with their normals (the CS184 Cornell floor): trust the
      // authored normal and turn the geometric one to its side.
      if (dot(unit_ns, unit_ng) < 0.0f) si.geometric_normal = -si.geometric_normal;
    }
  }
  if (!mesh.uvs.empty()) {
    const size_t corner = 3 * size_t(hit.prim_id);
    si.uv = w * mesh.uvs[corner] + hit.u * mesh.uvs[corner + 1] + hit.v * mesh.uvs[corner + 2];
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

Vec3 offset_ray_origin(const Vec3& p, const Vec3& error, const Vec3& geometric_normal,
                       const Vec3& toward) {
  const float distance = glm::dot(abs_components(geometric_normal), error);
  const Vec3 n = glm::dot(geometric_normal, toward) >= 0.0f ? geometric_normal : -geometric_normal;
  Vec3 origin = p + distance * n;
  // p + distance * n may round back toward p by half an ulp: one more ulp outward makes the
  // move at least `distance` along every axis the normal has a component on.
  for (int k = 0; k < 3; ++k) {
    if (n[k] > 0.0f) {
      origin[k] = next_float_up(origin[k]);
    } else if (n[k] < 0.0f) {
      origin[k] = next_float_down(origin[k]);
    }
  }
  return origin;
}

Ray spawn_ray(const SurfaceInteraction& si, const Vec3& direction) {
  return build_ray(
      offset_ray_origin(si.position, si.position_error, si.geometric_normal, direction), direction,
      0.0f, kInfinity);
}

Ray spawn_ray_to(const SurfaceInteraction& si, const Vec3& target) {
  const Vec3 origin =
      offset_ray_origin(si.position, si.position_error, si.geometric_normal, target - si.position);
  const Vec3 direction = target - origin;
  // A target computed from a point far from the world origin is only known to a few ulps of its
  // coordinates: stop short of it by that too, or it may lie just behind its emitter.
  const float rounding = kTargetGamma * (max_component(abs_components(target)) +
                                         max_component(abs_components(origin)));
  const float length = glm::length(direction);
  const float short_of = std::max(kShadowEpsilon, rounding / length);
  return build_ray(origin, direction, 0.0f, short_of < 1.0f ? 1.0f - short_of : 0.0f);
}

}  // namespace prism
