#include "accel/embree/embree_accelerator.h"

#include "core/primitive_intersection.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "accel/embree/embree_spheres.h"
#include "core/error.h"

namespace prism {
namespace {

RTCBuildQuality parse_quality(const std::string& value) {
  if (value == "low") return RTC_BUILD_QUALITY_LOW;
  if (value == "medium") return RTC_BUILD_QUALITY_MEDIUM;
  if (value == "high") return RTC_BUILD_QUALITY_HIGH;
  throw Error(ErrorKind::kUsage,
              "parameter 'embree.quality': '" + value + "' is not one of low, medium, high");
}

/// tnear for Embree's half-open (tnear, tfar] so that t == tmin is still accepted.
float embree_tnear(float tmin) { return tmin > 0.0f ? std::nextafter(tmin, 0.0f) : 0.0f; }

void attach_mesh(RTCDevice device, RTCScene scene, const TriangleMesh& mesh, unsigned int id) {
  // Embree loads vertices 16 bytes at a time: the last one needs 4 readable bytes after it.
  PRISM_CHECK(mesh.positions.capacity() >= mesh.positions.size() + 1);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  if (geometry == nullptr) return;  // the device's error callback has the reason
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                             mesh.positions.data(), 0, sizeof(Vec3), mesh.positions.size());
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                             mesh.triangles.data(), 0, sizeof(glm::uvec3), mesh.triangles.size());
  rtcCommitGeometry(geometry);
  rtcAttachGeometryByID(scene, geometry, id);
  rtcReleaseGeometry(geometry);
}

void fill_ray(const Ray& ray, RTCRay& out) {
  out.org_x = ray.origin.x;
  out.org_y = ray.origin.y;
  out.org_z = ray.origin.z;
  out.tnear = embree_tnear(ray.tmin);
  out.dir_x = ray.direction.x;
  out.dir_y = ray.direction.y;
  out.dir_z = ray.direction.z;
  out.time = 0.0f;
  out.tfar = ray.tmax;
  out.mask = ~0u;
  out.id = 0;
  out.flags = 0;
}

}  // namespace

void EmbreeAccelerator::refine_triangle_hit(const Ray& ray, Hit& hit) const {
  // Embree's triangle test rounds differently from core's watertight test, so the same
  // primitive gets (t, u, v) a few ulps apart and interpolated normals differ in the last bits.
  // Re-running the shared test on the primitive Embree chose makes the backends differ only in
  // which primitive they choose (ties), never in the values for it.
  const TriangleMesh& mesh = geometry().meshes[hit.geom_id];
  const glm::uvec3 tri = mesh.triangles[hit.prim_id];
  const auto exact = intersect_triangle(WatertightRay(ray), mesh.positions[tri.x],
                                        mesh.positions[tri.y], mesh.positions[tri.z]);
  if (exact) {
    hit.t = exact->t;
    hit.u = exact->u;
    hit.v = exact->v;
  }
}

EmbreeAccelerator::EmbreeAccelerator(const ParamSet& params)
    : robust_(params.get_bool("embree.robust", false)),
      refine_(params.get_bool("embree.refine", true)),
      quality_(parse_quality(params.get_string("embree.quality", "medium"))),
      device_(std::make_unique<EmbreeDevice>()) {}

EmbreeAccelerator::~EmbreeAccelerator() {
  if (scene_ != nullptr) rtcReleaseScene(scene_);
}

void EmbreeAccelerator::build_structure(const SceneGeometry& geometry) {
  if (scene_ != nullptr) {
    rtcReleaseScene(scene_);
    scene_ = nullptr;
  }
  RTCDevice device = device_->handle();
  device_->throw_pending_error("before building the Embree scene");

  RTCScene scene = rtcNewScene(device);
  if (scene == nullptr) device_->throw_pending_error("creating the Embree scene");
  PRISM_CHECK(scene != nullptr);
  try {
    rtcSetSceneFlags(scene, robust_ ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
    rtcSetSceneBuildQuality(scene, quality_);
    for (size_t i = 0; i < geometry.meshes.size(); ++i) {
      // Ids are given explicitly, so skipping an empty mesh keeps the others' ids right.
      if (geometry.meshes[i].triangles.empty()) continue;
      attach_mesh(device, scene, geometry.meshes[i], static_cast<unsigned int>(i));
    }
    if (!geometry.spheres.empty()) {
      attach_sphere_geometry(device, scene, geometry.spheres, geometry.sphere_geom_id());
    }
    rtcCommitScene(scene);
    device_->throw_pending_error("building the Embree scene");
  } catch (...) {
    rtcReleaseScene(scene);
    throw;
  }
  scene_ = scene;
  stats_ = {};
  stats_.bytes = device_->bytes_in_use();
}

std::optional<Hit> EmbreeAccelerator::intersect_prepared(const Ray& ray) const {
  EmbreeQueryContext context;
  rtcInitIntersectContext(&context.base);
  context.tmin = ray.tmin;
  RTCRayHit rayhit;
  fill_ray(ray, rayhit.ray);
  rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rayhit.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context.base, &rayhit);
  if (rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  const float t = std::clamp(rayhit.ray.tfar, ray.tmin, ray.tmax);
  Hit hit{t, rayhit.hit.u, rayhit.hit.v, rayhit.hit.geomID, rayhit.hit.primID};
  if (refine_ && !geometry().is_sphere(hit.geom_id)) refine_triangle_hit(ray, hit);
  return hit;
}

bool EmbreeAccelerator::occluded_prepared(const Ray& ray) const {
  EmbreeQueryContext context;
  rtcInitIntersectContext(&context.base);
  context.tmin = ray.tmin;
  RTCRay embree_ray;
  fill_ray(ray, embree_ray);
  rtcOccluded1(scene_, &context.base, &embree_ray);
  return embree_ray.tfar == -kInfinity;
}

}  // namespace prism
