// Texture lookups in shading (integrators/surface_textures.*, ShadingContext::bsdf_at, textured
// emitters): the footprint rule, per-hit BSDFs, emission textures, and renders of textured
// surfaces. A lookup written for the tests stands in for OpenImageIO's (tested in
// color_texture_test.cpp), so every value here is known exactly.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <mutex>
#include <vector>

#include "core/error.h"
#include "integrators/bsdf/bsdf_factory.h"
#include "integrators/light_transport.h"
#include "integrators/lights/area_light.h"
#include "tests/support/integrators_test_scenes.h"

namespace prism {
namespace {

/// A texture of four quadrants (v up): red top left, green top right, blue bottom left, white
/// bottom right, repeating; remembers the last footprint asked for.
class QuadrantLookup final : public TextureLookup {
 public:
  size_t size() const override { return 1; }
  Rgb lookup(uint32_t, Vec2 uv, Vec2 dx, Vec2 dy) const override {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      last_dx = dx;
      last_dy = dy;
    }
    const float u = uv.x - std::floor(uv.x), v = uv.y - std::floor(uv.y);
    if (v >= 0.5f) return u < 0.5f ? Rgb(1, 0, 0) : Rgb(0, 1, 0);
    return u < 0.5f ? Rgb(0, 0, 1) : Rgb(1, 1, 1);
  }
  Rgb average(uint32_t) const override { return Rgb(0.5f); }
  uint64_t content_hash() const override { return 1; }

  mutable Vec2 last_dx{0.0f}, last_dy{0.0f};

