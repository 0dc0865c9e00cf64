#pragma once

#include "core/camera.h"
#include "core/scene.h"
#include "core/texture.h"

namespace prism {

/// How wide a pixel is where it meets a surface, for texture filtering.
struct TextureFilter {
  Vec3 eye{0.0f};  ///< the camera's position
  /// Footprint width per unit of distance from `eye`; 0: no filtering (the finest MIP level).
  float spread = 0.0f;
};

/// The filter of a render with `camera` (fitted to the image), an image `image_height` pixels
/// high and `spp` samples per pixel: spread = 2 tan(vfov / 2) / image_height x max(1/8,
/// 1/sqrt(spp)), the width of one pixel at unit distance, narrowed as the pixel's samples
/// supersample it (as pbrt-v4 does). image_height <= 0 gives no filtering.
TextureFilter camera_texture_filter(const Camera& camera, int image_height, int spp);

/// The texture lookups of one render (docs/SCENE_FORMAT.md, "Textures"). Every hit is
/// filtered as the camera would see it, whatever path reached it (pbrt-v4's approximation of
/// ray differentials): the footprint is `spread` x its distance from the eye across the view
/// direction and that divided by |cos| (at most 20 times) along it, on the surface, mapped to
/// uv by the triangle's (or sphere's) uv parameterisation. Built once per render; thread-safe.
class SurfaceTextures {
 public:
  /// Throws Error(kInternal) when a material of `scene` names a texture and the scene's
  /// textures were not loaded (Scene::texture_lookup). `scene` must outlive this.
  SurfaceTextures(const Scene& scene, const TextureFilter& filter);

  /// R, G, B of `texture` at the surface `si`, filtered over its footprint.
  Rgb at(uint32_t texture, const SurfaceInteraction& si) const;
  /// R, G, B of `texture` at `uv`, unfiltered (the finest level; points sampled on lights).
  Rgb at_uv(uint32_t texture, Vec2 uv) const;
  /// The mean of `texture`.
  Rgb average(uint32_t texture) const;

  /// `material`'s reflectance at `si`: reflectance x its texture, clamped to [0, 1].
  Rgb reflectance(const Material& material, const SurfaceInteraction& si) const;
  /// `material`'s emitted radiance at `si`: radiance x its texture, at least 0.
  Rgb radiance(const Material& material, const SurfaceInteraction& si) const;

 private:
  /// The uv offsets spanning the footprint of `si` (zero without filtering).
  void footprint(const SurfaceInteraction& si, Vec2& duv_dx, Vec2& duv_dy) const;

  const Scene& scene_;
  TextureFilter filter_;
  const TextureLookup* lookup_;
};

}  // namespace prism
