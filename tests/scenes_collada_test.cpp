// Tests of the CS184 COLLADA loader: every shared file against counts taken from the XML
// independently (pugixml here, not the loader's code), the Cornell floor's normals, the area
// light / emissive quad duplicate and a synthetic file exercising every feature. Bad input:
// scenes_collada_errors_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <pugixml.hpp>

#include "core/error.h"
#include "scenes/collada_loader.h"
#include "scenes/scene_loader.h"
#include "tests/support/collada_test_helpers.h"
#include "tests/support/test_support.h"

namespace prism {
namespace {

using test::collada::kBase;
using test::collada::line_of;
using test::collada::load_text;
using test::collada::read_file;
using test::collada::replaced;

TEST(ScenesCollada, BaseDocumentLoads) {
  const Scene scene = load_text(kBase);
  ASSERT_EQ(scene.geometry.meshes.size(), 1u);
  EXPECT_EQ(scene.geometry.meshes[0].name, "n/tri/mat");
  EXPECT_EQ(scene.geometry.triangle_count(), 1u);
  ASSERT_EQ(scene.geometry.spheres.size(), 1u);
  EXPECT_EQ(scene.geometry.spheres[0].center, Vec3(0, 0, 2));
  EXPECT_FLOAT_EQ(scene.geometry.spheres[0].radius, 0.5f);
  ASSERT_EQ(scene.materials.size(), 2u);  // red + the default grey of the unbound sphere
  const Material& red = scene.materials[scene.geometry.meshes[0].material_id];
  EXPECT_EQ(red.type, MaterialType::kDiffuse);
  EXPECT_EQ(red.reflectance, Rgb(0.8f, 0.1f, 0.1f));
  const Material& grey = scene.materials[scene.geometry.spheres[0].material_id];
  EXPECT_EQ(grey.reflectance, Rgb(0.5f));
  EXPECT_EQ(scene.settings.width, 480);
  EXPECT_EQ(scene.settings.height, 360);
}

// ---- Every shared CS184 file, checked against counts read from its XML here. ----

struct XmlCounts {
  size_t triangles = 0, spheres = 0;
  std::map<std::string, int> lights;     // by type
  std::map<std::string, int> materials;  // by type, distinct bound materials (+ default)
};

pugi::xml_node by_id(const pugi::xml_document& doc, const char* url) {
  const std::string id = std::string(url).substr(1);
  return doc.find_node([&](pugi::xml_node n) { return id == n.attribute("id").value(); });
}

XmlCounts count_from_xml(const std::filesystem::path& path) {
  pugi::xml_document doc;
  EXPECT_TRUE(doc.load_file(path.c_str()));
  XmlCounts counts;
  std::set<std::string> bound;
  bool uses_default = false;
  const auto visual = by_id(
      doc,
      doc.child("COLLADA").child("scene").child("instance_visual_scene").attribute("url").value());
  for (const pugi::xpath_node& x : visual.select_nodes(".//instance_geometry")) {
    const pugi::xml_node instance = x.node();
    const pugi::xml_node geometry = by_id(doc, instance.attribute("url").value());
    const auto targets = instance.select_nodes(".//instance_material");
    for (const auto& t : targets) bound.insert(t.node().attribute("target").value());
    if (!geometry.child("mesh")) {
      ++counts.spheres;
      uses_default |= targets.empty();
      continue;
    }
    for (pugi::xml_node group : geometry.child("mesh").children()) {
      if (std::string(group.name()) != "polylist") continue;
      std::istringstream vcount(group.child_value("vcount"));
      for (int n; vcount >> n;) counts.triangles += n - 2;
      uses_default |= !group.attribute("material");
    }
  }
  for (const pugi::xpath_node& x : visual.select_nodes(".//instance_light")) {
    const pugi::xml_node light = by_id(doc, x.node().attribute("url").value());
    const pugi::xml_node cgl = light.select_node("extra/technique[@profile='CGL']/*").node();
    ++counts.lights[cgl ? cgl.name() : light.child("technique_common").first_child().name()];
  }
  for (const std::string& target : bound) {
    const pugi::xml_node material = by_id(doc, target.c_str());
    const pugi::xml_node effect =
        by_id(doc, material.child("instance_effect").attribute("url").value());
    const pugi::xml_node cgl = effect.select_node("extra/technique[@profile='CGL']/*").node();
    ++counts.materials[cgl ? cgl.name() : "diffuse"];
  }
  if (uses_default) ++counts.materials["diffuse"];
  return counts;
}

TEST(ScenesCollada, EverySharedFileMatchesItsXml) {
  const auto names = test::cs184_scene_names();
  if (names.empty()) GTEST_SKIP() << "../shared/scenes/cs184 absent";
  // Sizes stated in docs/cs184-collada.md (and checked by hand against vcount sums).
  const std::map<std::string, std::pair<size_t, size_t>> documented = {
      {"CBempty.dae", {12, 0}},   {"CBspheres_lambertian.dae", {12, 2}},
      {"CBspheres.dae", {12, 2}}, {"CBbunny.dae", {28588, 0}},
      {"bunny.dae", {33696, 0}},  {"banana.dae", {2458, 0}},
      {"cow.dae", {5856, 0}},     {"cube.dae", {12, 0}}};
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    const auto path = *test::cs184_scene(name);
    const Scene scene = load_scene(path);
    const XmlCounts xml = count_from_xml(path);
    EXPECT_EQ(scene.geometry.triangle_count(), xml.triangles);
    EXPECT_EQ(scene.geometry.spheres.size(), xml.spheres);
    if (const auto it = documented.find(name); it != documented.end()) {
      EXPECT_EQ(scene.geometry.triangle_count(), it->second.first);
      EXPECT_EQ(scene.geometry.spheres.size(), it->second.second);
    }
    std::map<std::string, int> lights, materials;
    for (const Light& l : scene.lights) ++lights[std::string(to_string(l.type))];
    for (const Material& m : scene.materials) ++materials[std::string(to_string(m.type))];
    EXPECT_EQ(lights, xml.lights);
    EXPECT_EQ(materials, xml.materials);
    for (const TriangleMesh& mesh : scene.geometry.meshes) {
      for (const Vec3& n : mesh.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-5f) << mesh.name;
    }
    for (const Light& l : scene.lights) EXPECT_EQ(l.up, Vec3(0, 0, 1));
    EXPECT_EQ(scene.camera.up, Vec3(0, 0, 1));
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
  }
}

// The Cornell floor winds downward while its normals point up into the box; the loader keeps
// both, and the shared surface_at turns the geometric normal to the shading side.
TEST(ScenesCollada, CornellFloorNormalsVersusWinding) {
  PRISM_REQUIRE_CS184(path, "CBempty.dae");
  const Scene scene = load_scene(path);
  const auto& meshes = scene.geometry.meshes;
  const auto floor = std::find_if(meshes.begin(), meshes.end(), [](const TriangleMesh& m) {
    return m.name.rfind("floor/", 0) == 0;
  });
  ASSERT_NE(floor, meshes.end());
  ASSERT_EQ(floor->triangles.size(), 2u);
  for (const Vec3& n : floor->normals) EXPECT_NEAR(n.z, 1.0f, 1e-5f);
  const auto geom_id = static_cast<uint32_t>(floor - meshes.begin());
  for (uint32_t prim = 0; prim < 2; ++prim) {
    const glm::uvec3 t = floor->triangles[prim];
    const Vec3 winding = glm::cross(floor->positions[t.y] - floor->positions[t.x],
                                    floor->positions[t.z] - floor->positions[t.x]);
    EXPECT_LT(winding.z, 0.0f) << "the file's floor winds downward";
    const Ray ray{Vec3(0.1f, 0.2f, 1.0f), 0.0f, Vec3(0, 0, -1), kInfinity};
    const SurfaceInteraction si = scene.surface_at(ray, Hit{1.0f, 0.25f, 0.25f, geom_id, prim});
    EXPECT_GT(si.geometric_normal.z, 0.99f);
    EXPECT_GT(si.shading_normal.z, 0.99f);
  }
}

// Emitted power (radiance x area x pi) of everything that emits on its own account.
double emitted_power(const Scene& scene) {
  double power = 0.0;
  for (const TriangleMesh& mesh : scene.geometry.meshes) {
    const Material& m = scene.materials[mesh.material_id];
    if (!m.is_emissive()) continue;
    for (const glm::uvec3& t : mesh.triangles) {
      const double area = 0.5 * glm::length(glm::cross(mesh.positions[t.y] - mesh.positions[t.x],
                                                       mesh.positions[t.z] - mesh.positions[t.x]));
      power += kPi * area * m.radiance.x;
    }
  }
  for (const Light& l : scene.lights) {
    if (l.type == LightType::kArea && !l.duplicates_emissive_mesh) {
      power += kPi * glm::length(glm::cross(l.edge_u, l.edge_v)) * l.color.x;
    }
  }
  return power;
}

TEST(ScenesCollada, AreaLightDuplicatingTheEmissiveQuadIsFlagged) {
  for (const char* name : {"CBspheres.dae", "CBspheres_lambertian.dae", "CBbunny.dae"}) {
    SCOPED_TRACE(name);
    PRISM_REQUIRE_CS184(path, name);
    const Scene scene = load_scene(path);
    ASSERT_EQ(scene.lights.size(), 1u);
    const Light& area = scene.lights[0];
    EXPECT_EQ(area.type, LightType::kArea);
    EXPECT_TRUE(area.duplicates_emissive_mesh);
    EXPECT_NEAR(glm::length(area.edge_u), 0.6f, 1e-6f);
    EXPECT_NEAR(glm::length(area.edge_v), 0.8f, 1e-6f);
    EXPECT_NEAR(area.position.z, 1.49f, 1e-6f);
    EXPECT_NEAR(area.direction.z, -1.0f, 1e-6f);
    // Energy is not doubled: the same as the file with the area light removed, and the same as
    // the file with the emissive quad removed (then the area light is the only emitter).
    const std::string text = read_file(path);
    const Scene without_light =
        load_text(replaced(text, "<instance_light url=\"#Area-light\"/>", ""));
    EXPECT_TRUE(without_light.lights.empty());
    // The quad stays but turns into a plain wall: bound to the ceiling's diffuse material.
    const Scene without_quad =
        load_text(replaced(text, "target=\"#light-material\"", "target=\"#ceiling-material\""));
    ASSERT_EQ(without_quad.lights.size(), 1u);
    EXPECT_FALSE(without_quad.lights[0].duplicates_emissive_mesh);
    EXPECT_NEAR(emitted_power(scene), kPi * 0.48 * 10.0, 1e-3);
    EXPECT_NEAR(emitted_power(without_light), emitted_power(scene), 1e-3);
    EXPECT_NEAR(emitted_power(without_quad), emitted_power(scene), 1e-3);
  }
}

// CBempty lights its box with a point light (no CGL area light) besides the emissive quad:
// nothing there is an area light, so nothing may be flagged.
TEST(ScenesCollada, CBemptyHasAPointLightAndTheEmissiveQuad) {
  PRISM_REQUIRE_CS184(path, "CBempty.dae");
  const Scene scene = load_scene(path);
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].type, LightType::kPoint);
  EXPECT_FALSE(scene.lights[0].duplicates_emissive_mesh);
  EXPECT_EQ(scene.lights[0].color, Rgb(5.0f));
  EXPECT_NEAR(emitted_power(scene), kPi * 0.48 * 10.0, 1e-3);
}

