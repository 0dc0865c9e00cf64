#include "accel/embree/embree_spheres.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/primitive_intersection.h"
#include "core/ray.h"

namespace prism {
namespace {

void sphere_bounds(const RTCBoundsFunctionArguments* args) {
  const Sphere& s = static_cast<const Sphere*>(args->geometryUserPtr)[args->primID];
  // Embree's non-robust box test can cull a box that a grazing ray only touches; a margin far
  // below any visible size keeps it from dropping hits intersect_sphere() would report.
  const float scale = std::max({std::abs(s.center.x), std::abs(s.center.y), std::abs(s.center.z)});
  const Vec3 pad(s.radius * 0x1p-16f + scale * 0x1p-20f);
  const Bounds3 b = s.bounds();
  *args->bounds_o = RTCBounds{b.lower.x - pad.x, b.lower.y - pad.y, b.lower.z - pad.z, 0.0f,
                              b.upper.x + pad.x, b.upper.y + pad.y, b.upper.z + pad.z, 0.0f};
}

/// Ray i of a ray packet, with the query's own tmin and the packet's current tfar.
Ray packet_ray(RTCRayN* rays, unsigned int n, unsigned int i, float tmin) {
  Ray r;
  r.origin = Vec3(RTCRayN_org_x(rays, n, i), RTCRayN_org_y(rays, n, i), RTCRayN_org_z(rays, n, i));
  r.direction =
      Vec3(RTCRayN_dir_x(rays, n, i), RTCRayN_dir_y(rays, n, i), RTCRayN_dir_z(rays, n, i));
  r.tmin = tmin;
  r.tmax = RTCRayN_tfar(rays, n, i);
  return r;
}

void sphere_intersect(const RTCIntersectFunctionNArguments* args) {
  const Sphere& s = static_cast<const Sphere*>(args->geometryUserPtr)[args->primID];
  const auto* context = reinterpret_cast<const EmbreeQueryContext*>(args->context);
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, args->N);
  for (unsigned int i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const Ray ray = packet_ray(rays, args->N, i, context->tmin);
    const std::optional<PrimitiveHit> h = intersect_sphere(ray, s.center, s.radius);
    if (!h) continue;
    unsigned int& geom_id = RTCHitN_geomID(hits, args->N, i);
    unsigned int& prim_id = RTCHitN_primID(hits, args->N, i);
    const bool tie = h->t == ray.tmax && geom_id != RTC_INVALID_GEOMETRY_ID;
    if (tie && !(geom_id == args->geomID && args->primID < prim_id)) continue;
    const Vec3 normal = ray.at(h->t) - s.center;
    RTCRayN_tfar(rays, args->N, i) = h->t;
    RTCHitN_Ng_x(hits, args->N, i) = normal.x;
    RTCHitN_Ng_y(hits, args->N, i) = normal.y;
    RTCHitN_Ng_z(hits, args->N, i) = normal.z;
    RTCHitN_u(hits, args->N, i) = h->u;
    RTCHitN_v(hits, args->N, i) = h->v;
    prim_id = args->primID;
    geom_id = args->geomID;
    RTCHitN_instID(hits, args->N, i, 0) = context->base.instID[0];
  }
}

void sphere_occluded(const RTCOccludedFunctionNArguments* args) {
  const Sphere& s = static_cast<const Sphere*>(args->geometryUserPtr)[args->primID];
  const auto* context = reinterpret_cast<const EmbreeQueryContext*>(args->context);
  for (unsigned int i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const Ray ray = packet_ray(args->ray, args->N, i, context->tmin);
    // Embree's convention for "occluded": tfar becomes -inf.
    if (intersect_sphere_t(ray, s.center, s.radius))
      RTCRayN_tfar(args->ray, args->N, i) = -kInfinity;
  }
}

}  // namespace

void attach_sphere_geometry(RTCDevice device, RTCScene scene, const std::vector<Sphere>& spheres,
                            unsigned int geom_id) {
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  if (geometry == nullptr) return;  // the device's error callback has the reason
  rtcSetGeometryUserPrimitiveCount(geometry, static_cast<unsigned int>(spheres.size()));
  rtcSetGeometryUserData(geometry, const_cast<Sphere*>(spheres.data()));
  rtcSetGeometryBoundsFunction(geometry, &sphere_bounds, nullptr);
  rtcSetGeometryIntersectFunction(geometry, &sphere_intersect);
  rtcSetGeometryOccludedFunction(geometry, &sphere_occluded);
  rtcCommitGeometry(geometry);
  rtcAttachGeometryByID(scene, geometry, geom_id);
  rtcReleaseGeometry(geometry);
}

}  // namespace prism
