// What every integrator shares (integrators/integrator, integrator_registry): the registry and
// the parameters it hands over, the AOVs of the first hit, the PixelIntegrator tile loop with
// adaptive sampling, and images independent of the thread count and of concurrent renders.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <memory>
#include <span>
#include <string>
#include <thread>
#include <utility>

#include "core/camera_coverage.h"
#include "core/error.h"
#include "core/parallel.h"
#include "tests/support/integrators_test_scenes.h"

namespace prism {
namespace {

using test::TestRender;

TEST(IntegratorsIntegrator, RegistryListsEveryIntegrator) {
  const auto& registry = integrator_registry();
  for (const char* name : {"path", "direct", "ao", "normals", "depth"}) {
    ASSERT_TRUE(registry.contains(name)) << name;
    const auto integrator = registry.create(name, ParamSet{});
    EXPECT_EQ(integrator->name(), name);
  }
  for (const auto& e : registry.entries()) EXPECT_FALSE(e.description.empty()) << e.name;
  try {
    registry.create("pth", ParamSet{});
    FAIL() << "no error for an unknown integrator";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kUsage);
    EXPECT_NE(std::string(e.what()).find("path"), std::string::npos) << e.what();
  }
  // Each value of `key` makes `integrator` throw (or not, with `accepted`).
  const auto check_values = [&](const char* integrator, const std::string& key,
                                std::initializer_list<const char*> values, bool accepted) {
    for (const char* value : values) {
      ParamSet params;
      params.set(key, value);
      if (accepted) {
        EXPECT_NO_THROW(registry.create(integrator, params)) << key << "=" << value;
      } else {
        EXPECT_THROW(registry.create(integrator, params), Error) << key << "=" << value;
      }
    }
  };
  check_values("path", "path.microfacet", {"phong"}, false);
  check_values("direct", "direct.rectangle_sampling", {"bilinear", "solid_angle", "area"}, true);
  check_values("path", "path.rectangle_sampling", {"spherical"}, false);
  check_values("path", "path.caustic_connections", {"0", "1.5", "nan"}, false);
  check_values("path", "path.rr_probability", {"1.5"}, false);
  check_values("path", "path.rr_threshold", {"0", "-0.5", "1.5", "nan"}, false);
}

TEST(IntegratorsIntegrator, FlagAliasesReachTheIntegratorsThatReadThem) {
  // -m 2 for every integrator, as the driver gives it: only path reads it; nothing is unused.
  for (const char* name : {"path", "direct", "ao", "normals", "depth"}) {
    ParamSet params;
    params.set_alias(std::string(name) + ".max_depth", "2", "-m 2");
    params.set_alias(std::string(name) + ".light_samples", "4", "-l 4");
    integrator_registry().create(name, params);
    EXPECT_TRUE(params.unused_with_prefix(std::string(name) + ".").empty()) << name;
    EXPECT_TRUE(params.keys().empty()) << name;
    EXPECT_EQ(params.to_string(), "") << name;
  }
  // An explicit value agrees with the alias when it parses to the same value.
  ParamSet same;
  same.set_alias("path.max_depth", "3", "-m 3");
  same.set("path.max_depth", "03");
  EXPECT_NO_THROW(integrator_registry().create("path", same));
  EXPECT_EQ(same.to_string(), "path.max_depth=03");
  ParamSet conflict;
  conflict.set_alias("direct.hemisphere", "true", "-H");
  conflict.set("direct.hemisphere", "off");
  try {
    integrator_registry().create("direct", conflict);
    FAIL() << "no error for -H with direct.hemisphere=off";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kUsage);
    EXPECT_NE(std::string(e.what()).find("direct.hemisphere=off"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("-H"), std::string::npos) << e.what();
  }
  // The parameters' ranges are the flags'.
  ParamSet too_deep;
  too_deep.set("path.max_depth", "1025");
  EXPECT_THROW(integrator_registry().create("path", too_deep), Error);
  ParamSet no_samples;
  no_samples.set("direct.light_samples", "0");
  EXPECT_THROW(integrator_registry().create("direct", no_samples), Error);
}

TEST(IntegratorsIntegrator, AovsMatchTheDebugIntegrators) {
  const Scene scene = test::cornell_box({.spheres = true});
  TestRender settings;
  settings.spp = 4;
  const Image path = test::render_scene(scene, "path", settings);
  const Image normals = test::render_scene(scene, "normals", settings);
  const Image depth = test::render_scene(scene, "depth", settings);
  ASSERT_EQ(path.channels(), Film::kChannels);
  const std::vector<std::string> expected = {
      "R",   "G",   "B", "albedo.R",      "albedo.G",   "albedo.B",   "N.X",
      "N.Y", "N.Z", "Z", "sampleCount.Y", "variance.R", "variance.G", "variance.B"};
  EXPECT_EQ(path.channel_names, expected);
  for (int y = 0; y < path.height; ++y) {
    for (int x = 0; x < path.width; ++x) {
      // Same sampler, same camera rays: the AOVs are the debug integrators' values.
      EXPECT_NEAR(path.at(x, y, Film::kDepthChannel), depth.at(x, y, 0), 1e-4f);
      for (int c = 0; c < 3; ++c) {
        const float n = path.at(x, y, Film::kNormalChannel + c);
        const float from_normals = depth.at(x, y, 0) > 0.0f ? 0.5f * n + 0.5f : 0.0f;
        EXPECT_NEAR(from_normals, normals.at(x, y, c), 1e-4f);
      }
      EXPECT_EQ(path.at(x, y, Film::kSampleCountChannel), 4.0f);
      EXPECT_GE(path.at(x, y, Film::kVarianceChannel), 0.0f);
    }
  }
  // The middle of the back wall: white (0.75), facing +z.
  const int cx = path.width / 2, cy = path.height / 3;
  EXPECT_NEAR(path.at(cx, cy, Film::kAlbedoChannel), 0.75f, 1e-5f);
  EXPECT_NEAR(path.at(cx, cy, Film::kNormalChannel + 2), 1.0f, 1e-4f);
}

TEST(IntegratorsIntegrator, AdaptiveSamplingStopsConvergedPixels) {
  Scene scene = test::cornell_box({.spheres = true, .sphere_material = MaterialType::kDiffuse});
  scene.camera.hfov_deg = scene.camera.vfov_deg = 60.0f;  // the black outside in view too
  TestRender settings;
  settings.width = settings.height = 16;
  settings.spp = 256;
  settings.adaptive_batch = 16;
  settings.adaptive_tolerance = 0.05f;
  settings.max_depth = 3;
  const Image image = test::render_scene(scene, "path", settings);
  int stopped_early = 0, black = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const float n = image.at(x, y, Film::kSampleCountChannel);
      ASSERT_GE(n, 16.0f);
      ASSERT_LE(n, 256.0f);
      ASSERT_EQ(std::fmod(n, 16.0f), 0.0f);  // whole batches
      stopped_early += n < 256.0f ? 1 : 0;
      if (image.at(x, y, 0) == 0.0f && image.at(x, y, Film::kDepthChannel) == 0.0f) {
        // Outside the box: the first batch is black and noiseless, so it stops at once.
        ++black;
        EXPECT_EQ(n, 16.0f);
      }
    }
  }
  EXPECT_GT(stopped_early, 0);
  EXPECT_GT(black, 0);
  // Without -a every pixel takes every sample.
  settings.adaptive_batch = 0;
  settings.spp = 8;
  const Image fixed = test::render_scene(scene, "path", settings);
  for (int y = 0; y < fixed.height; ++y) {
    for (int x = 0; x < fixed.width; ++x) {
      ASSERT_EQ(fixed.at(x, y, Film::kSampleCountChannel), 8.0f);
    }
  }
}