 private:
  mutable std::mutex mutex_;
};

/// A 2 x 2 quad in z = 0 facing +z with uvs spanning [0, 1]^2, material `material`, and a
/// camera on +z looking at it.
Scene textured_quad_scene(const Material& material) {
  Scene scene;
  scene.source = "textured quad (built in code)";
  scene.materials.push_back(material);
  TriangleMesh quad = test::quad("quad", {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, 0);
  // Per corner: (0,1,2), (0,2,3).
  quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
  scene.geometry.meshes.push_back(quad);
  TextureSource source;
  source.name = "quadrants";
  scene.textures.push_back(source);
  scene.texture_lookup = std::make_shared<QuadrantLookup>();
  test::aim_camera_and_finish(scene, {0, 0, 4}, {0, 0, 0}, scene.camera.up, 40.0f);
  return scene;
}

Material diffuse_textured(const Rgb& reflectance) {
  Material m;
  m.name = "textured";
  m.type = MaterialType::kDiffuse;
  m.reflectance = reflectance;
  m.reflectance_texture = 0;
  return m;
}

/// The surface at (x, y) of the quad seen along -z.
SurfaceInteraction quad_point(const Scene& scene, float x, float y) {
  Ray ray;
  ray.origin = Vec3(x, y, 4);
  ray.direction = Vec3(0, 0, -1);
  // The hit (u, v) on triangle 0 or 1 by hand: the quad is the square [-1, 1]^2.
  Hit hit;
  hit.t = 4;
  hit.geom_id = 0;
  const float s = 0.5f * (x + 1), t = 0.5f * (y + 1);
  if (s >= t) {  // triangle (0, 1, 2): p = p0 + u (p1 - p0) + v (p2 - p0)
    hit.prim_id = 0;
    hit.u = s - t;
    hit.v = t;
  } else {  // triangle (0, 2, 3)
    hit.prim_id = 1;
    hit.u = s;
    hit.v = t - s;
  }
  return scene.surface_at(ray, hit);
}

TEST(IntegratorsSurfaceTextures, TheFootprintIsAPixelAtTheHitsDistance) {
  const Scene scene = textured_quad_scene(diffuse_textured(Rgb(1.0f)));
  const auto& lookup = static_cast<const QuadrantLookup&>(*scene.texture_lookup);
  // One pixel of a 100-pixel-high image, 1 sample per pixel.
  const TextureFilter filter = camera_texture_filter(scene.camera, 100, 1);
  const float pixel = 2.0f * std::tan(radians(20.0f)) / 100.0f;
  EXPECT_NEAR(filter.spread, pixel, 1e-7f);
  EXPECT_NEAR(camera_texture_filter(scene.camera, 100, 16).spread, pixel / 4, 1e-7f);
  EXPECT_NEAR(camera_texture_filter(scene.camera, 100, 1024).spread, pixel / 8, 1e-7f);
  EXPECT_EQ(camera_texture_filter(scene.camera, 0, 1).spread, 0.0f);

  const SurfaceTextures textures(scene, filter);
  // Nearly head-on at distance d: the footprint is d pixel widths of world space across the
  // view (d / cos along it), and one world unit is half a uv unit.
  textures.at(0, quad_point(scene, 0.2f, 0.3f));
  const float d = std::sqrt(16.0f + 0.04f + 0.09f), cos_view = 4.0f / d;
  EXPECT_NEAR(glm::length(lookup.last_dx), 0.5f * d * pixel, 1e-6f);
  EXPECT_NEAR(glm::length(lookup.last_dy), 0.5f * d * pixel / cos_view, 1e-6f);
  EXPECT_NEAR(glm::dot(lookup.last_dx, lookup.last_dy), 0.0f, 1e-9f);

  // Seen at 60 degrees from the normal, the footprint doubles along the view direction.
  SurfaceTextures oblique(scene, {Vec3(0.0f, -4.0f * std::sqrt(3.0f), 4.0f), filter.spread});
  oblique.at(0, quad_point(scene, 0.0f, 0.0f));
  const float width = 8.0f * pixel;  // distance 8
  EXPECT_NEAR(glm::length(lookup.last_dx), 0.5f * width, 1e-5f);
  EXPECT_NEAR(glm::length(lookup.last_dy), 0.5f * width * 2.0f, 1e-5f);
  EXPECT_NEAR(std::abs(lookup.last_dy.y), glm::length(lookup.last_dy), 1e-6f);  // along v

  SurfaceTextures unfiltered(scene, TextureFilter{});
  unfiltered.at(0, quad_point(scene, 0.2f, 0.3f));
  EXPECT_EQ(lookup.last_dx, Vec2(0.0f));
  EXPECT_EQ(lookup.last_dy, Vec2(0.0f));
}

TEST(IntegratorsSurfaceTextures, TexturedMaterialsGetAPerHitBsdf) {
  Scene scene = textured_quad_scene(diffuse_textured(Rgb(0.5f)));
  Material plain;
  plain.name = "plain";
  plain.reflectance = Rgb(0.25f);
  scene.materials.push_back(plain);
  Material metal;
  metal.name = "metal";
  metal.type = MaterialType::kMicrofacet;
  metal.reflectance = Rgb(0.8f);
  metal.reflectance_texture = 0;
  metal.alpha = 0.3f;
  scene.materials.push_back(metal);
  const ShadingContext shading(scene, BsdfOptions{}, LightOptions{});
  BsdfStorage storage;
  SurfaceInteraction si = quad_point(scene, -0.5f, 0.5f);  // top left: red
  const Bsdf& red = shading.bsdf_at(si, storage);
  EXPECT_EQ(red.albedo(), Rgb(0.5f, 0.0f, 0.0f));
  EXPECT_TRUE(red.lobes() & kLobeDiffuse);
  si = quad_point(scene, 0.5f, -0.5f);  // bottom right: white
  EXPECT_EQ(shading.bsdf_at(si, storage).albedo(), Rgb(0.5f));

  si.material_id = 1;  // untextured: the shared BSDF, nothing built
  EXPECT_EQ(&shading.bsdf_at(si, storage), shading.bsdfs[1].get());

  si.material_id = 2;  // a textured metal: eta and k from 0.8 x white at this point
  const Bsdf& conductor = shading.bsdf_at(si, storage);
  EXPECT_TRUE(conductor.lobes() & kLobeGlossy);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(conductor.albedo()[c], 0.8f, 1e-4f);
}

TEST(IntegratorsSurfaceTextures, TexturesNeedTheirLookups) {
  Scene scene = textured_quad_scene(diffuse_textured(Rgb(0.5f)));
  scene.texture_lookup.reset();
  try {
    const ShadingContext shading(scene, BsdfOptions{}, LightOptions{});
    FAIL() << "shading a textured scene without its lookups";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInternal);
    EXPECT_NE(e.message().find("not loaded"), std::string::npos) << e.message();
  }
}

TEST(IntegratorsSurfaceTextures, EmissionTexturesShapeTheLight) {
  Material lamp;
  lamp.name = "screen";
  lamp.type = MaterialType::kEmission;
  lamp.radiance = Rgb(2.0f);
  lamp.radiance_texture = 0;
  const Scene scene = textured_quad_scene(lamp);
  const ShadingContext shading(scene, BsdfOptions{}, LightOptions{});
  ASSERT_EQ(shading.lights.size(), 1u);
  const LightSource& light = *shading.lights.lights()[0];
  EXPECT_EQ(light.le(quad_point(scene, -0.5f, 0.5f), Vec3(0, 0, 1)), Rgb(2, 0, 0));
  EXPECT_EQ(light.le(quad_point(scene, 0.5f, 0.5f), Vec3(0, 0, 1)), Rgb(0, 2, 0));
  EXPECT_EQ(light.le(quad_point(scene, 0.5f, 0.5f), Vec3(0, 0, -1)), Rgb(0.0f));  // the back
  // Power from the texture's mean (0.5): pi x area 4 x 2 x 0.5.
  EXPECT_NEAR(light.power().r, kPi * 4.0f, 1e-4f);
  // Light sampling sees the texture where it lands.
  const Vec3 p(0, 0, 3);
  for (int i = 0; i < 64; ++i) {
    const Vec2 u((i % 8 + 0.5f) / 8.0f, (i / 8 + 0.5f) / 8.0f);
    const std::optional<LightLiSample> s = light.sample_li(p, u);
    ASSERT_TRUE(s.has_value());
    const Vec3 q = p + s->distance * s->wi;
    const Rgb expected = 2.0f * (q.y >= 0 ? (q.x < 0 ? Rgb(1, 0, 0) : Rgb(0, 1, 0))
                                          : (q.x < 0 ? Rgb(0, 0, 1) : Rgb(1, 1, 1)));
    if (std::abs(q.x) > 1e-3f && std::abs(q.y) > 1e-3f) {
      EXPECT_EQ(s->li, expected) << "sample at " << q.x << ", " << q.y;
    }
  }
}

TEST(IntegratorsSurfaceTextures, RendersShowTheTexture) {
  // An emissive screen seen directly: every pixel is exactly its quadrant's radiance.
  Material lamp;
  lamp.name = "screen";
  lamp.type = MaterialType::kEmission;
  lamp.radiance = Rgb(1.0f);
  lamp.radiance_texture = 0;
  const Scene screen = textured_quad_scene(lamp);
  test::TestRender r;
  r.width = r.height = 32;
  r.spp = 4;
  const Image image = test::render_scene(screen, "direct", r);
  // The quad spans the middle of the picture; sample well inside each quadrant.
  const auto pixel = [&](int x, int y) {
    return Rgb(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2));
  };
  EXPECT_EQ(pixel(12, 12), Rgb(1, 0, 0));  // top left of the image
  EXPECT_EQ(pixel(19, 12), Rgb(0, 1, 0));
  EXPECT_EQ(pixel(12, 19), Rgb(0, 0, 1));
  EXPECT_EQ(pixel(19, 19), Rgb(1, 1, 1));

