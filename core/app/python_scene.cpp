// prism.load_scene() and prism.info(): what `prism info` prints, as dicts.

#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/app/commands.h"
#include "core/app/python_bindings.h"
#include "core/app/scene_summary.h"
#include "scenes/scene_loader.h"

namespace prism::python {
namespace {

template <typename T>
py::object optional_value(const std::optional<T>& value) {
  return value ? py::cast(*value) : py::none();
}

py::dict count_dict(const CountByName& counts) {
  py::dict out;
  for (const auto& [name, count] : counts.counts) out[py::str(name)] = count;
  return out;
}

py::dict summary_dict(const SceneSummary& s) {
  py::dict out;
  out["source"] = s.source;
  out["triangles"] = s.triangles;
  out["meshes"] = s.meshes;
  out["spheres"] = s.spheres;
  out["emissive_meshes"] = s.emissive_meshes;
  out["lights"] = count_dict(s.lights);
  out["materials"] = count_dict(s.materials);
  out["textures"] = py::cast(s.textures);
  out["bounds"] =
      s.bounds.empty()
          ? py::object(py::none())
          : py::object(py::make_tuple(vec3_tuple(s.bounds.lower), vec3_tuple(s.bounds.upper)));
  const Camera& c = s.camera;
  py::dict camera;
  camera["position"] = vec3_tuple(c.position);
  camera["target"] = vec3_tuple(c.target);
  camera["up"] = vec3_tuple(c.up);
  camera["hfov_deg"] = c.hfov_deg;
  camera["vfov_deg"] = c.vfov_deg;
  camera["lens_radius"] = c.lens_radius;
  camera["focal_distance"] = c.focal_distance;
  out["camera"] = camera;
  const SceneRenderSettings& r = s.settings;
  py::dict settings;
  settings["resolution"] = r.width && r.height ? py::object(py::make_tuple(*r.width, *r.height))
                                               : py::object(py::none());
  settings["spp"] = optional_value(r.spp);
  settings["max_depth"] = optional_value(r.max_depth);
  settings["integrator"] = optional_value(r.integrator);
  settings["seed"] = optional_value(r.seed);
  out["settings"] = settings;
  return out;
}

/// The meshes (vertices N x 3 float32, indices M x 3 uint32, material name) and the spheres
/// (S x 4 float32: centre, radius) of a scene, copied.
py::dict geometry_dict(const Scene& scene) {
  py::list meshes;
  for (const TriangleMesh& mesh : scene.geometry.meshes) {
    const py::ssize_t n = py::ssize_t(mesh.positions.size());
    const py::ssize_t m = py::ssize_t(mesh.triangles.size());
    py::array_t<float> vertices({n, py::ssize_t(3)});
    py::array_t<uint32_t> indices({m, py::ssize_t(3)});
    std::memcpy(vertices.mutable_data(), mesh.positions.data(), size_t(n) * 3 * sizeof(float));
    std::memcpy(indices.mutable_data(), mesh.triangles.data(), size_t(m) * 3 * sizeof(uint32_t));
    py::dict entry;
    entry["name"] = mesh.name;
    entry["vertices"] = vertices;
    entry["indices"] = indices;
    entry["material"] = mesh.material_id < scene.materials.size()
                            ? scene.materials[mesh.material_id].name
                            : std::string();
    meshes.append(entry);
  }
  const py::ssize_t count = py::ssize_t(scene.geometry.spheres.size());
  py::array_t<float> spheres({count, py::ssize_t(4)});
  float* out = spheres.mutable_data();
  for (const Sphere& s : scene.geometry.spheres) {
    *out++ = s.center.x;
    *out++ = s.center.y;
    *out++ = s.center.z;
    *out++ = s.radius;
  }
  py::dict geometry;
  geometry["meshes"] = meshes;
  geometry["spheres"] = spheres;
  return geometry;
}

py::dict stats_dict(const AccelStats& stats, size_t primitives) {
  py::dict out;
  out["build_ms"] = stats.build_ms;
  out["nodes"] = stats.nodes;
  out["leaves"] = stats.leaves;
  out["max_depth"] = stats.max_depth;
  out["bytes"] = stats.bytes;
  out["bytes_per_primitive"] = primitives ? double(stats.bytes) / double(primitives) : 0.0;
  out["sah_cost"] = stats.sah_cost;
  return out;
}

/// None, one name, or a list of names.
std::vector<std::string> accelerator_names(const py::handle& accel) {
  if (accel.is_none()) return {};
  if (py::isinstance<py::str>(accel)) return {accel.cast<std::string>()};
  return accel.cast<std::vector<std::string>>();
}

}  // namespace

void bind_scene(py::module_& m) {
  m.def(
      "load_scene",
      [](const std::filesystem::path& path, bool literal_camera) {
        Scene scene;
        {
          py::gil_scoped_release release;
          scene = load_scene(path, SceneLoadOptions{.literal_camera = literal_camera});
        }
        py::dict out = summary_dict(summarize_scene(scene));
        out["geometry"] = geometry_dict(scene);
        return out;
      },
      py::arg("path"), py::kw_only(), py::arg("literal_camera") = false,
      R"(Loads a scene file (.dae, .json, .obj, .ply) as `prism render` does and returns what
`prism info` prints about it, as a dict: "source", "triangles", "meshes", "spheres",
"emissive_meshes" (counts), "lights" and "materials" ({type: count}), "textures" (names), "bounds" (((x, y, z),
(x, y, z)), or None without geometry), "camera" (position, target, up, hfov_deg, vfov_deg,
lens_radius, focal_distance) and "settings" (the file's resolution, spp, max_depth,
integrator, seed; None where it gives none); plus "geometry": {"meshes": [{"name",
"vertices" (N x 3 float32), "indices" (M x 3 uint32), "material"}], "spheres" (S x 4 float32:
centre, radius)}, in world space, ready for prism.Accelerator.)");

  m.def(
      "info",
      [](const std::filesystem::path& path, const py::object& accel, const py::object& set,
         int threads, bool literal_camera) {
        InfoOptions options;
        options.scene = path.string();
        options.accelerators = accelerator_names(accel);
        options.set = set_assignments(set);
        options.threads = threads;
        options.literal_camera = literal_camera;
        InfoReport report;
        {
          py::gil_scoped_release release;
          report = collect_info(options);
        }
        py::dict out = summary_dict(report.scene);
        out["threads"] = report.threads;
        py::dict accelerators;
        for (const auto& [name, stats] : report.accelerators) {
          accelerators[py::str(name)] = stats_dict(stats, report.primitives);
        }
        out["accelerators"] = accelerators;
        return out;
      },
      py::arg("path"), py::kw_only(), py::arg("accel") = py::none(), py::arg("set") = py::none(),
      py::arg("threads") = 0, py::arg("literal_camera") = false,
      R"(`prism info` as a dict: what load_scene() returns without "geometry", plus "threads"
(the builds ran on) and "accelerators": {name: {"build_ms", "nodes", "leaves", "max_depth",
"bytes", "bytes_per_primitive", "sah_cost"}} for each accelerator built over the scene, in
turn. accel: a name or a list of names (None: every accelerator); set: --set parameters (a
dict or a list of "key=value"); threads: 0 for all.)");
}

}  // namespace prism::python
