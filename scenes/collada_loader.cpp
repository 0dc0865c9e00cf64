// CS184 COLLADA loader: walks the visual scene's node tree and hands each element to the module
// that knows it (scenes/collada/*: document and references, transforms, geometry, materials,
// lights, camera framing). Coordinates: prism's world is Z-up; see collada/transforms.h.
#include "scenes/collada_loader.h"

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/error.h"
#include "scenes/collada/camera_framing.h"
#include "scenes/collada/document.h"
#include "scenes/collada/geometry.h"
#include "scenes/collada/lights.h"
#include "scenes/collada/materials.h"
#include "scenes/collada/transforms.h"

namespace prism {
namespace {

using namespace collada;

// Limits that keep hostile files (deep nesting, <instance_node> cycles or fan-outs, a mesh
// instanced millions of times) from exhausting the stack, time or memory. Real files are far
// below them: the largest CS184 scene has 10 nodes and 34k triangles.
constexpr int kMaxNodeDepth = 256;
constexpr size_t kMaxNodeVisits = 100'000;
constexpr size_t kMaxTriangles = size_t{1} << 24;

class SceneBuilder {
 public:
  SceneBuilder(const Document& doc, Scene& scene)
      : doc_(doc), scene_(scene), materials_(doc, scene.materials) {}

  /// Fails naming `visual_scene` when building its nodes would visit more than kMaxNodeVisits
  /// of them, counted before anything is built: a fan-out of <instance_node>s (each node
  /// instancing the next twice: 2^40 visits through 40 nodes) is refused in time linear in the
  /// file. Each node's count is computed once; a node met again while its own count is open (a
  /// cycle) counts one here, and visit() reports the cycle.
  void check_visit_count(pugi::xml_node visual_scene) {
    std::unordered_map<const void*, size_t> counts;
    if (count_visits(visual_scene, counts) - 1 > kMaxNodeVisits) {
      doc_.fail(visual_scene,
                "the scene instantiates more than " + std::to_string(kMaxNodeVisits) + " nodes");
    }
  }

  /// Builds `node` and what it holds and instances. check_visit_count() has bounded the visits.
  void visit(pugi::xml_node node, const DMat4& parent, int depth) {
    if (depth > kMaxNodeDepth) {
      doc_.fail(node, "nodes nest deeper than " + std::to_string(kMaxNodeDepth) + " levels");
    }
    if (std::find(path_.begin(), path_.end(), node) != path_.end()) {
      doc_.fail(node, "node '" + std::string(node.attribute("id").value()) +
                          "' instances itself through <instance_node> (a cycle)");
    }
    path_.push_back(node);
    std::vector<ShortMatrix> short_matrices;
    const DMat4 world = parent * node_transform(doc_, node, &short_matrices);
    for (const ShortMatrix& short_matrix : short_matrices) check_short_matrix(node, short_matrix);
    for (pugi::xml_node child = node.first_child(); child; child = child.next_sibling()) {
      const std::string_view name = child.name();
      if (name == "node") {
        visit(child, world, depth + 1);
      } else if (name == "instance_node") {
        visit(doc_.resolve(child, "url", "node"), world, depth + 1);
      } else if (name == "instance_geometry") {
        add_geometry(child, world, node);
      } else if (name == "instance_light") {
        scene_.lights.push_back(parse_light(doc_, child, world));
      } else if (name == "instance_camera") {
        // The first camera in document order is the scene's camera, as in the homework.
        if (!camera_instance_) {
          camera_instance_ = child;
          camera_world_ = world;
        }
      }
      // <instance_controller> (skinning) is not part of the CS184 dialect and is skipped.
    }
    path_.pop_back();
  }

  pugi::xml_node camera_instance() const { return camera_instance_; }
  const DMat4& camera_world() const { return camera_world_; }

