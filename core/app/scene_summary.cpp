#include "core/app/scene_summary.h"

#include <fmt/format.h>

#include <algorithm>

namespace prism {
namespace {

template <typename Item, typename NameOf>
CountByName count_by_name(const std::vector<Item>& items, NameOf name_of) {
  CountByName out;
  out.total = items.size();
  for (const auto& item : items) {
    const std::string name(name_of(item));
    auto it = std::find_if(out.counts.begin(), out.counts.end(),
                           [&](const auto& c) { return c.first == name; });
    if (it == out.counts.end()) {
      out.counts.emplace_back(name, 1);
    } else {
      ++it->second;
    }
  }
  return out;
}

}  // namespace

std::string CountByName::to_string() const {
  std::string out = std::to_string(total);
  if (counts.empty()) return out;
  out += " (";
  for (size_t i = 0; i < counts.size(); ++i) {
    out += fmt::format("{}{} {}", i ? ", " : "", counts[i].first, counts[i].second);
  }
  return out + ")";
}

SceneSummary summarize_scene(const Scene& scene) {
  const SceneGeometry& g = scene.geometry;
  SceneSummary s;
  s.source = scene.source;
  s.triangles = g.triangle_count();
  s.meshes = g.meshes.size();
  s.spheres = g.spheres.size();
  for (const auto& mesh : g.meshes) {
    if (mesh.material_id < scene.materials.size() &&
        scene.materials[mesh.material_id].is_emissive()) {
      ++s.emissive_meshes;
    }
  }
  s.lights = count_by_name(scene.lights, [](const Light& l) { return to_string(l.type); });
  s.materials = count_by_name(scene.materials, [](const Material& m) { return to_string(m.type); });
  for (const TextureSource& t : scene.textures) s.textures.push_back(t.name);
  s.bounds = g.bounds();
  s.camera = scene.camera;
  s.settings = scene.settings;
  return s;
}

}  // namespace prism
