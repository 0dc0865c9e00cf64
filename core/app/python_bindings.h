#pragma once

// The Python module `prism` (README "Python"): python_module.cpp defines it and its exception,
// python_render.cpp prism.render(), python_scene.cpp prism.load_scene() and prism.info(),
// python_accelerator.cpp prism.Accelerator; python_convert.cpp turns prism's data into Python
// objects and NumPy arrays and back. Only the module's files include this header (and pybind11).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <string>
#include <vector>

#include "color/image_output.h"
#include "core/image.h"
#include "core/math.h"

namespace prism::python {

namespace py = pybind11;

void bind_render(py::module_& m);
void bind_scene(py::module_& m);
void bind_accelerator(py::module_& m);

/// C-contiguous NumPy arrays of float32 and int64, converted from other dtypes on the way in.
using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;
using IntArray = py::array_t<int64_t, py::array::c_style | py::array::forcecast>;

/// A float32 array of shape (n, columns) from any NumPy-convertible value of real numbers
/// (float64 values are rounded to float32). Throws ValueError naming `what` and the expected
/// shape when the value is not a 2-D array of that width, TypeError when its values are not
/// numbers.
FloatArray float_rows(const py::handle& value, const char* what, py::ssize_t columns);

/// The same for integers, as int64 (TypeError for any other dtype).
IntArray integer_rows(const py::handle& value, const char* what, py::ssize_t columns);

/// `value` as the text of a --set assignment: True/False as true/false, other values as str().
std::string param_text(const py::handle& value);

/// --set assignments ("key=value") from None, a dict {key: value} or a sequence of "key=value"
/// strings. Throws TypeError for anything else.
std::vector<std::string> set_assignments(const py::handle& set);

/// The layers of `image` as NumPy arrays (float32, copied, row 0 at the top): "image", the
/// beauty (H x W x 3, or x 4 with A), and "aovs", a dict of the other layers by name ("albedo",
/// "normal", "depth", "sample_count", "variance", others by their channel prefix); a layer of
/// one channel is H x W, of several H x W x C.
py::dict image_layers(const Image& image);

/// The attributes as a dict of strings, in order.
py::dict metadata_dict(const ImageMetadata& metadata);

/// (x, y, z).
py::tuple vec3_tuple(const Vec3& v);

}  // namespace prism::python
