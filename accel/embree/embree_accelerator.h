#pragma once

#include <embree3/rtcore.h>

#include <memory>
#include <optional>
#include <string_view>

#include "accel/accelerator.h"
#include "accel/embree/embree_device.h"

namespace prism {

/// Intel Embree 3 as a backend. One device per accelerator; triangle meshes share the scene's
/// own vertex and index buffers (TriangleMesh::finalize() must have run: Embree reads 16 bytes
/// at the last vertex); all spheres form one user geometry running core's sphere test. Embree
/// geometry ids equal prism's geom_ids.
///
/// Parameters: embree.robust (bool, default false: RTC_SCENE_FLAG_ROBUST), embree.quality
/// (low | medium | high, default medium: the BVH build quality), embree.refine (bool, default
/// true: t, u, v of a triangle hit are recomputed by core's watertight test on the primitive
/// Embree chose, so renders with bvh and embree differ only where the backends pick different
/// primitives; false gives Embree's own values, as `prism bench` and the differential test use).
///
/// Interval convention: Embree accepts a triangle at t only if tnear < t <= tfar, evaluated in
/// its own scaled arithmetic (t * |den| against tnear * |den|). To honour prism's closed
/// [tmin, tmax] it is given tnear = the float below tmin, and the t it reports is clamped into
/// [tmin, tmax] (the final division may round it by an ulp). What remains different: a hit at
/// exactly t = 0 with tmin = 0 (origin on a triangle) is not reported, and Embree's triangle
/// test is its own (not watertight unless embree.robust), so without refinement its t, u, v
/// differ from brute force by rounding. Sphere hits are bit for bit those of brute force.
class EmbreeAccelerator final : public Accelerator {
 public:
  /// Reads the parameters (throws Error(kUsage) on a bad value) and creates the device
  /// (throws Error if Embree cannot).
  explicit EmbreeAccelerator(const ParamSet& params);
  ~EmbreeAccelerator() override;
  EmbreeAccelerator(const EmbreeAccelerator&) = delete;
  EmbreeAccelerator& operator=(const EmbreeAccelerator&) = delete;

  std::string_view name() const override { return "embree"; }

 protected:
  /// Builds the Embree scene on `geometry` and throws the first error Embree reported
  /// (kResource for out-of-memory, else kInternal).
  void build_structure(const SceneGeometry& geometry) override;
  std::optional<Hit> intersect_prepared(const Ray& ray) const override;
  bool occluded_prepared(const Ray& ray) const override;
  /// bytes (Embree's memory monitor: everything the device holds after the build); Embree does
  /// not expose node counts, depth or SAH cost, so those are 0.
  AccelStats structure_stats() const override { return stats_; }

 private:
  /// Recomputes t, u, v of a triangle hit with core's watertight test (embree.refine).
  void refine_triangle_hit(const Ray& ray, Hit& hit) const;

  bool robust_ = false;
  bool refine_ = true;
  RTCBuildQuality quality_ = RTC_BUILD_QUALITY_MEDIUM;
  std::unique_ptr<EmbreeDevice> device_;
  RTCScene scene_ = nullptr;
  AccelStats stats_;
};

}  // namespace prism