TEST(IntegratorsIntegrator, ImagesDoNotDependOnTheThreadCount) {
  const Scene scene = test::cornell_box({.spheres = true, .sphere_material = MaterialType::kGlass});
  TestRender settings;
  settings.spp = 4;
  settings.sampler = "sobol";
  Image one, two;
  {
    const ThreadLimit limit(1);
    one = test::render_scene(scene, "path", settings);
  }
  {
    const ThreadLimit limit(2);
    two = test::render_scene(scene, "path", settings);
  }
  ASSERT_EQ(one.pixels.size(), two.pixels.size());
  for (size_t i = 0; i < one.pixels.size(); ++i) ASSERT_EQ(one.pixels[i], two.pixels[i]) << i;
}

/// What one render reads besides the integrator: a scene and its accelerator, camera, sampler.
struct RenderInputs {
  /// For a square film of size x size pixels.
  RenderInputs(Scene scene_in, int size_in)
      : scene(std::move(scene_in)),
        accel(accelerator_registry().create("bvh", ParamSet{})),
        camera(scene.camera),
        sampler(create_sampler("sobol", 3)),
        size(size_in) {
    accel->build(scene.geometry);
    camera.fit_to_aspect(1.0f);
  }
  RenderContext context() const {
    return RenderContext{
        .scene = scene, .accel = *accel, .camera = camera, .sampler_prototype = *sampler, .spp = 4};
  }
  Scene scene;
  std::unique_ptr<Accelerator> accel;
  Camera camera;
  std::unique_ptr<Sampler> sampler;
  int size;
};