  // A textured diffuse quad lit head-on by a directional light: red where the texture is red.
  Scene lit = textured_quad_scene(diffuse_textured(Rgb(1.0f)));
  Light sun;
  sun.type = LightType::kDirectional;
  sun.direction = Vec3(0, 0, -1);
  sun.color = Rgb(kPi);
  lit.lights.push_back(sun);
  const Image shaded = test::render_scene(lit, "path", r);
  EXPECT_NEAR(shaded.at(12, 12, 0), 1.0f, 1e-4f);
  EXPECT_NEAR(shaded.at(12, 12, 1), 0.0f, 1e-6f);
  EXPECT_NEAR(shaded.at(19, 12, 1), 1.0f, 1e-4f);
  EXPECT_NEAR(shaded.at(12, 19, 2), 1.0f, 1e-4f);
  // The albedo AOV is the texture too.
  const int albedo = [&] {
    for (int c = 0; c < shaded.channels(); ++c) {
      if (shaded.channel_names[size_t(c)] == "albedo.R") return c;
    }
    return -1;
  }();
  ASSERT_GE(albedo, 0);
  EXPECT_NEAR(shaded.at(19, 12, albedo + 1), 1.0f, 1e-6f);
  EXPECT_NEAR(shaded.at(19, 12, albedo), 0.0f, 1e-6f);
}

}  // namespace
}  // namespace prism
