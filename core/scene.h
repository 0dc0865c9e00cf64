#pragma once

#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/hit.h"
#include "core/image.h"
#include "core/light.h"
#include "core/material.h"
#include "core/ray.h"
#include "core/scene_geometry.h"
#include "core/texture.h"

namespace prism {

/// Render settings a scene file may carry. Command-line flags override every one of them.
struct SceneRenderSettings {
  std::optional<int> width, height;
  std::optional<int> spp;
  std::optional<int> max_depth;
  std::optional<std::string> integrator;
  std::optional<uint64_t> seed;
};

/// Local geometry at a hit, computed the same way for every accelerator.
struct SurfaceInteraction {
  Vec3 position;  ///< rebuilt from (prim, u, v), not from origin + t * dir
  /// Per component, a conservative bound on how far the surface, as the ray tests see it from a
  /// ray starting next to `position`, may be from `position`: the rounding of the rebuilt point
  /// plus the tests' own rounding (offset_ray_origin() clears it).
  Vec3 position_error{0.0f};
  Vec3 geometric_normal;  ///< unit; in the hemisphere of the shading normal
  Vec3 shading_normal;    ///< unit; interpolated per-corner normal, else the geometric one
  Vec2 uv;
  float t = 0.0f;
  uint32_t material_id = 0;
  uint32_t geom_id = 0;
  uint32_t prim_id = 0;
};

/// An environment map surrounding the scene at infinity (-e). Plain data; the lights read it.
struct SceneEnvironment {
  /// Radiance in latitude-longitude layout: channels R, G, B in the working space, columns
  /// spanning 360 degrees, rows 180 from the pole along `up` (row 0) to the opposite one.
  Image image;
  Vec3 up{0.0f, 1.0f, 0.0f};  ///< the pole of row 0: the scene camera's up when it was added
  std::string file;           ///< the file it was read from, as given (provenance)
  std::string color_space;    ///< the colour space the file's values were read as (provenance)
};

/// A loaded scene: plain data, independent of any accelerator.
struct Scene {
  std::string source;  ///< file it came from, or a description for built-in scenes
  SceneGeometry geometry;
  std::vector<Material> materials;
  /// The images materials name (Material::reflectance_texture, radiance_texture).
  std::vector<TextureSource> textures;
  std::vector<Light> lights;
  Camera camera;
  SceneRenderSettings settings;
  /// Set by the render driver from -e (scene files do not name one); none: no environment.
  std::optional<SceneEnvironment> environment;
  /// Lookups in `textures`, converted to the working space: set by the render driver
  /// (load_scene_textures() in color/texture_set.h) before rendering; null until then. Shading
  /// a textured material without it is an internal error.
  std::shared_ptr<const TextureLookup> texture_lookup;
  /// Defects of the file the loader tolerated, in the order found, one line each
  /// ("file:line: <element>: what was read instead"); the driver prints each as
  /// "prism: warning: ...". They never change scene_hash().
  std::vector<std::string> warnings;

  /// The surface at `hit` of `ray` (hit must come from an accelerator built on this geometry).
  SurfaceInteraction surface_at(const Ray& ray, const Hit& hit) const;

  /// Checks geometry, camera, every material id and texture index: throws Error(kInput) naming
  /// the element.
  void validate() const;
};

/// gamma(n) = n u / (1 - n u) with u = 2^-24: bounds the relative error of n float operations
/// (Higham; pbrt-v4's error analysis).
constexpr float rounding_gamma(int n) {
  constexpr float u = 0.5f * std::numeric_limits<float>::epsilon();
  return (float(n) * u) / (1.0f - float(n) * u);
}

/// Shadow rays stop this fraction of their length short of the point they aim at (at least;
/// see spawn_ray_to()), so they do not hit the emitter that point lies on.
inline constexpr float kShadowEpsilon = 1e-4f;

/// The origin of a ray leaving the surface point `p` toward `toward`'s side of the surface:
/// p moved along the geometric normal by dot(|n|, error) (`error`: the surface point's
/// SurfaceInteraction::position_error), to `toward`'s side, each moved coordinate then rounded
/// one more float away from p. Nothing but the coordinates' own precision sets the distance, so
/// it holds at every scale and distance from the world origin. Shared by all backends.
Vec3 offset_ray_origin(const Vec3& p, const Vec3& error, const Vec3& geometric_normal,
                       const Vec3& toward);

/// The ray leaving `si` along `direction` (not necessarily unit): from offset_ray_origin(),
/// t in [0, infinity).
Ray spawn_ray(const SurfaceInteraction& si, const Vec3& direction);

/// The ray from `si` to `target` (a light point): from offset_ray_origin() toward the target,
/// direction target - origin, ending short of the target by kShadowEpsilon of the length or,
/// when larger, by the rounding error of the coordinates at the ends, so a target rebuilt on an
/// emitter far from the world origin does not land behind it.
Ray spawn_ray_to(const SurfaceInteraction& si, const Vec3& target);

}  // namespace prism
