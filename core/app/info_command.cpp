// `prism info`: what a scene holds and what each accelerator makes of it.

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>

#include "accel/accelerator.h"
#include "core/app/commands.h"
#include "core/app/component_params.h"
#include "core/parallel.h"
#include "core/strings.h"
#include "scenes/scene_loader.h"

namespace prism {
namespace {

std::string vec3(const Vec3& v) { return fmt::format("({:.4g}, {:.4g}, {:.4g})", v.x, v.y, v.z); }

/// "3 (diffuse 2, emission 1)": a total and a count per name, names in first-seen order.
template <typename Item, typename NameOf>
std::string count_by_name(const std::vector<Item>& items, NameOf name_of) {
  std::vector<std::pair<std::string, size_t>> counts;
  for (const auto& item : items) {
    const std::string name(name_of(item));
    auto it =
        std::find_if(counts.begin(), counts.end(), [&](const auto& c) { return c.first == name; });
    if (it == counts.end()) {
      counts.emplace_back(name, 1);
    } else {
      ++it->second;
    }
  }
  std::string out = std::to_string(items.size());
  if (counts.empty()) return out;
  out += " (";
  for (size_t i = 0; i < counts.size(); ++i) {
    out += fmt::format("{}{} {}", i ? ", " : "", counts[i].first, counts[i].second);
  }
  return out + ")";
}

template <typename T>
std::string setting(const std::optional<T>& value) {
  return value ? fmt::format("{}", *value) : std::string("-");
}

void print_scene(const Scene& scene) {
  const SceneGeometry& g = scene.geometry;
  size_t emissive_meshes = 0;
  for (const auto& mesh : g.meshes) {
    if (mesh.material_id < scene.materials.size() &&
        scene.materials[mesh.material_id].is_emissive()) {
      ++emissive_meshes;
    }
  }
  fmt::print("scene            {}\n", scene.source);
  fmt::print("triangles        {}\n", g.triangle_count());
  fmt::print("meshes           {}\n", g.meshes.size());
  fmt::print("spheres          {}\n", g.spheres.size());
  fmt::print("emissive meshes  {}\n", emissive_meshes);
  fmt::print("lights           {}\n",
             count_by_name(scene.lights, [](const Light& l) { return to_string(l.type); }));
  fmt::print("materials        {}\n",
             count_by_name(scene.materials, [](const Material& m) { return to_string(m.type); }));
  std::vector<std::string> textures;
  for (const TextureSource& t : scene.textures) textures.push_back(t.name);
  fmt::print("textures         {}{}\n", textures.size(),
             textures.empty() ? "" : " (" + join(textures, ", ") + ")");
  const Bounds3 bounds = g.bounds();
  if (bounds.empty()) {
    fmt::print("bounds           empty\n");
  } else {
    fmt::print("bounds           {} to {}\n", vec3(bounds.lower), vec3(bounds.upper));
  }
  const Camera& c = scene.camera;
  fmt::print("camera           position {}, target {}, up {}\n", vec3(c.position), vec3(c.target),
             vec3(c.up));
  fmt::print(
      "                 hfov {:.4g} deg, vfov {:.4g} deg, lens radius {:.4g}, focal "
      "distance {:.4g}\n",
      c.hfov_deg, c.vfov_deg, c.lens_radius, c.focal_distance);
  const SceneRenderSettings& s = scene.settings;
  fmt::print(
      "settings         resolution {} x {}, spp {}, max depth {}, integrator {}, seed {}"
      "  (-: prism's default)\n",
      setting(s.width), setting(s.height), setting(s.spp), setting(s.max_depth),
      setting(s.integrator), setting(s.seed));
}

void print_accel_stats(const std::string& name, const AccelStats& stats, size_t primitives) {
  const double per_primitive = primitives ? double(stats.bytes) / double(primitives) : 0.0;
  fmt::print("  {:<8} {:>10.2f} {:>10} {:>10} {:>6} {:>12} {:>10.1f} {:>10.2f}\n", name,
             stats.build_ms, stats.nodes, stats.leaves, stats.max_depth, stats.bytes, per_primitive,
             stats.sah_cost);
}

}  // namespace

int run_info_command(const InfoOptions& options) {
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
  for (const std::string& warning : scene.warnings) {
    std::fprintf(stderr, "prism: warning: %s\n", warning.c_str());
  }
  print_scene(scene);

  fmt::print("accelerators     (build on {} threads)\n", thread_limit.threads());
  fmt::print("  {:<8} {:>10} {:>10} {:>10} {:>6} {:>12} {:>10} {:>10}\n", "name", "build ms",
             "nodes", "leaves", "depth", "bytes", "bytes/prim", "SAH cost");
  for (size_t i = 0; i < accels.size(); ++i) {
    accels[i]->build(scene.geometry);
    print_accel_stats(names[i], accels[i]->stats(), scene.geometry.primitive_count());
  }
  return kExitSuccess;
}

}  // namespace prism
