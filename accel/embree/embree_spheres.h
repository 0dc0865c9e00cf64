#pragma once

#include <embree3/rtcore.h>

#include <vector>

#include "core/scene_geometry.h"

namespace prism {

/// The intersect context of every Embree query prism makes. Embree hands `base` back to user
/// geometry callbacks, which read the query's own tmin from it (the tnear given to Embree is
/// shifted, see EmbreeAccelerator).
struct EmbreeQueryContext {
  RTCIntersectContext base;  // must stay first: callbacks cast the context pointer back
  float tmin;
};

/// Creates ONE user geometry for all `spheres` (primID = sphere index) whose callbacks run
/// core's intersect_sphere(), so sphere hits match brute force bit for bit, and attaches it to
/// `scene` under `geom_id`. `spheres` must outlive the scene. Queries must pass an
/// EmbreeQueryContext. At exactly equal t the callback keeps a hit on a lower geom_id or on a
/// lower-numbered sphere, as comes_before() does.
void attach_sphere_geometry(RTCDevice device, RTCScene scene, const std::vector<Sphere>& spheres,
                            unsigned int geom_id);

}  // namespace prism