TEST(ScenesCollada, AreaLightAwayFromTheQuadIsNotADuplicate) {
  PRISM_REQUIRE_CS184(path, "CBspheres.dae");
  const std::string text = read_file(path);
  const std::string node = "<matrix sid=\"transform\">0.6 0 0 0 0 0.8 0 0 0 0 1 1.49";
  const Scene moved =
      load_text(replaced(text, node, "<matrix sid=\"transform\">0.6 0 0 0.3 0 0.8 0 0 0 0 1 1.49"));
  EXPECT_FALSE(moved.lights[0].duplicates_emissive_mesh);
  const Scene bigger =
      load_text(replaced(text, node, "<matrix sid=\"transform\">0.7 0 0 0 0 0.8 0 0 0 0 1 1.49"));
  EXPECT_FALSE(bigger.lights[0].duplicates_emissive_mesh);
}

// ---- A synthetic file exercising every feature. ----

constexpr const char* kFeatures = R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
<asset><up_axis>Y_UP</up_axis></asset>
<library_cameras>
<camera id="cam"><optics><technique_common><perspective><yfov>30</yfov><aspect_ratio>2</aspect_ratio><znear>0.5</znear><zfar>50</zfar></perspective></technique_common></optics></camera>
</library_cameras>
<library_lights>
<light id="spot"><technique_common><spot><color>1 2 3</color><constant_attenuation>1</constant_attenuation><linear_attenuation>0.5</linear_attenuation><quadratic_attenuation>0.25</quadratic_attenuation><falloff_angle>40</falloff_angle><falloff_exponent>2</falloff_exponent></spot></technique_common></light>
<light id="point"><technique_common><point><color>4 4 4</color></point></technique_common></light>
<light id="sun"><technique_common><directional><color>0.5 0.5 0.5</color></directional></technique_common></light>
<light id="sky"><technique_common><ambient><color>0.1 0.2 0.3</color></ambient></technique_common></light>
</library_lights>
<library_effects>
<effect id="e-emission"><extra><technique profile="CGL"><emission><radiance>7 8 9</radiance></emission></technique></extra></effect>
<effect id="e-mirror"><extra><technique profile="CGL"><mirror><reflectance>0.9 0.8 0.7</reflectance></mirror></technique></extra></effect>
<effect id="e-glass"><extra><technique profile="CGL"><glass><reflectance>1 1 1</reflectance><transmittance>0.5 0.6 0.7</transmittance><roughness>0</roughness><ior>1.45</ior></glass></technique></extra></effect>
<effect id="e-refraction"><extra><technique profile="CGL"><refraction><transmittance>0.3 0.3 0.3</transmittance><roughness>0.1</roughness><ior>1.33</ior></refraction></technique></extra></effect>
<effect id="e-microfacet"><extra><technique profile="CGL"><microfacet><alpha>0.25</alpha><eta>0.2 0.9 1.1</eta><k>3.9 2.4 2.2</k></microfacet></technique></extra></effect>
<effect id="e-phong"><profile_COMMON><technique sid="common"><phong><diffuse><color>0.1 0.2 0.3 1</color></diffuse></phong></technique></profile_COMMON></effect>
<effect id="e-textured"><profile_COMMON><technique sid="common"><phong><diffuse><texture texture="img" texcoord="uv"/></diffuse></phong></technique></profile_COMMON></effect>
</library_effects>
<library_materials>
<material id="m-emission"><instance_effect url="#e-emission"/></material>
<material id="m-mirror"><instance_effect url="#e-mirror"/></material>
<material id="m-glass"><instance_effect url="#e-glass"/></material>
<material id="m-refraction"><instance_effect url="#e-refraction"/></material>
<material id="m-microfacet"><instance_effect url="#e-microfacet"/></material>
<material id="m-phong"><instance_effect url="#e-phong"/></material>
<material id="m-textured"><instance_effect url="#e-textured"/></material>
</library_materials>
<library_geometries>
<geometry id="quad"><mesh>
<source id="quad-pos"><float_array id="quad-pos-a" count="12">0 0 0 1 0 0 1 1 0 0 1 0</float_array><technique_common><accessor source="#quad-pos-a" count="4" stride="3"/></technique_common></source>
<source id="quad-n"><float_array id="quad-n-a" count="3">0 0 1</float_array><technique_common><accessor source="#quad-n-a" count="1" stride="3"/></technique_common></source>
<source id="quad-uv"><float_array id="quad-uv-a" count="8">0 0 1 0 1 1 0 1</float_array><technique_common><accessor source="#quad-uv-a" count="4" stride="2"/></technique_common></source>
<vertices id="quad-v"><input semantic="POSITION" source="#quad-pos"/></vertices>
<polylist material="q" count="1">
<input semantic="VERTEX" source="#quad-v" offset="0"/>
<input semantic="TEXCOORD" source="#quad-uv" offset="2" set="0"/>
<input semantic="NORMAL" source="#quad-n" offset="1"/>
<vcount>4</vcount>
<p>0 0 3  1 0 2  2 0 1  3 0 0</p>
</polylist>
</mesh></geometry>
<geometry id="tri"><mesh>
<source id="tri-pos"><float_array id="tri-pos-a" count="9">0 0 0 1 0 0 0 0 -1</float_array><technique_common><accessor source="#tri-pos-a" count="3" stride="3"/></technique_common></source>
<vertices id="tri-v"><input semantic="POSITION" source="#tri-pos"/></vertices>
<triangles material="m" count="1"><input semantic="VERTEX" source="#tri-v" offset="0"/><p>0 1 2</p></triangles>
</mesh></geometry>
</library_geometries>
<library_visual_scenes>
<visual_scene id="Scene">
<node id="parent"><translate>1 2 3</translate><rotate>0 0 1 90</rotate>
<node id="child"><matrix>1 0 0 10 0 1 0 0 0 0 1 0 0 0 0 1</matrix><scale>2 2 2</scale>
<instance_geometry url="#quad"><bind_material><technique_common><instance_material symbol="q" target="#m-phong"/></technique_common></bind_material></instance_geometry>
</node>
</node>
<node id="mirrored"><scale>-1 1 1</scale><instance_geometry url="#quad"><bind_material><technique_common><instance_material symbol="q" target="#m-phong"/></technique_common></bind_material></instance_geometry></node>
<node id="spot-node"><translate>0 5 0</translate><rotate>1 0 0 -90</rotate><instance_light url="#spot"/></node>
<node id="point-node"><translate>1 2 3</translate><instance_light url="#point"/></node>
<node id="sun-node"><instance_light url="#sun"/></node>
<node id="sky-node"><instance_light url="#sky"/></node>
<node id="cam-node"><translate>0 3 10</translate><instance_camera url="#cam"/></node>
MATERIAL_NODES
</visual_scene>
</library_visual_scenes>
<scene><instance_visual_scene url="#Scene"/></scene>
</COLLADA>
)";