 private:
  // The homework reads a short <matrix> with the missing numbers as 0. It reads cameras and
  // lights through the matrix's top three rows only, so they come out as the file meant; but
  // it divides vertex positions by the bottom row (w), which a missing bottom-right 1 makes 0
  // at the node's origin: geometry under such a node is lost there, so here it is an error.
  void check_short_matrix(pugi::xml_node node, const ShortMatrix& short_matrix) const {
    const std::string count = std::to_string(short_matrix.numbers) + " numbers, not 16";
    if (const pugi::xml_node geometry = first_geometry_instance(node)) {
      doc_.fail(short_matrix.element,
                count + "; a short <matrix> is read (missing numbers as 0, as the CS184 " +
                    "homework does) only above cameras and lights, and this node holds " +
                    describe(geometry) + " at line " + std::to_string(doc_.line_of(geometry)));
    }
    doc_.warn(short_matrix.element,
              count + "; the missing ones are read as 0, as the CS184 homework does");
  }

  // Visits of `node` (counting itself) and of the nodes it holds and instances, saturating
  // just above kMaxNodeVisits + 1.
  size_t count_visits(pugi::xml_node node, std::unordered_map<const void*, size_t>& counts,
                      int depth = 1) {
    const auto [entry, inserted] = counts.try_emplace(node.internal_object(), 1);
    if (!inserted || depth > kMaxNodeDepth) return entry->second;  // done, open (a cycle) or deep
    size_t total = 1;
    for (pugi::xml_node child = node.first_child(); child; child = child.next_sibling()) {
      const std::string_view name = child.name();
      pugi::xml_node target;
      if (name == "node") {
        target = child;
      } else if (name == "instance_node") {
        target = doc_.resolve(child, "url", "node");
      } else {
        continue;
      }
      total = std::min(total + count_visits(target, counts, depth + 1), kMaxNodeVisits + 2);
    }
    counts[node.internal_object()] = total;
    return total;
  }

  // An <instance_geometry> or <instance_node> (which may hold geometry) in `node` or the
  // <node>s nested in it; null when there is none.
  static pugi::xml_node first_geometry_instance(pugi::xml_node node) {
    std::vector<pugi::xml_node> stack{node};  // explicit: a deep file must not exhaust the stack
    while (!stack.empty()) {
      const pugi::xml_node current = stack.back();
      stack.pop_back();
      std::vector<pugi::xml_node> nested;
      for (pugi::xml_node child = current.first_child(); child; child = child.next_sibling()) {
        const std::string_view name = child.name();
        if (name == "instance_geometry" || name == "instance_node") return child;
        if (name == "node") nested.push_back(child);
      }
      stack.insert(stack.end(), nested.rbegin(), nested.rend());
    }
    return {};
  }

  const Geometry& geometry_for(pugi::xml_node element) {
    std::unique_ptr<Geometry>& slot = geometries_[element.hash_value()];
    if (!slot) slot = std::make_unique<Geometry>(parse_geometry(doc_, element));
    return *slot;
  }

