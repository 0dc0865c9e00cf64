#pragma once

#include <cstdint>

#include "core/scene.h"

namespace prism {

/// A 64-bit hash (FNV-1a) of everything in `scene` that decides a pixel: geometry (positions,
/// triangles, normals, uvs, material ids, spheres), materials, lights, camera, render settings,
/// the environment map's pixels and orientation, and the textures' pixels once loaded
/// (Scene::texture_lookup). Equal scenes hash equally on every
/// machine; a change in any of them (in the scene file or a mesh file it names) changes it but
/// for a 2^-64 chance. Not names or the source path.
uint64_t scene_hash(const Scene& scene);

}  // namespace prism