constexpr std::array<const char*, 7> kMaterialKinds = {
    "emission", "mirror", "glass", "refraction", "microfacet", "phong", "textured"};

std::string features_document() {
  std::string nodes;
  for (const std::string kind : kMaterialKinds) {
    nodes += "<node id=\"with-" + kind + "\"><translate>0 -1 0</translate>";
    nodes += "<instance_geometry url=\"#tri\"><bind_material><technique_common>";
    nodes += "<instance_material symbol=\"m\" target=\"#m-" + kind + "\"/>";
    nodes += "</technique_common></bind_material></instance_geometry></node>\n";
  }
  return replaced(kFeatures, "MATERIAL_NODES\n", nodes);
}

void expect_near(const Vec3& actual, const Vec3& expected, float tolerance = 1e-5f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance)
      << "actual " << actual.x << " " << actual.y << " " << actual.z;
  EXPECT_NEAR(actual.y, expected.y, tolerance)
      << "actual " << actual.x << " " << actual.y << " " << actual.z;
  EXPECT_NEAR(actual.z, expected.z, tolerance)
      << "actual " << actual.x << " " << actual.y << " " << actual.z;
}

const TriangleMesh& mesh_named(const Scene& scene, const std::string& name) {
  for (const TriangleMesh& m : scene.geometry.meshes) {
    if (m.name == name) return m;
  }
  ADD_FAILURE() << "no mesh " << name;
  static const TriangleMesh none;
  return none;
}