TEST(IntegratorsIntegrator, ConcurrentRendersOfOneInstanceMatchSequentialOnes) {
  // Two different scenes (other materials, lights, size and film), so that state of one render
  // leaking into the other would show.
  Scene with_environment = test::cornell_box({.camera_on_floor = true});
  test::set_environment(with_environment, test::uniform_rgb_image(8, 4, 0.5f));
  const RenderInputs a(
      test::cornell_box({.spheres = true, .sphere_material = MaterialType::kGlass}), 24);
  const RenderInputs b(std::move(with_environment), 20);
  for (const char* name : {"path", "direct", "ao", "normals", "depth"}) {
    SCOPED_TRACE(name);
    const std::unique_ptr<Integrator> integrator = integrator_registry().create(name, ParamSet{});
    const auto render = [&](const RenderInputs& inputs, Film& film) {
      integrator->render(inputs.context(), film);
    };
    Film sequential_a(a.size, a.size), sequential_b(b.size, b.size);
    render(a, sequential_a);
    render(b, sequential_b);
    Film concurrent_a(a.size, a.size), concurrent_b(b.size, b.size);
    {
      std::thread first([&] { render(a, concurrent_a); });
      std::thread second([&] { render(b, concurrent_b); });
      first.join();
      second.join();
    }
    EXPECT_TRUE(concurrent_a.resolve().pixels == sequential_a.resolve().pixels);
    EXPECT_TRUE(concurrent_b.resolve().pixels == sequential_b.resolve().pixels);
  }
}

/// Renders `film` as the progressive loop does: in passes, the samples [0, 3) of every pixel
/// first and then the rest, tile by tile.
void render_in_two_passes(const Integrator& integrator, const RenderContext& context, Film& film) {
  const std::unique_ptr<TileRenderer> renderer = integrator.start(context);
  const uint32_t spp = uint32_t(std::max(1, context.spp));
  const uint32_t split = std::min(3u, spp);
  const PixelRect& w = film.window();
  for (const SampleRange range : {SampleRange{0, split}, SampleRange{split, spp}}) {
    for (int y = w.begin.y; y < w.end.y; y += 8) {
      for (int x = w.begin.x; x < w.end.x; x += 8) {
        const Tile tile{{x, y}, {std::min(x + 8, w.end.x), std::min(y + 8, w.end.y)}};
        renderer->render_tile(tile, range, film);
      }
    }
  }
}

