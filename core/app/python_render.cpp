// prism.render(): the options of `prism render` as keyword arguments, the image as NumPy arrays.

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>

#include "core/app/python_bindings.h"
#include "core/app/render_driver.h"

namespace prism::python {
namespace {

/// "prism.render('scene.json', spp=4)": how the render was asked for, for prism:command_line.
class CallText {
 public:
  explicit CallText(const std::optional<std::filesystem::path>& scene) {
    if (scene) text_ += std::string(py::repr(py::str(scene->string())));
  }
  template <typename T>
  void add(const char* name, const T& value) {
    add_object(name, py::cast(value));
  }
  template <typename T>
  void add(const char* name, const std::optional<T>& value) {
    if (value) add_object(name, py::cast(*value));
  }
  void add_object(const char* name, const py::handle& value) {
    if (value.is_none()) return;
    if (text_.size() > 0) text_ += ", ";
    text_ += std::string(name) + "=" + std::string(py::repr(value));
  }
  std::string str() const { return "prism.render(" + text_ + ")"; }

 private:
  std::string text_;
};

std::string path_text(const std::filesystem::path& path) { return path.string(); }

/// prism.render(): see its docstring below.
py::dict render(const std::optional<std::filesystem::path>& scene, const std::string& accel,
                const std::optional<std::string>& integrator, const std::string& sampler,
                const std::optional<int>& spp, const std::optional<std::pair<int, int>>& resolution,
                const py::object& seed, int threads, const py::object& set,
                const std::optional<int>& max_depth, const std::optional<int>& light_samples,
                bool hemisphere, const std::optional<std::pair<int, double>>& adaptive,
                const std::optional<std::array<int, 4>>& crop,
                const std::optional<std::pair<int, int>>& samples,
                const std::optional<int>& pass_samples, const std::optional<double>& time_limit,
                const std::optional<float>& lens_radius, const std::optional<float>& focal_distance,
                const std::optional<std::filesystem::path>& environment, bool literal_camera,
                const std::optional<std::string>& ocio_config,
                const std::optional<std::string>& working_space, bool quiet) {
  RenderOptions o;
  CallText call(scene);
  if (scene) o.scene = path_text(*scene);
  o.accelerator = accel;
  call.add("accel", accel);
  o.integrator = integrator;
  call.add("integrator", integrator);
  o.sampler = sampler;
  if (sampler != kDefaultSampler) call.add("sampler", sampler);
  o.spp = spp;
  call.add("spp", spp);
  o.resolution = resolution;
  call.add("resolution", resolution);
  if (!seed.is_none()) {
    if (!py::isinstance<py::int_>(seed) || py::isinstance<py::bool_>(seed)) {
      throw py::type_error("seed must be an int");
    }
    o.seed = std::string(py::str(seed));  // checked as --seed's text is
    call.add_object("seed", seed);
  }
  o.threads = threads;
  if (threads != 0) call.add("threads", threads);
  o.set = set_assignments(set);
  call.add_object("set", set);
  o.max_depth = max_depth;
  call.add("max_depth", max_depth);
  o.light_samples = light_samples;
  call.add("light_samples", light_samples);
  o.hemisphere_sampling = hemisphere;
  if (hemisphere) call.add("hemisphere", hemisphere);
  o.adaptive = adaptive;
  call.add("adaptive", adaptive);
  o.crop = crop;
  call.add("crop", crop);
  o.sample_range = samples;
  call.add("samples", samples);
  o.pass_samples = pass_samples;
  call.add("pass_samples", pass_samples);
  o.time_limit = time_limit;
  call.add("time_limit", time_limit);
  o.lens_radius = lens_radius;
  call.add("lens_radius", lens_radius);
  o.focal_distance = focal_distance;
  call.add("focal_distance", focal_distance);
  if (environment) {
    o.environment_map = path_text(*environment);
    call.add("environment", o.environment_map);
  }
  o.literal_camera = literal_camera;
  if (literal_camera) call.add("literal_camera", literal_camera);
  o.color.ocio_config = ocio_config.value_or("");
  call.add("ocio_config", ocio_config);
  o.color.working_space = working_space.value_or("");
  call.add("working_space", working_space);
  o.quiet = quiet;
  o.command_line = call.str();

  RenderedFrame frame;
  {
    py::gil_scoped_release release;
    // Between passes, on this thread: Ctrl-C (or another signal Python handles) stops the
    // render with Python's exception (KeyboardInterrupt).
    const auto check_signals = [] {
      py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    };
    frame = render_in_memory(o, check_signals);
  }
  py::dict out = image_layers(frame.image);
  out["provenance"] = metadata_dict(frame.metadata);
  const Image& image = frame.image;
  out["window"] = py::make_tuple(image.x, image.y, image.x + image.width, image.y + image.height);
  out["resolution"] = py::make_tuple(image.full_width ? image.full_width : image.width,
                                     image.full_height ? image.full_height : image.height);
  return out;
}

}  // namespace

void bind_render(py::module_& m) {
  m.def("render", &render, py::arg("scene") = py::none(), py::kw_only(),
        py::arg("accel") = kDefaultAccelerator, py::arg("integrator") = py::none(),
        py::arg("sampler") = kDefaultSampler, py::arg("spp") = py::none(),
        py::arg("resolution") = py::none(), py::arg("seed") = py::none(), py::arg("threads") = 0,
        py::arg("set") = py::none(), py::arg("max_depth") = py::none(),
        py::arg("light_samples") = py::none(), py::arg("hemisphere") = false,
        py::arg("adaptive") = py::none(), py::arg("crop") = py::none(),
        py::arg("samples") = py::none(), py::arg("pass_samples") = py::none(),
        py::arg("time_limit") = py::none(), py::arg("lens_radius") = py::none(),
        py::arg("focal_distance") = py::none(), py::arg("environment") = py::none(),
        py::arg("literal_camera") = false, py::arg("ocio_config") = py::none(),
        py::arg("working_space") = py::none(), py::arg("quiet") = true,
        R"(Renders `scene` (a .dae, .json, .obj or .ply path; None: the bundled Cornell box) as
`prism render` would, and returns the image in memory instead of writing files.

Keywords are the command line's options: accel (--accel), integrator, sampler, spp (-s),
resolution=(W, H) (-r), seed, threads (-t, 0: all), set (--set: a dict {"bvh.max_leaf_size": 4}
or a list of "key=value"), max_depth (-m), light_samples (-l), hemisphere (-H),
adaptive=(B, TOL) (-a), crop=(X0, Y0, X1, Y1), samples=(FIRST, LAST), pass_samples, time_limit
(seconds), lens_radius (-b), focal_distance (-d), environment (-e), literal_camera,
ocio_config, working_space; quiet=False shows the progress bar on stderr. Flags override the
scene file's settings, which override prism's defaults.

Returns a dict: "image" (H x W x 3 float32, the beauty in the working space, row 0 at the
top), "aovs" ({"albedo": H x W x 3, "normal": H x W x 3, "depth": H x W, "sample_count":
H x W, "variance": H x W x 3}), "provenance" (the prism:* attributes an EXR of the render
carries, as strings), "window" ((X0, Y0, X1, Y1): the pixels of the arrays in the image, the
crop) and "resolution" ((W, H) of the whole image). The pixels are those `prism render` writes
for the same options. The GIL is released while rendering; Ctrl-C stops the render between
passes with KeyboardInterrupt. Raises prism.Error with the command line's one-line message.)");
}

}  // namespace prism::python