TEST(ScenesCollada, SyntheticNodesTransformsAndFanTriangulation) {
  const Scene scene = load_text(features_document());
  const TriangleMesh& quad = mesh_named(scene, "child/quad/q");
  // By hand: p -> scale 2 -> matrix (+10 x) -> rotate 90 about z -> translate (1,2,3), in the
  // Y-up file frame: (1 - 2y, 2x + 12, 2z + 3); then Y_UP -> Z-up maps (x, y, z) to (x, -z, y).
  ASSERT_EQ(quad.positions.size(), 4u);
  expect_near(quad.positions[0], {1, -3, 12});
  expect_near(quad.positions[1], {1, -3, 14});
  expect_near(quad.positions[2], {-1, -3, 14});
  expect_near(quad.positions[3], {-1, -3, 12});
  ASSERT_EQ(quad.triangles.size(), 2u);  // the quad as a fan around its first corner
  EXPECT_EQ(quad.triangles[0], glm::uvec3(0, 1, 2));
  EXPECT_EQ(quad.triangles[1], glm::uvec3(0, 2, 3));
  ASSERT_EQ(quad.normals.size(), 6u);
  for (const Vec3& n : quad.normals) expect_near(n, {0, -1, 0});
  // Texture coordinates follow their own offset in <p> (reversed against the vertices here).
  const std::vector<Vec2> uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 1}, {1, 0}, {0, 0}};
  EXPECT_EQ(quad.uvs, uvs);
  EXPECT_EQ(scene.materials[quad.material_id].reflectance, Rgb(0.1f, 0.2f, 0.3f));

  // A mirroring scale keeps the winding on the side of the transformed normals.
  const TriangleMesh& mirrored = mesh_named(scene, "mirrored/quad/q");
  ASSERT_EQ(mirrored.triangles.size(), 2u);
  for (size_t t = 0; t < 2; ++t) {
    const glm::uvec3 tri = mirrored.triangles[t];
    const Vec3 winding = glm::cross(mirrored.positions[tri.y] - mirrored.positions[tri.x],
                                    mirrored.positions[tri.z] - mirrored.positions[tri.x]);
    EXPECT_GT(glm::dot(winding, mirrored.normals[3 * t]), 0.0f);
  }
}

