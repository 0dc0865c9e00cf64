#include "scenes/generated_scene.h"

#include <filesystem>

#include "core/error.h"
#include "scenes/scene_loader.h"

namespace prism {
namespace {

/// "10k" -> 10000, "1M" -> 1000000, "2500" -> 2500; throws Error(kUsage).
size_t parse_count(const std::string& text, const std::string& spec) {
  size_t scale = 1;
  std::string digits = text;
  if (!digits.empty() && (digits.back() == 'k' || digits.back() == 'K')) {
    scale = 1000;
    digits.pop_back();
  } else if (!digits.empty() && digits.back() == 'M') {
    scale = 1000000;
    digits.pop_back();
  }
  if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos ||
      digits.size() > 9) {
    throw Error(ErrorKind::kUsage, "'" + spec + "': triangle count must be like 5000, 10k or 1M");
  }
  return std::stoul(digits) * scale;
}

std::string count_label(size_t n) {
  if (n % 1000000 == 0) return std::to_string(n / 1000000) + "M";
  if (n % 1000 == 0) return std::to_string(n / 1000) + "k";
  return std::to_string(n);
}

/// Twelve triangles of an axis-aligned box: the room around a generated mesh.
TriangleMesh room(const Bounds3& b) {
  TriangleMesh m;
  m.name = "room";
  for (int i = 0; i < 8; ++i) {
    m.positions.emplace_back(i & 1 ? b.upper.x : b.lower.x, i & 2 ? b.upper.y : b.lower.y,
                             i & 4 ? b.upper.z : b.lower.z);
  }
  const uint32_t quads[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                                {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  m.material_id = 0;
  return m;
}

}  // namespace

Scene make_generated_scene(GeneratedMeshKind kind, size_t count) {
  Scene scene;
  scene.source = "generated " + to_string(kind) + " " + std::to_string(count);
  TriangleMesh mesh = generate_mesh(kind, count, /*seed=*/1, /*material_id=*/0);
  const Bounds3 b = mesh.bounds();
  const Vec3 c = b.center();
  const float r = 0.5f * glm::length(b.diagonal());
  scene.geometry.meshes.push_back(std::move(mesh));
  scene.geometry.meshes.push_back(room({c - Vec3(3.0f * r), c + Vec3(3.0f * r)}));
  scene.geometry.finalize();
  scene.materials.push_back(Material{});
  scene.camera.position = c + r * Vec3(0.45f, 0.6f, 1.9f);
  scene.camera.target = c;
  scene.camera.hfov_deg = 55.0f;
  scene.camera.fit_to_aspect(1.0f);
  Light light;
  light.name = "key";
  light.position = c + r * Vec3(1.6f, 2.4f, 1.2f);
  scene.lights.push_back(light);
  scene.validate();
  return scene;
}

Scene load_scene_or_generated(const std::string& spec, std::string& name) {
  if (spec.rfind("gen:", 0) == 0) {
    const size_t colon = spec.find(':', 4);
    if (colon == std::string::npos) {
      throw Error(ErrorKind::kUsage, "'" + spec + "': generated scenes are gen:KIND:COUNT");
    }
    const GeneratedMeshKind kind = parse_generated_mesh_kind(spec.substr(4, colon - 4));
    const size_t count = parse_count(spec.substr(colon + 1), spec);
    name = to_string(kind) + "_" + count_label(count);
    return make_generated_scene(kind, count);
  }
  name = std::filesystem::path(spec).stem().string();
  return load_scene(spec);
}

}  // namespace prism
