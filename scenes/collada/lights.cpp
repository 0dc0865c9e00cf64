#include "scenes/collada/lights.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>

#include "scenes/collada/transforms.h"

namespace prism::collada {
namespace {

float read_non_negative(const Document& doc, pugi::xml_node parent, const char* name,
                        float fallback) {
  const pugi::xml_node e = parent.child(name);
  if (!e) return fallback;
  const double v = doc.scalar(e);
  if (v < 0.0) doc.fail(e, std::string(name) + " must be >= 0");
  return static_cast<float>(v);
}

void read_attenuation(const Document& doc, pugi::xml_node params, Light& light) {
  light.constant_attenuation = read_non_negative(doc, params, "constant_attenuation", 1.0f);
  light.linear_attenuation = read_non_negative(doc, params, "linear_attenuation", 0.0f);
  light.quadratic_attenuation = read_non_negative(doc, params, "quadratic_attenuation", 0.0f);
  if (light.constant_attenuation == 0.0f && light.linear_attenuation == 0.0f &&
      light.quadratic_attenuation == 0.0f) {
    doc.fail(params, "constant, linear and quadratic attenuation are all zero");
  }
}

struct Emitter {
  double area = 0.0;
  DVec3 centre{0.0};
  DVec3 normal{0.0};
};

Emitter summarize(const TriangleMesh& mesh) {
  Emitter e;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3 tri = mesh.triangles[t];
    const DVec3 p0(mesh.positions[tri.x]), p1(mesh.positions[tri.y]), p2(mesh.positions[tri.z]);
    const DVec3 cross = glm::cross(p1 - p0, p2 - p0);
    const double twice_area = glm::length(cross);
    if (!(twice_area > 0.0)) continue;
    DVec3 n = cross / twice_area;
    // The side that emits is the side of the authored normals (see Scene::surface_at).
    if (!mesh.normals.empty()) {
      const DVec3 ns(mesh.normals[3 * t] + mesh.normals[3 * t + 1] + mesh.normals[3 * t + 2]);
      if (glm::dot(ns, n) < 0.0) n = -n;
    }
    const double a = 0.5 * twice_area;
    e.area += a;
    e.centre += a * (p0 + p1 + p2) / 3.0;
    e.normal += a * n;
  }
  if (e.area > 0.0) {
    e.centre /= e.area;
    const double length = glm::length(e.normal);
    if (length > 0.0) e.normal /= length;
  }
  return e;
}

}  // namespace

Light parse_light(const Document& doc, pugi::xml_node instance, const DMat4& world) {
  const pugi::xml_node element = doc.resolve(instance, "url", "light");
  Light light;
  light.name = element.attribute("name") ? element.attribute("name").value()
                                         : element.attribute("id").value();
  light.up = kWorldUp;
  const pugi::xml_node cgl = first_element(find_extra_technique(element, "CGL"));
  const pugi::xml_node common = first_element(element.child("technique_common"));
  const pugi::xml_node params = cgl ? cgl : common;
  if (!params) {
    doc.fail(element, "light has neither a technique_common type nor a CGL <area>");
  }
  const std::string_view type = params.name();
  if (cgl && type != "area") {
    doc.fail(cgl, "unknown CGL light type <" + quote(type) + "> (expected area)");
  }
  if (type == "area") {
    light.type = LightType::kArea;
  } else if (type == "point") {
    light.type = LightType::kPoint;
    read_attenuation(doc, params, light);
  } else if (type == "spot") {
    light.type = LightType::kSpot;
    read_attenuation(doc, params, light);
    if (const pugi::xml_node angle = params.child("falloff_angle")) {
      const double degrees = doc.scalar(angle);
      if (!(degrees > 0.0 && degrees <= 360.0)) {
        doc.fail(angle, "falloff_angle must be in (0, 360] degrees");
      }
      light.falloff_angle_deg = static_cast<float>(degrees);
    }
    light.falloff_exponent = read_non_negative(doc, params, "falloff_exponent", 0.0f);
  } else if (type == "directional") {
    light.type = LightType::kDirectional;
  } else if (type == "ambient") {
    light.type = LightType::kAmbient;
  } else {
    doc.fail(params, "unknown light type <" + quote(type) +
                         "> (expected point, spot, directional or ambient)");
  }
  if (const pugi::xml_node color = params.child("color")) light.color = doc.color(color);

  const DVec3 position = transform_point(world, DVec3(0.0));
  const DVec3 direction = transform_vector(world, DVec3(0, 0, -1));
  const double length = glm::length(direction);
  if (!(length > 0.0) || !std::isfinite(length) || !is_finite(Vec3(position))) {
    doc.fail(instance, "the node's transform collapses or overflows the light's frame");
  }
  light.position = Vec3(position);
  light.direction = Vec3(direction / length);
  if (light.type == LightType::kArea) {
    light.edge_u = Vec3(transform_vector(world, DVec3(1, 0, 0)));
    light.edge_v = Vec3(transform_vector(world, DVec3(0, 1, 0)));
    const float area = glm::length(glm::cross(light.edge_u, light.edge_v));
    if (!(area > 0.0f) || !std::isfinite(area)) {
      doc.fail(instance, "the area light's node scales it to zero (or infinite) area");
    }
  }
  return light;
}

void mark_duplicate_area_lights(std::vector<Light>& lights, const SceneGeometry& geometry,
                                const std::vector<Material>& materials) {
  std::vector<Emitter> emitters;
  for (const TriangleMesh& mesh : geometry.meshes) {
    if (mesh.material_id < materials.size() && materials[mesh.material_id].is_emissive()) {
      const Emitter e = summarize(mesh);
      if (e.area > 0.0) emitters.push_back(e);
    }
  }
  if (emitters.empty()) return;
  const Bounds3 bounds = geometry.bounds();
  const double scene_size = bounds.empty() ? 0.0 : glm::length(DVec3(bounds.diagonal()));
  for (Light& light : lights) {
    if (light.type != LightType::kArea) continue;
    const double area = glm::length(glm::cross(DVec3(light.edge_u), DVec3(light.edge_v)));
    const double tolerance = std::max(1e-3 * scene_size, 1e-2 * std::sqrt(area));
    for (const Emitter& e : emitters) {
      const bool same_area = std::abs(e.area - area) <= 0.01 * area;
      const bool same_place = glm::length(e.centre - DVec3(light.position)) <= tolerance;
      const bool same_facing = glm::dot(e.normal, DVec3(light.direction)) >= 0.99;
      if (same_area && same_place && same_facing) {
        light.duplicates_emissive_mesh = true;
        break;
      }
    }
  }
}

}  // namespace prism::collada