TEST(ScenesCollada, SyntheticLightsInTheZUpWorld) {
  const Scene scene = load_text(features_document());
  ASSERT_EQ(scene.lights.size(), 4u);
  const Light& spot = scene.lights[0];
  EXPECT_EQ(spot.type, LightType::kSpot);
  expect_near(spot.position, {0, 0, 5});    // 5 above the origin in the Y-up file
  expect_near(spot.direction, {0, 0, -1});  // rotated to point down
  EXPECT_EQ(spot.color, Rgb(1, 2, 3));
  EXPECT_FLOAT_EQ(spot.constant_attenuation, 1.0f);
  EXPECT_FLOAT_EQ(spot.linear_attenuation, 0.5f);
  EXPECT_FLOAT_EQ(spot.quadratic_attenuation, 0.25f);
  EXPECT_FLOAT_EQ(spot.falloff_angle_deg, 40.0f);
  EXPECT_FLOAT_EQ(spot.falloff_exponent, 2.0f);
  const Light& point = scene.lights[1];
  EXPECT_EQ(point.type, LightType::kPoint);
  expect_near(point.position, {1, -3, 2});
  EXPECT_FLOAT_EQ(point.constant_attenuation, 1.0f);
  EXPECT_FLOAT_EQ(point.quadratic_attenuation, 0.0f);
  const Light& sun = scene.lights[2];
  EXPECT_EQ(sun.type, LightType::kDirectional);
  expect_near(sun.direction, {0, 1, 0});  // the file's -Z
  const Light& sky = scene.lights[3];
  EXPECT_EQ(sky.type, LightType::kAmbient);
  EXPECT_EQ(sky.color, Rgb(0.1f, 0.2f, 0.3f));
  for (const Light& l : scene.lights) EXPECT_EQ(l.up, Vec3(0, 0, 1));
}

