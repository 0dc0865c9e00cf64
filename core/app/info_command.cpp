// `prism info`: what a scene holds and what each accelerator makes of it.

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>

#include "accel/accelerator.h"
#include "core/app/commands.h"
#include "core/app/component_params.h"
#include "core/app/scene_summary.h"
#include "core/parallel.h"
#include "core/strings.h"
#include "scenes/scene_loader.h"

namespace prism {
namespace {

std::string vec3(const Vec3& v) { return fmt::format("({:.4g}, {:.4g}, {:.4g})", v.x, v.y, v.z); }

template <typename T>
std::string setting(const std::optional<T>& value) {
  return value ? fmt::format("{}", *value) : std::string("-");
}

void print_scene(const SceneSummary& s) {
  fmt::print("scene            {}\n", s.source);
  fmt::print("triangles        {}\n", s.triangles);
  fmt::print("meshes           {}\n", s.meshes);
  fmt::print("spheres          {}\n", s.spheres);
  fmt::print("emissive meshes  {}\n", s.emissive_meshes);
  fmt::print("lights           {}\n", s.lights.to_string());
  fmt::print("materials        {}\n", s.materials.to_string());
  fmt::print("textures         {}{}\n", s.textures.size(),
             s.textures.empty() ? "" : " (" + join(s.textures, ", ") + ")");
  if (s.bounds.empty()) {
    fmt::print("bounds           empty\n");
  } else {
    fmt::print("bounds           {} to {}\n", vec3(s.bounds.lower), vec3(s.bounds.upper));
  }
  const Camera& c = s.camera;
  fmt::print("camera           position {}, target {}, up {}\n", vec3(c.position), vec3(c.target),
             vec3(c.up));
  fmt::print(
      "                 hfov {:.4g} deg, vfov {:.4g} deg, lens radius {:.4g}, focal "
      "distance {:.4g}\n",
      c.hfov_deg, c.vfov_deg, c.lens_radius, c.focal_distance);
  const SceneRenderSettings& settings = s.settings;
  fmt::print(
      "settings         resolution {} x {}, spp {}, max depth {}, integrator {}, seed {}"
      "  (-: prism's default)\n",
      setting(settings.width), setting(settings.height), setting(settings.spp),
      setting(settings.max_depth), setting(settings.integrator), setting(settings.seed));
}

void print_accel_stats(const std::string& name, const AccelStats& stats, size_t primitives) {
  const double per_primitive = primitives ? double(stats.bytes) / double(primitives) : 0.0;
  fmt::print("  {:<8} {:>10.2f} {:>10} {:>10} {:>6} {:>12} {:>10.1f} {:>10.2f}\n", name,
             stats.build_ms, stats.nodes, stats.leaves, stats.max_depth, stats.bytes, per_primitive,
             stats.sah_cost);
}

}  // namespace

InfoReport collect_info(const InfoOptions& options) {
  const ParamSet params = parse_param_assignments(options.set);
  validate_thread_count(options.threads);
  ThreadLimit thread_limit(options.threads);
  std::vector<std::string> names = options.accelerators;
  if (names.empty()) {
    names = accelerator_registry().names();
  }
  // Creating them all first rejects an unknown name or --set key before the scene loads.
  std::vector<std::unique_ptr<Accelerator>> accels;
  std::vector<ComponentInUse> in_use;
  for (const auto& name : names) {
    accels.push_back(accelerator_registry().create(name, params));
    in_use.push_back({"accelerator", name});
  }
  check_component_params(params, in_use);

  const Scene scene =
      load_scene(options.scene, SceneLoadOptions{.literal_camera = options.literal_camera});
  InfoReport report;
  report.scene = summarize_scene(scene);
  report.primitives = scene.geometry.primitive_count();
  report.threads = thread_limit.threads();
  report.warnings = scene.warnings;
  for (size_t i = 0; i < accels.size(); ++i) {
    accels[i]->build(scene.geometry);
    report.accelerators.emplace_back(names[i], accels[i]->stats());
  }
  return report;
}

int run_info_command(const InfoOptions& options) {
  const InfoReport report = collect_info(options);
  for (const std::string& warning : report.warnings) {
    std::fprintf(stderr, "prism: warning: %s\n", warning.c_str());
  }
  print_scene(report.scene);
  fmt::print("accelerators     (build on {} threads)\n", report.threads);
  fmt::print("  {:<8} {:>10} {:>10} {:>10} {:>6} {:>12} {:>10} {:>10}\n", "name", "build ms",
             "nodes", "leaves", "depth", "bytes", "bytes/prim", "SAH cost");
  for (const auto& [name, stats] : report.accelerators) {
    print_accel_stats(name, stats, report.primitives);
  }
  return kExitSuccess;
}

}  // namespace prism
