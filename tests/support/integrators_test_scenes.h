#pragma once
// Scenes built in code and a small render harness for the integrator tests.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "accel/accelerator.h"
#include "core/film.h"
#include "core/samplers.h"
#include "core/scene.h"
#include "integrators/integrator.h"
#include "integrators/sampling/warp.h"

namespace prism::test {

inline uint32_t add_material(Scene& scene, MaterialType type, const Rgb& colour,
                             const std::string& name) {
  Material m;
  m.name = name;
  m.type = type;
  m.reflectance = colour;
  m.transmittance = Rgb(1.0f);
  if (type == MaterialType::kEmission) m.radiance = colour;
  scene.materials.push_back(m);
  return uint32_t(scene.materials.size() - 1);
}

/// A quad a, b, c, d (in order) as a two-triangle mesh; the geometric normal is
/// cross(b - a, c - a).
inline TriangleMesh quad(const std::string& name, Vec3 a, Vec3 b, Vec3 c, Vec3 d,
                         uint32_t material) {
  TriangleMesh mesh;
  mesh.name = name;
  mesh.positions = {a, b, c, d};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh.material_id = material;
  return mesh;
}

/// Aims the camera of `scene` from `position` at `target` with `up` and a square field of view
/// of `fov_deg`, then finalizes and validates the scene: the last step of building a test scene.
inline void aim_camera_and_finish(Scene& scene, Vec3 position, Vec3 target, Vec3 up,
                                  float fov_deg) {
  scene.camera.position = position;
  scene.camera.target = target;
  scene.camera.up = up;
  scene.camera.hfov_deg = scene.camera.vfov_deg = fov_deg;
  scene.geometry.finalize();
  scene.validate();
}

/// Options of cornell_box().
struct CornellOptions {
  bool spheres = false;  ///< a diffuse sphere and a second one of `sphere_material`
  MaterialType sphere_material = MaterialType::kMirror;
  bool light_mesh = true;            ///< the emissive quad under the ceiling
  bool area_light = false;           ///< a CGL area light at the same place as the quad
  bool area_duplicates_mesh = true;  ///< flag the area light as the mesh's duplicate
  bool camera_on_floor = false;      ///< look down at the floor only (the light out of view)
  /// Look at the room below the light: the emitter's edges, whose pixels dominate the variance
  /// of an image mean, stay out of view.
  bool camera_below_light = false;
};

/// A Cornell box, Y up: floor y = 0, ceiling y = 2, walls x = +-1 (red left, blue right), back
/// wall z = -1, open at z = +1; a 0.5 x 0.5 light of radiance 10 facing down at y = 1.98.
inline Scene cornell_box(const CornellOptions& o = {}) {
  Scene scene;
  scene.source = "cornell (built in code)";
  const uint32_t white = add_material(scene, MaterialType::kDiffuse, Rgb(0.75f), "white");
  const uint32_t red = add_material(scene, MaterialType::kDiffuse, Rgb(0.75f, 0.2f, 0.2f), "red");
  const uint32_t blue = add_material(scene, MaterialType::kDiffuse, Rgb(0.2f, 0.2f, 0.75f), "blue");
  const uint32_t lamp = add_material(scene, MaterialType::kEmission, Rgb(10.0f), "light");
  auto& meshes = scene.geometry.meshes;
  meshes.push_back(quad("floor", {-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, white));
  meshes.push_back(quad("ceiling", {-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}, white));
  meshes.push_back(quad("back", {-1, 0, -1}, {1, 0, -1}, {1, 2, -1}, {-1, 2, -1}, white));
  meshes.push_back(quad("left", {-1, 0, -1}, {-1, 2, -1}, {-1, 2, 1}, {-1, 0, 1}, red));
  meshes.push_back(quad("right", {1, 0, -1}, {1, 0, 1}, {1, 2, 1}, {1, 2, -1}, blue));
  const float h = 1.98f, s = 0.25f;
  if (o.light_mesh) {
    // Wound so that the normal faces down, into the room.
    meshes.push_back(quad("light", {-s, h, -s}, {s, h, -s}, {s, h, s}, {-s, h, s}, lamp));
  }
  if (o.area_light) {
    Light l;
    l.name = "area";
    l.type = LightType::kArea;
    l.color = Rgb(10.0f);
    l.position = Vec3(0.0f, h, 0.0f);
    l.direction = Vec3(0.0f, -1.0f, 0.0f);
    l.edge_u = Vec3(0.0f, 0.0f, 2 * s);
    l.edge_v = Vec3(2 * s, 0.0f, 0.0f);
    l.duplicates_emissive_mesh = o.area_duplicates_mesh;
    scene.lights.push_back(l);
  }
  if (o.spheres) {
    const uint32_t special = add_material(scene, o.sphere_material, Rgb(0.9f), "special");
    if (o.sphere_material == MaterialType::kMicrofacet) {
      scene.materials[special].alpha = 0.3f;
      scene.materials[special].eta = Rgb(0.2f, 0.9f, 1.1f);
      scene.materials[special].k = Rgb(3.9f, 2.4f, 2.2f);
    }
    scene.geometry.spheres.push_back(Sphere{Vec3(-0.45f, 0.35f, -0.3f), 0.35f, white});
    scene.geometry.spheres.push_back(Sphere{Vec3(0.45f, 0.35f, 0.25f), 0.35f, special});
  }
  scene.camera.position = o.camera_on_floor ? Vec3(0.0f, 1.2f, 0.0f) : Vec3(0.0f, 1.0f, 3.6f);
  scene.camera.target = o.camera_on_floor ? Vec3(0.0f, 0.0f, 0.0f) : Vec3(0.0f, 1.0f, 0.0f);
  scene.camera.up = o.camera_on_floor ? Vec3(0.0f, 0.0f, -1.0f) : Vec3(0.0f, 1.0f, 0.0f);
  scene.camera.hfov_deg = o.camera_on_floor ? 60.0f : 40.0f;
  scene.camera.vfov_deg = scene.camera.hfov_deg;
  if (o.camera_below_light) {
    scene.camera.position = Vec3(0.0f, 0.8f, 3.0f);
    scene.camera.target = Vec3(0.0f, 0.6f, 0.0f);
  }
  scene.geometry.finalize();
  scene.validate();
  return scene;
}

/// Settings of render_scene().
struct TestRender {
  int width = 24, height = 24;
  int spp = 16;
  /// Given to the integrator as the flags -l, -m, -H give them: aliases of `<name>.light_samples`,
  /// `<name>.max_depth` and `<name>.hemisphere`, read by the integrators that have them.
  int light_samples = 1;
  int max_depth = 5;
  bool hemisphere = false;
  int adaptive_batch = 0;
  float adaptive_tolerance = 0.05f;
  uint64_t seed = 1;
  std::string sampler = "independent";
  std::string accelerator = "bvh";
};

/// A width x height RGB image with every channel `value` (an environment map of one radiance).
inline Image uniform_rgb_image(int width, int height, float value) {
  Image image;
  image.width = width;
  image.height = height;
  image.channel_names = {"R", "G", "B"};
  image.pixels.assign(size_t(width) * size_t(height) * 3, value);
  return image;
}

/// Gives `scene` the environment map `image`, its row 0 at the pole along the scene camera's
/// up, as the render driver does for -e.
inline void set_environment(Scene& scene, Image image) {
  SceneEnvironment environment;
  environment.image = std::move(image);
  environment.up = scene.camera.up;
  scene.environment = std::move(environment);
}

/// Renders `scene` with integrator `name`; fails the test if any sample was not finite.
inline Image render_scene(const Scene& scene, const std::string& name, const ParamSet& params,
                          const TestRender& r) {
  const std::unique_ptr<Accelerator> accel = accelerator_registry().create(r.accelerator, params);
  accel->build(scene.geometry);
  ParamSet integrator_params = params;
  integrator_params.set_alias(name + ".light_samples", std::to_string(r.light_samples), "-l");
  integrator_params.set_alias(name + ".max_depth", std::to_string(r.max_depth), "-m");
  if (r.hemisphere) integrator_params.set_alias(name + ".hemisphere", "true", "-H");
  const std::unique_ptr<Integrator> integrator =
      integrator_registry().create(name, integrator_params);
  const std::unique_ptr<Sampler> sampler = create_sampler(r.sampler, r.seed);
  Camera camera = scene.camera;
  camera.fit_to_aspect(float(r.width) / float(r.height));
  Film film(r.width, r.height);
  const RenderContext context{
      .scene = scene,
      .accel = *accel,
      .camera = camera,
      .sampler_prototype = *sampler,
      .spp = r.spp,
      .image_height = r.height,
      .image_width = r.width,
      .adaptive_batch = r.adaptive_batch,
      .adaptive_tolerance = r.adaptive_tolerance,
  };
  integrator->render(context, film);
  EXPECT_EQ(film.non_finite_samples(), 0u) << name << " produced NaN or infinite samples";
  Image image = film.resolve();
  EXPECT_EQ(image.count_non_finite(), 0u);
  return image;
}

inline Image render_scene(const Scene& scene, const std::string& name, const TestRender& r) {
  return render_scene(scene, name, ParamSet{}, r);
}

/// Mean over all pixels of channel c, and the estimated variance of that mean (from the film's
/// per-pixel variance of the mean; pixels are independent).
struct ImageMean {
  double mean = 0.0;
  double variance = 0.0;
};

inline ImageMean image_mean(const Image& image, int c) {
  ImageMean m;
  const double n = double(image.width) * image.height;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      m.mean += image.at(x, y, c);
      m.variance += image.at(x, y, Film::kVarianceChannel + c);
    }
  }
  m.mean /= n;
  m.variance /= n * n;
  return m;
}

/// Expects the means of channels R, G, B of two independent renders to agree: |z| < z_max.
inline void expect_same_mean(const Image& a, const Image& b, double z_max,
                             const std::string& what) {
  for (int c = 0; c < 3; ++c) {
    const ImageMean ma = image_mean(a, c), mb = image_mean(b, c);
    const double sigma = std::sqrt(ma.variance + mb.variance);
    // A comparison is only worth something when the error bars are narrow.
    EXPECT_LT(sigma, 0.02 * std::max(ma.mean, mb.mean)) << what << ": too noisy to compare";
    EXPECT_LT(std::abs(ma.mean - mb.mean), z_max * sigma + 1e-7)
        << what << ", channel " << c << ": " << ma.mean << " vs " << mb.mean << " (sigma " << sigma
        << ")";
  }
}

}  // namespace prism::test