TEST(ScenesCollada, SyntheticMaterialsOfEveryKind) {
  const Scene scene = load_text(features_document());
  std::map<std::string, Material> by_kind;
  for (const std::string kind : kMaterialKinds) {
    const TriangleMesh& mesh = mesh_named(scene, "with-" + kind + "/tri/m");
    ASSERT_EQ(mesh.triangle_count(), 1u);  // from <triangles>
    by_kind[kind] = scene.materials[mesh.material_id];
  }
  EXPECT_EQ(by_kind["emission"].type, MaterialType::kEmission);
  EXPECT_EQ(by_kind["emission"].radiance, Rgb(7, 8, 9));
  EXPECT_EQ(by_kind["mirror"].type, MaterialType::kMirror);
  EXPECT_EQ(by_kind["mirror"].reflectance, Rgb(0.9f, 0.8f, 0.7f));
  EXPECT_EQ(by_kind["glass"].type, MaterialType::kGlass);
  EXPECT_EQ(by_kind["glass"].transmittance, Rgb(0.5f, 0.6f, 0.7f));
  EXPECT_FLOAT_EQ(by_kind["glass"].ior, 1.45f);
  EXPECT_FLOAT_EQ(by_kind["glass"].roughness, 0.0f);
  EXPECT_EQ(by_kind["refraction"].type, MaterialType::kRefraction);
  EXPECT_EQ(by_kind["refraction"].transmittance, Rgb(0.3f));
  EXPECT_FLOAT_EQ(by_kind["refraction"].roughness, 0.1f);
  EXPECT_FLOAT_EQ(by_kind["refraction"].ior, 1.33f);
  EXPECT_EQ(by_kind["microfacet"].type, MaterialType::kMicrofacet);
  EXPECT_FLOAT_EQ(by_kind["microfacet"].alpha, 0.25f);
  EXPECT_EQ(by_kind["microfacet"].eta, Rgb(0.2f, 0.9f, 1.1f));
  EXPECT_EQ(by_kind["microfacet"].k, Rgb(3.9f, 2.4f, 2.2f));
  EXPECT_EQ(by_kind["phong"].type, MaterialType::kDiffuse);
  EXPECT_EQ(by_kind["phong"].reflectance, Rgb(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(by_kind["textured"].type, MaterialType::kDiffuse);
  EXPECT_EQ(by_kind["textured"].reflectance, Rgb(0.5f));
  EXPECT_EQ(scene.materials.size(), kMaterialKinds.size());  // each bound material once
}

TEST(ScenesCollada, SyntheticCameraUsesYfovAndAspect) {
  const Scene scene = load_text(features_document());
  EXPECT_NEAR(scene.camera.vfov_deg, 30.0f, 1e-4f);
  const double hfov = 2.0 * std::atan(std::tan(15.0 * kPi / 180.0) * 2.0) * 180.0 / kPi;
  EXPECT_NEAR(scene.camera.hfov_deg, hfov, 1e-4);
  EXPECT_FLOAT_EQ(scene.camera.znear, 0.5f);
  // The camera node sits at file (0,3,10): one unit in front is (0,3,9), world (0,-9,3).
  const Vec3 c = glm::normalize(scene.camera.position - scene.camera.target);
  expect_near(c, glm::normalize(Vec3(0, -9, 3)));
  EXPECT_EQ(scene.camera.up, Vec3(0, 0, 1));
}

// The up axis is a global rotation into prism's Z-up world: reading the same numbers as Y_UP
// or X_UP gives the Z_UP scene turned so the file's up axis becomes +Z, camera included (the
// framing's axis-aligned box turns exactly with it).
TEST(ScenesCollada, UpAxisIsAGlobalRotation) {
  const std::string y_up = features_document();
  const Scene as_z = load_text(replaced(y_up, "Y_UP", "Z_UP"));
  const Scene as_y = load_text(y_up);
  const Scene as_x = load_text(replaced(y_up, "Y_UP", "X_UP"));
  const auto y_to_z = [](const Vec3& p) { return Vec3(p.x, -p.z, p.y); };
  const auto x_to_z = [](const Vec3& p) { return Vec3(-p.z, p.y, p.x); };
  for (const auto& [scene, rotate] : {std::pair{&as_y, +y_to_z}, std::pair{&as_x, +x_to_z}}) {
    ASSERT_EQ(scene->geometry.meshes.size(), as_z.geometry.meshes.size());
    for (size_t m = 0; m < as_z.geometry.meshes.size(); ++m) {
      const auto& expected = as_z.geometry.meshes[m].positions;
      const auto& actual = scene->geometry.meshes[m].positions;
      ASSERT_EQ(actual.size(), expected.size());
      for (size_t i = 0; i < actual.size(); ++i) expect_near(actual[i], rotate(expected[i]), 1e-4f);
    }
    for (size_t l = 0; l < as_z.lights.size(); ++l) {
      expect_near(scene->lights[l].position, rotate(as_z.lights[l].position), 1e-4f);
      expect_near(scene->lights[l].direction, rotate(as_z.lights[l].direction), 1e-5f);
    }
    expect_near(scene->camera.target, rotate(as_z.camera.target), 1e-4f);
    expect_near(scene->camera.position, rotate(as_z.camera.position), 1e-4f);
    EXPECT_EQ(scene->camera.up, Vec3(0, 0, 1));
  }
}

TEST(ScenesCollada, FileWithoutCameraIsFramedFromTheFront) {
  const Scene scene = load_text(kBase);
  const Bounds3 b = scene.geometry.bounds();
  expect_near(scene.camera.target, b.center());
  const float r = 1.5f * glm::length(b.diagonal());
  expect_near(scene.camera.position, b.center() + Vec3(0, -r, 0), 1e-4f);
}

TEST(ScenesCollada, LiteralCameraOption) {
  SceneLoadOptions literal;
  literal.literal_camera = true;
  const Scene scene = load_text(features_document(), literal);
  // File (0,3,10) looking down -Z with +Y up -> world (0,-10,3) looking +Y with +Z up.
  expect_near(scene.camera.position, {0, -10, 3});
  expect_near(glm::normalize(scene.camera.target - scene.camera.position), {0, 1, 0});
  expect_near(scene.camera.up, {0, 0, 1});
}

// ---- Defects the homework tolerates: one warning each, then read as the homework reads them.
// (Real errors are in scenes_collada_errors_test.cpp.) ----

// kBase with a perspective camera whose node has `matrix` as its <matrix> text.
std::string with_camera_matrix(const std::string& matrix) {
  std::string text = replaced(kBase, "<library_effects>",
                              "<library_cameras><camera id=\"cam\"><optics><technique_common>"
                              "<perspective><xfov>49.13434</xfov><aspect_ratio>1.777778</"
                              "aspect_ratio></perspective></technique_common></optics></camera>"
                              "</library_cameras>\n<library_effects>");
  return replaced(text, "</visual_scene>",
                  "<node id=\"cam-node\">\n<matrix>" + matrix +
                      "</matrix>\n<instance_camera url=\"#cam\"/></node>\n</visual_scene>");
}

// Expects exactly one warning, at `line` of the loaded file, ending with `tail`.
void expect_one_warning(const Scene& scene, int line, const std::string& tail) {
  ASSERT_EQ(scene.warnings.size(), 1u);
  const std::string& w = scene.warnings[0];
  EXPECT_NE(w.find("scene.dae:" + std::to_string(line) + ": "), std::string::npos) << w;
  EXPECT_EQ(w.find('\n'), std::string::npos) << w;
  ASSERT_GE(w.size(), tail.size()) << w;
  EXPECT_EQ(w.substr(w.size() - tail.size()), tail) << w;
}

void expect_same_camera(const Camera& a, const Camera& b) {
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.target, b.target);
  EXPECT_EQ(a.up, b.up);
  EXPECT_EQ(a.hfov_deg, b.hfov_deg);
  EXPECT_EQ(a.vfov_deg, b.vfov_deg);
}

TEST(ScenesCollada, ShortCameraMatrixFramesAsTheHomework) {
  // The CBempty camera, and the same matrix with one number lost as in the homework's
  // CBgems.dae: its 15 numbers fill rows 0-2 and three of row 3. The homework frames with
  // c = normalize(xyz of M (0, 0, -1, 1)), reading only the top three rows: (0, 2, 0) from both
  // (dividing by the short matrix's w = -1 would turn the camera round).
  const std::string full = "-1 0 0 0 0 0 1 3 0 1 0 0 0 0 0 1";
  const std::string gems = "-1 0 0 0 0 0 1 3 0 0 0 0 0 0 1";
  const Scene reference = load_text(with_camera_matrix(full));
  EXPECT_TRUE(reference.warnings.empty());
  const std::string text = with_camera_matrix(gems);
  const Scene scene = load_text(text);
  expect_one_warning(scene, line_of(text, gems),
                     "<matrix>: 15 numbers, not 16; the missing ones are read as 0, as the CS184 "
                     "homework does");
  expect_same_camera(scene.camera, reference.camera);
  expect_near(glm::normalize(scene.camera.position - scene.camera.target), {0, 1, 0});
  // The same numbers padded with zeros, as ../shared/peers/cycles_render.py frames them.
  const Scene padded = load_text(with_camera_matrix(gems + " 0"));
  EXPECT_TRUE(padded.warnings.empty());
  expect_same_camera(scene.camera, padded.camera);
  // A matrix short of only its final 1 frames like the full one too.
  expect_same_camera(load_text(with_camera_matrix("-1 0 0 0 0 0 1 3 0 1 0 0 0 0 0")).camera,
                     reference.camera);
  // The file's camera taken literally has no up axis left (row 2 is zero): an error there.
  SceneLoadOptions literal;
  literal.literal_camera = true;
  EXPECT_THROW(load_text(text, literal), Error);
}

TEST(ScenesCollada, ShortMatrixAboveLightsReadsTheTopRows) {
  // Lights, like cameras, come from the top three rows in the homework.
  const std::string lights =
      "<library_lights><light id=\"l\"><technique_common><point><color>1 1 1</color>"
      "</point></technique_common></light></library_lights>\n<library_geometries>";
  const std::string base = replaced(kBase, "<library_geometries>", lights);
  const auto with_light_matrix = [&](const std::string& matrix) {
    return replaced(base, "</visual_scene>",
                    "<node id=\"lamp\"><node><matrix>" + matrix +
                        "</matrix><instance_light url=\"#l\"/></node></node>\n</visual_scene>");
  };
  const Scene full = load_text(with_light_matrix("1 0 0 1 0 1 0 2 0 0 1 3 0 0 0 1"));
  const std::string text = with_light_matrix("1 0 0 1 0 1 0 2 0 0 1 3 0 0 0");
  const Scene scene = load_text(text);
  expect_one_warning(scene, line_of(text, "1 0 0 1 0 1 0 2 0 0 1 3 0 0 0<"),
                     "15 numbers, not 16; the missing ones are read as 0, as the CS184 homework "
                     "does");
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].position, Vec3(1, 2, 3));
  EXPECT_EQ(scene.lights[0].position, full.lights[0].position);
  EXPECT_EQ(scene.lights[0].direction, full.lights[0].direction);
}

