#include "scenes/json_scene_loader.h"

#include <cmath>
#include <new>
#include <string>

#include "core/error.h"
#include "scenes/json/json_document.h"
#include "scenes/json/json_meshes.h"
#include "scenes/json/json_textures.h"

namespace prism {
namespace {

using json::JsonNode;
using json::Range;

/// Image aspect assumed for the camera when the file's `render` block gives no resolution: the
/// 480 x 360 default of the CS184 homework.
constexpr float kDefaultAspect = 480.0f / 360.0f;
// The same limits as the command line's (core/app/render_options.h), which scenes cannot see.
constexpr int64_t kMaxImageSide = 16384;
constexpr int64_t kMaxSpp = int64_t(1) << 20;
constexpr int64_t kMaxRayDepth = 1024;

SceneRenderSettings read_render(const JsonNode& node) {
  node.check_keys({"width", "height", "spp", "max_depth", "integrator", "seed"});
  SceneRenderSettings s;
  if (const auto v = node.find("width")) s.width = static_cast<int>(v->integer(1, kMaxImageSide));
  if (const auto v = node.find("height")) s.height = static_cast<int>(v->integer(1, kMaxImageSide));
  if (const auto v = node.find("spp")) s.spp = static_cast<int>(v->integer(1, kMaxSpp));
  if (const auto v = node.find("max_depth")) {
    s.max_depth = static_cast<int>(v->integer(0, kMaxRayDepth));
  }
  if (const auto v = node.find("integrator")) {
    s.integrator = v->string();
    if (s.integrator->empty()) v->fail("integrator name is empty");
  }
  if (const auto v = node.find("seed")) s.seed = v->unsigned_integer();
  return s;
}

Camera read_camera(const JsonNode& node, const SceneRenderSettings& settings) {
  node.check_keys(
      {"position", "target", "look_at", "up", "fov", "fov_axis", "lens_radius", "focal_distance"});
  Camera camera;
  camera.position = node.child("position").vec3();
  if (node.has("target") && node.has("look_at")) {
    node.fail("give either 'target' or 'look_at', not both");
  }
  if (!node.has("target") && !node.has("look_at")) {
    node.fail("missing required field 'target' (or 'look_at')");
  }
  camera.target = node.child(node.has("target") ? "target" : "look_at").vec3();
  camera.up = json::vec3_or(node, "up", Vec3(0.0f, 1.0f, 0.0f));
  const float fov = node.child("fov").number(Range::open(0.0, 180.0));
  bool vertical = true;
  if (const auto axis = node.find("fov_axis")) {
    const std::string name = axis->string();
    if (name != "vertical" && name != "horizontal") {
      axis->fail("fov_axis must be 'vertical' or 'horizontal', not '" + name + "'");
    }
    vertical = name == "vertical";
  }
  // The other axis follows from the file's own resolution; a different output resolution
  // later widens one axis (Camera::fit_to_aspect) and never narrows the authored one.
  const float aspect = settings.width && settings.height ? static_cast<float>(*settings.width) /
                                                               static_cast<float>(*settings.height)
                                                         : kDefaultAspect;
  const float half_tan = std::tan(radians(fov) * 0.5f);
  if (vertical) {
    camera.vfov_deg = fov;
    camera.hfov_deg = degrees(2.0f * std::atan(half_tan * aspect));
  } else {
    camera.hfov_deg = fov;
    camera.vfov_deg = degrees(2.0f * std::atan(half_tan / aspect));
  }
  camera.lens_radius = json::number_or(node, "lens_radius", 0.0f, Range::at_least(0.0));
  camera.focal_distance = json::number_or(
      node, "focal_distance", glm::length(camera.target - camera.position), Range::above(0.0));
  try {
    camera.validate();
  } catch (const Error& e) {
    node.fail(e.message());
  }
  return camera;
}

/// A material's optional colour `key` that may name a texture (json_textures.h).
Rgb textured_color_or(const JsonNode& node, std::string_view key, Rgb fallback, Range range,
                      json::TextureContext& textures, uint32_t& texture) {
  texture = kNoTexture;
  const auto value = node.find(key);
  return value ? json::read_textured_color(*value, range, textures, texture) : fallback;
}

Material read_material(const JsonNode& node, json::TextureContext& textures) {
  node.expect_object();
  if (!node.has("type")) {
    // A misspelt "type" reads better as an unknown key than as a missing one.
    node.check_keys({"name", "type", "reflectance", "transmittance", "roughness", "ior", "alpha",
                     "eta", "k", "radiance"});
  }
  Material m;
  const JsonNode type = node.child("type");
  const std::string kind = type.string();
  const Range unit = Range::closed(0.0, 1.0);
  const Range non_negative = Range::at_least(0.0);
  if (kind == "diffuse") {
    node.check_keys({"name", "type", "reflectance"});
    m.type = MaterialType::kDiffuse;
    m.reflectance =
        textured_color_or(node, "reflectance", Rgb(0.5f), unit, textures, m.reflectance_texture);
  } else if (kind == "mirror") {
    node.check_keys({"name", "type", "reflectance"});
    m.type = MaterialType::kMirror;
    m.reflectance =
        textured_color_or(node, "reflectance", Rgb(1.0f), unit, textures, m.reflectance_texture);
  } else if (kind == "glass") {
    node.check_keys({"name", "type", "reflectance", "transmittance", "roughness", "ior"});
    m.type = MaterialType::kGlass;
    m.reflectance = json::color_or(node, "reflectance", Rgb(1.0f), unit);
    m.transmittance = json::color_or(node, "transmittance", Rgb(1.0f), unit);
    m.roughness = json::number_or(node, "roughness", 0.0f, non_negative);
    m.ior = json::number_or(node, "ior", 1.5f, Range::above(0.0));
  } else if (kind == "refraction") {
    node.check_keys({"name", "type", "transmittance", "roughness", "ior"});
    m.type = MaterialType::kRefraction;
    m.transmittance = json::color_or(node, "transmittance", Rgb(1.0f), unit);
    m.roughness = json::number_or(node, "roughness", 0.0f, non_negative);
    m.ior = json::number_or(node, "ior", 1.5f, Range::above(0.0));
  } else if (kind == "microfacet") {
    node.check_keys({"name", "type", "alpha", "eta", "k", "reflectance"});
    m.type = MaterialType::kMicrofacet;
    m.alpha = json::number_or(node, "alpha", 0.5f, Range::above(0.0));
    if (const auto reflectance = node.find("reflectance")) {
      // The metal by its colour: eta and k follow (conductor_from_reflectance()).
      if (node.has("eta") || node.has("k")) {
        reflectance->fail("give either 'reflectance' or 'eta' and 'k', not both");
      }
      m.reflectance =
          json::read_textured_color(*reflectance, unit, textures, m.reflectance_texture);
      conductor_from_reflectance(m.reflectance, m.eta, m.k);
    } else {
      m.eta = node.child("eta").color(Range::above(0.0));
      m.k = node.child("k").color(non_negative);
    }
  } else if (kind == "emission") {
    node.check_keys({"name", "type", "radiance"});
    m.type = MaterialType::kEmission;
    m.radiance = json::read_textured_color(node.child("radiance"), non_negative, textures,
                                           m.radiance_texture);
  } else {
    type.fail("unknown material type '" + kind +
              "'; available: diffuse, mirror, glass, refraction, microfacet, emission");
  }
  m.name = node.child("name").string();
  return m;
}

/// Point and spot lights: position, intensity and COLLADA's attenuation 1 / (c + l d + q d^2).
void read_point_fields(const JsonNode& node, Light& light) {
  light.position = node.child("position").vec3();
  light.color = node.child("color").color(Range::at_least(0.0));
  if (const auto att = node.find("attenuation")) {
    const Vec3 a = att->vec3();
    if (a.x < 0.0f || a.y < 0.0f || a.z < 0.0f || a.x + a.y + a.z <= 0.0f) {
      att->fail("attenuation [constant, linear, quadratic] must be >= 0 and not all 0");
    }
    light.constant_attenuation = a.x;
    light.linear_attenuation = a.y;
    light.quadratic_attenuation = a.z;
  }
}

Light read_light(const JsonNode& node) {
  node.expect_object();
  if (!node.has("type")) {
    node.check_keys({"name", "type", "position", "direction", "color", "attenuation",
                     "falloff_angle", "falloff_exponent", "up", "center", "edge_u", "edge_v"});
  }
  Light light;
  const JsonNode type = node.child("type");
  const std::string kind = type.string();
  const Range non_negative = Range::at_least(0.0);
  if (kind == "point") {
    node.check_keys({"name", "type", "position", "color", "attenuation"});
    light.type = LightType::kPoint;
    read_point_fields(node, light);
  } else if (kind == "spot") {
    node.check_keys({"name", "type", "position", "direction", "color", "attenuation",
                     "falloff_angle", "falloff_exponent"});
    light.type = LightType::kSpot;
    read_point_fields(node, light);
    light.direction = node.child("direction").direction();
    light.falloff_angle_deg = node.child("falloff_angle").number({0.0, 180.0, true, false});
    light.falloff_exponent = json::number_or(node, "falloff_exponent", 0.0f, non_negative);
  } else if (kind == "directional") {
    node.check_keys({"name", "type", "direction", "color"});
    light.type = LightType::kDirectional;
    light.direction = node.child("direction").direction();
    light.color = node.child("color").color(non_negative);
  } else if (kind == "ambient") {
    node.check_keys({"name", "type", "color", "up"});
    light.type = LightType::kAmbient;
    light.color = node.child("color").color(non_negative);
    if (const auto up = node.find("up"))
      light.up = up->direction();
    else
      light.up = Vec3(0.0f, 1.0f, 0.0f);
  } else if (kind == "area") {
    node.check_keys({"name", "type", "center", "edge_u", "edge_v", "color"});
    light.type = LightType::kArea;
    light.position = node.child("center").vec3();
    light.edge_u = node.child("edge_u").vec3();
    light.edge_v = node.child("edge_v").vec3();
    light.color = node.child("color").color(non_negative);
    const Vec3 normal = glm::cross(light.edge_u, light.edge_v);
    const float area = glm::length(normal);
    if (!(area > 0.0f) || !std::isfinite(area)) {
      node.fail("area light edges 'edge_u' and 'edge_v' span no area");
    }
    light.direction = normal / area;
  } else {
    type.fail("unknown light type '" + kind +
              "'; available: point, spot, directional, ambient, area");
  }
  const auto name = node.find("name");
  light.name = name ? name->string() : json::to_string(node.path());
  return light;
}

Sphere read_sphere(const JsonNode& node, const json::MaterialNames& materials) {
  node.check_keys({"center", "radius", "material"});
  Sphere s;
  s.center = node.child("center").vec3();
  s.radius = node.child("radius").number(Range::above(0.0));
  s.material_id = materials.resolve(node.child("material"));
  return s;
}

Scene read_scene(const json::JsonDocument& doc) {
  const JsonNode root(doc, doc.root(), {});
  root.check_keys({"camera", "render", "materials", "lights", "meshes", "spheres"});
  Scene scene;
  if (const auto render = root.find("render")) scene.settings = read_render(*render);
  scene.camera = read_camera(root.child("camera"), scene.settings);

  json::MaterialNames names;
  json::TextureContext textures{doc.file().parent_path(), &scene.textures};
  if (const auto materials = root.find("materials")) {
    for (size_t i = 0; i < materials->size(); ++i) {
      const JsonNode node = materials->at(i);
      scene.materials.push_back(read_material(node, textures));
      names.add(scene.materials.back().name, static_cast<uint32_t>(i), node.child("name"));
    }
  }
  if (const auto lights = root.find("lights")) {
    for (size_t i = 0; i < lights->size(); ++i) scene.lights.push_back(read_light(lights->at(i)));
  }
  const std::filesystem::path base_dir = doc.file().parent_path();
  if (const auto meshes = root.find("meshes")) {
    scene.geometry.meshes.reserve(meshes->size());
    for (size_t i = 0; i < meshes->size(); ++i) {
      const JsonNode node = meshes->at(i);
      scene.geometry.meshes.push_back(
          json::read_mesh(node, names, base_dir, json::to_string(node.path())));
    }
  }
  if (const auto spheres = root.find("spheres")) {
    for (size_t i = 0; i < spheres->size(); ++i) {
      scene.geometry.spheres.push_back(read_sphere(spheres->at(i), names));
    }
  }
  return scene;
}

}  // namespace

Scene load_json_scene(const std::filesystem::path& path) {
  try {
    const json::JsonDocument doc(path);
    return read_scene(doc);
  } catch (const std::bad_alloc&) {
    throw Error(ErrorKind::kResource, "out of memory while loading the scene",
                {path.string(), 0, {}});
  }
}

}  // namespace prism
