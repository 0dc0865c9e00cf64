// The Python module `prism`: the renderer, scene loading and the accelerators of the command line
// for NumPy users (README "Python"). Its failures are Python exceptions carrying the one line
// `prism` prints after "prism: error: ".

#include <algorithm>
#include <string>

#include "accel/accelerator.h"
#include "core/app/python_bindings.h"
#include "core/error.h"
#include "integrators/integrator.h"

namespace prism::python {
namespace {

const char* kind_name(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::kUsage:
      return "usage";
    case ErrorKind::kInput:
      return "input";
    case ErrorKind::kOutput:
      return "output";
    case ErrorKind::kResource:
      return "resource";
    case ErrorKind::kInternal:
      return "internal";
  }
  return "internal";
}

/// prism.Error(message) with the attributes of `e`, raised.
void raise_error(const py::object& type, const Error& e) {
  std::string line = e.what();
  std::replace(line.begin(), line.end(), '\n', ' ');  // one line, as main() prints it
  py::object error = type(line);
  error.attr("kind") = kind_name(e.kind());
  error.attr("exit_code") = e.exit_code();
  error.attr("file") = e.location().file;
  error.attr("line") = e.location().line;
  error.attr("element") = e.location().element;
  error.attr("detail") = e.message();
  PyErr_SetObject(type.ptr(), error.ptr());
}

}  // namespace
}  // namespace prism::python

PYBIND11_MODULE(prism, m) {
  namespace py = pybind11;
  using namespace prism::python;
  m.doc() =
      "prism, a CPU path tracer: render scenes into NumPy arrays, load scenes, and query its "
      "ray-tracing accelerators (bvh, embree, brute) with arrays of rays. See README.md, "
      "\"Python\".";
  m.attr("__version__") = PRISM_VERSION;

  // Created once and kept for the life of the process, as pybind11 recommends for exception types.
  static py::exception<prism::Error> error_type(m, "Error", PyExc_RuntimeError);
  error_type.doc() =
      "A failure prism reports: str(e) is the one line `prism` prints after 'prism: error: '. "
      "Attributes: kind ('usage', 'input', 'output', 'resource' or 'internal'), exit_code (the "
      "command line's: 2, 3 or 1), file, line, element (where; empty or 0 when unknown) and "
      "detail (the message without its location).";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const prism::Error& e) {
      raise_error(error_type, e);
    }
  });

  m.def(
      "accelerators", [] { return prism::accelerator_registry().names(); },
      "The names of the accelerators, as `prism list` shows them: brute, bvh, embree.");
  m.def(
      "integrators", [] { return prism::integrator_registry().names(); },
      "The names of the integrators, as `prism list` shows them.");

  bind_render(m);
  bind_scene(m);
  bind_accelerator(m);
}