  void add_geometry(pugi::xml_node instance, const DMat4& world, pugi::xml_node node) {
    const Geometry& geometry = geometry_for(doc_.resolve(instance, "url", "geometry"));
    // symbol -> target bindings; every target must resolve, used or not.
    std::vector<std::pair<std::string_view, pugi::xml_node>> bindings;
    const pugi::xml_node common = instance.child("bind_material").child("technique_common");
    for (pugi::xml_node bound : common.children("instance_material")) {
      if (!bound.attribute("symbol")) doc_.fail(bound, "missing attribute 'symbol'");
      bindings.emplace_back(bound.attribute("symbol").value(),
                            doc_.resolve(bound, "target", "material"));
    }
    if (geometry.is_sphere) {
      const DVec3 centre = transform_point(world, DVec3(0.0));
      if (!is_finite(Vec3(centre))) doc_.fail(instance, "sphere centre is not finite");
      // The homework places spheres at the node's origin and ignores its rotation and scale.
      scene_.geometry.spheres.push_back({Vec3(centre), geometry.radius,
                                         bindings.empty()
                                             ? materials_.default_index()
                                             : materials_.index_of(bindings[0].second)});
      return;
    }
    triangles_ += geometry.triangle_count();
    if (triangles_ > kMaxTriangles) {
      doc_.fail(instance, "the scene exceeds " + std::to_string(kMaxTriangles) +
                              " triangles after instancing");
    }
    std::vector<uint32_t> material_ids;
    for (const PrimitiveGroup& group : geometry.groups) {
      if (group.material_symbol.empty()) {
        material_ids.push_back(materials_.default_index());
        continue;
      }
      const auto it = std::find_if(bindings.begin(), bindings.end(),
                                   [&](const auto& b) { return b.first == group.material_symbol; });
      if (it == bindings.end()) {
        doc_.fail(instance, "no <instance_material> binds material symbol '" +
                                quote(group.material_symbol) + "' used by " +
                                describe(group.element) + " at line " +
                                std::to_string(doc_.line_of(group.element)));
      }
      material_ids.push_back(materials_.index_of(it->second));
    }
    const std::string node_name = node.attribute("id")     ? node.attribute("id").value()
                                  : node.attribute("name") ? node.attribute("name").value()
                                                           : "node";
    const size_t first = scene_.geometry.meshes.size();
    append_mesh_instance(geometry, world, material_ids, node_name + "/" + geometry.id,
                         scene_.geometry);
    for (size_t m = first; m < scene_.geometry.meshes.size(); ++m) {
      for (const Vec3& p : scene_.geometry.meshes[m].positions) {
        if (!is_finite(p)) doc_.fail(instance, "the node's transform makes vertices non-finite");
      }
    }
  }

  const Document& doc_;
  Scene& scene_;
  MaterialTable materials_;
  std::unordered_map<size_t, std::unique_ptr<Geometry>> geometries_;  // by xml_node hash
  std::vector<pugi::xml_node> path_;  // the nodes being visited, outermost first (cycles)
  size_t triangles_ = 0;
  pugi::xml_node camera_instance_;
  DMat4 camera_world_{1.0};
};

}  // namespace

Scene load_collada(const std::filesystem::path& path, const SceneLoadOptions& options) {
  const Document doc(path);
  Scene scene;
  scene.source = path.string();
  const DMat4 up_rotation = up_axis_rotation(doc);
  const pugi::xml_node scene_element = doc.root().child("scene");
  const pugi::xml_node instance = scene_element.child("instance_visual_scene");
  if (!instance) {
    doc.fail(scene_element ? scene_element : doc.root(),
             "missing <scene><instance_visual_scene>: the file names no visual scene");
  }
  const pugi::xml_node visual_scene = doc.resolve(instance, "url", "visual_scene");

  SceneBuilder builder(doc, scene);
  builder.check_visit_count(visual_scene);
  for (pugi::xml_node node : visual_scene.children("node")) builder.visit(node, up_rotation, 1);

  mark_duplicate_area_lights(scene.lights, scene.geometry, scene.materials);

  const Bounds3 bounds = scene.geometry.bounds();
  if (const pugi::xml_node camera = builder.camera_instance()) {
    const CameraOptics optics = parse_camera(doc, camera);
    scene.camera =
        options.literal_camera
            ? literal_camera(doc, camera, optics, builder.camera_world())
            : frame_homework(optics, bounds, homework_view_direction(builder.camera_world()));
  } else {
    // No camera in the file: the homework framing seen from the default (front) direction,
    // with the fields of view of Blender's default lens at the homework's 4:3.
    scene.camera = frame_homework(CameraOptics{}, bounds, kDefaultViewDirection);
  }
  // The homework renders its scenes at 480 x 360; the driver fits the fovs to the output size.
  scene.settings.width = 480;
  scene.settings.height = 360;
  scene.warnings = doc.warnings();
  return scene;
}

}  // namespace prism