TEST(IntegratorsIntegrator, UnseenPixelsTakeTheSamplesTracingWouldGive) {
  // The box seen from farther back, so that a border of the frame sees nothing: the tile loop
  // fills those pixels without tracing them (only counting their samples, when nothing can land
  // on them), and the film must be the one tracing gives, bit for bit, state and image, for
  // every integrator, with the light tracer's caustics (glass sphere), adaptive sampling, a crop
  // window, and in one range of samples or in two passes; with an environment map nothing may
  // be skipped.
  Scene box = test::cornell_box({.spheres = true, .sphere_material = MaterialType::kGlass});
  box.camera.position = Vec3(0.0f, 1.0f, 5.5f);
  Scene with_environment = test::cornell_box({.spheres = true});
  with_environment.camera.position = box.camera.position;
  test::set_environment(with_environment, test::uniform_rgb_image(8, 4, 0.5f));
  const RenderInputs inputs[] = {RenderInputs(std::move(box), 32),
                                 RenderInputs(std::move(with_environment), 32)};
  // The test is only worth something if a good part of the frame is skippable.
  const PixelRect seeing =
      pixels_seeing_bounds(inputs[0].camera, inputs[0].scene.geometry.bounds(), 32, 32);
  ASSERT_LT(seeing.pixel_count(), size_t(32 * 32 * 3 / 4));
  ASSERT_GT(seeing.pixel_count(), 0u);
  const PixelRect crop{{2, 5}, {29, 30}};
  for (const RenderInputs& in : inputs) {
    for (const char* name : {"path", "direct", "ao", "normals", "depth"}) {
      for (const int batch : {0, 2}) {
        SCOPED_TRACE(std::string(name) + (batch ? " adaptive" : "") +
                     (&in == &inputs[0] ? "" : " environment"));
        const std::unique_ptr<Integrator> integrator =
            integrator_registry().create(name, ParamSet{});
        RenderContext context = in.context();
        context.image_width = context.image_height = in.size;
        context.adaptive_batch = batch;
        context.adaptive_tolerance = 0.2f;
        Film skipped(in.size, in.size, crop), traced(in.size, in.size, crop);
        Film skipped_in_passes(in.size, in.size, crop), traced_in_passes(in.size, in.size, crop);
        context.skip_unseen_pixels = true;
        integrator->render(context, skipped);
        render_in_two_passes(*integrator, context, skipped_in_passes);
        context.skip_unseen_pixels = false;
        integrator->render(context, traced);
        render_in_two_passes(*integrator, context, traced_in_passes);
        for (const auto& [a_film, b_film] :
             {std::pair{&skipped, &traced}, std::pair{&skipped_in_passes, &traced_in_passes}}) {
          SCOPED_TRACE(a_film == &skipped ? "one range" : "two passes");
          const std::span<const FilmPixel> a_state = std::as_const(*a_film).pixels();
          const std::span<const FilmPixel> b_state = std::as_const(*b_film).pixels();
          ASSERT_EQ(a_state.size(), b_state.size());
          for (size_t i = 0; i < a_state.size(); ++i) {
            ASSERT_EQ(std::memcmp(&a_state[i], &b_state[i], sizeof(FilmPixel)), 0)
                << "film state of pixel " << i;
          }
          const Image a = a_film->resolve(), b = b_film->resolve();
          ASSERT_EQ(a.pixels.size(), b.pixels.size());
          for (size_t i = 0; i < a.pixels.size(); ++i) {
            ASSERT_EQ(std::bit_cast<uint32_t>(a.pixels[i]), std::bit_cast<uint32_t>(b.pixels[i]))
                << "channel value " << i;
          }
        }
        const Image a = skipped.resolve();
        const std::string integrator_name(name);
        const bool sky_seen =
            &in != &inputs[0] && (integrator_name == "path" || integrator_name == "direct");
        if (sky_seen) {
          // The crop's corner sees the sky past the box: not left black.
          ASSERT_FALSE(seeing.contains(crop.begin));
          EXPECT_GT(a.at(0, 0, 0), 0.0f);
        }
      }
    }
  }
}

}  // namespace
}  // namespace prism