TEST(ScenesCollada, LongMatrixReadsTheFirstSixteen) {
  const std::string node = "<node id=\"n\">";
  const Scene plain =
      load_text(replaced(kBase, node, node + "<matrix>1 0 0 5 0 1 0 0 0 0 1 0 0 0 0 1</matrix>"));
  const std::string text =
      replaced(kBase, node, node + "\n<matrix>1 0 0 5 0 1 0 0 0 0 1 0 0 0 0 1 7 7</matrix>");
  const Scene scene = load_text(text);
  expect_one_warning(scene, line_of(text, "7 7</matrix>"),
                     "<matrix>: 18 numbers, not 16; the numbers after the 16th are ignored, as the "
                     "CS184 homework does");
  EXPECT_EQ(scene.geometry.meshes[0].positions, plain.geometry.meshes[0].positions);
  EXPECT_EQ(scene.geometry.meshes[0].positions[0], Vec3(5, 0, 0));
}

TEST(ScenesCollada, FloatArrayCountDisagreeingWithItsNumbers) {
  const Scene plain = load_text(kBase);
  // More declared than present: the homework pads with copies of the last number, which no
  // accessor or index here uses; the numbers present are read. A huge count allocates nothing.
  for (const std::string count : {"12", "999999999999"}) {
    SCOPED_TRACE(count);
    const std::string text = replaced(kBase, "count=\"9\"", "count=\"" + count + "\"");
    const Scene scene = load_text(text);
    expect_one_warning(scene, line_of(text, "tri-pos-array\""),
                       "<float_array id=\"tri-pos-array\">: count=\"" + count +
                           "\" but the element holds 9 numbers; the 9 present are read, as the "
                           "CS184 homework reads them, and nothing may use more");
    EXPECT_EQ(scene.geometry.meshes[0].positions, plain.geometry.meshes[0].positions);
  }
  // Fewer declared than present: the homework reads only `count` numbers.
  const std::string text =
      replaced(kBase, "0 0 0 1 0 0 0 1 0</float_array>", "0 0 0 1 0 0 0 1 0 7 7 7</float_array>");
  const Scene scene = load_text(text);
  expect_one_warning(scene, line_of(text, "tri-pos-array\""),
                     "count=\"9\" but the element holds 12 numbers; only the first 9 are read, as "
                     "the CS184 homework does");
  EXPECT_EQ(scene.geometry.meshes[0].positions, plain.geometry.meshes[0].positions);
  // ... so an accessor that needs the numbers beyond the count reads past the end: an error
  // (the homework would read outside its array).
  EXPECT_THROW(
      load_text(replaced(replaced(text, "count=\"3\" stride=\"3\"", "count=\"4\" stride=\"3\""),
                         "<p>0 1 2</p>", "<p>0 1 3</p>")),
      Error);
}

TEST(ScenesCollada, ColourWithMissingOrExtraNumbers) {
  const std::string colour = "0.8 0.1 0.1 1";
  struct Case {
    std::string numbers;
    Rgb expected;
    std::string tail;
  };
  const std::vector<Case> cases = {
      {"0.8 0.1", Rgb(0.8f, 0.1f, 0.0f),
       "<color>: 2 numbers, not 3; the missing ones are read as 0, as the CS184 homework does"},
      {"0.8", Rgb(0.8f, 0.0f, 0.0f),
       "<color>: 1 number, not 3; the missing ones are read as 0, as the CS184 homework does"},
      {"0.8 0.1 0.1 1 0.5", Rgb(0.8f, 0.1f, 0.1f),
       "<color>: 5 numbers, not 3 or 4; only the first 3 are read, as the CS184 homework does"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.numbers);
    const std::string text = replaced(kBase, colour, c.numbers);
    const Scene scene = load_text(text);
    expect_one_warning(scene, line_of(text, "<color>"), c.tail);
    EXPECT_EQ(scene.materials[scene.geometry.meshes[0].material_id].reflectance, c.expected);
  }
}

// ---- Bad input: one test per class; each names the element or id and gives its line. ----

}  // namespace
}  // namespace prism
