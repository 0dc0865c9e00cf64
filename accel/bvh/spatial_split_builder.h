#pragma once

#include <vector>

#include "accel/bvh/build_reference.h"
#include "core/scene_geometry.h"

namespace prism {

/// Builds a binary BVH with binned SAH object splits and, where the children of the best object
/// split overlap by more than settings.spatial_alpha of the root's area, spatial splits that
/// clip triangles at a plane (Stich, Friedrich, Dietrich 2009: "SBVH"). A clipped triangle is
/// referenced from both sides with bounds of its part on each; duplication stops once
/// settings.spatial_budget x the primitive count of extra references exist. Spheres are never
/// clipped by geometry, only their boxes. Same guarantees as build_object_split_bvh().
BinaryBvh build_spatial_split_bvh(const SceneGeometry& geometry, std::vector<PrimRef> refs,
                                  const BvhBuildSettings& settings);

}  // namespace prism
