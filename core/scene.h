#pragma once

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
  Vec3 position;          ///< rebuilt from (prim, u, v), not from origin + t * dir
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

/// A point offset off a surface along its geometric normal by an amount that scales with the
/// point's magnitude, so secondary rays from it do not re-hit the same surface. `toward` is the
/// side (direction of the new ray) to move to. Shared by all backends.
Vec3 offset_ray_origin(const Vec3& p, const Vec3& geometric_normal, const Vec3& toward);

}  // namespace prism
