// prism's data as Python objects and NumPy arrays, and NumPy arrays as prism's inputs.

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <map>

#include "core/app/python_bindings.h"

namespace prism::python {
namespace {

std::string shape_text(const py::array& array) {
  std::string out = "(";
  for (py::ssize_t i = 0; i < array.ndim(); ++i) {
    out += (i ? ", " : "") + std::to_string(array.shape(i));
  }
  return out + (array.ndim() == 1 ? ",)" : ")");
}

/// `value` as a NumPy array of its own dtype, checked to be 2-D with `columns` columns and of a
/// dtype kind in `kinds`.
py::array checked_rows(const py::handle& value, const char* what, py::ssize_t columns,
                       const char* kinds, const char* kind_name) {
  py::array array = py::array::ensure(value);
  if (!array) {
    throw py::type_error(fmt::format("{} must be an array of {}", what, kind_name));
  }
  if (std::strchr(kinds, array.dtype().kind()) == nullptr) {
    throw py::type_error(fmt::format("{} must hold {}, got dtype {}", what, kind_name,
                                     std::string(py::str(array.dtype()))));
  }
  if (array.ndim() != 2 || array.shape(1) != columns) {
    throw py::value_error(
        fmt::format("{} must have shape (N, {}), got {}", what, columns, shape_text(array)));
  }
  return array;
}

/// The Python name of an image layer: the names prism's film gives them, in Python's words.
std::string layer_name(const std::string& prefix) {
  static const std::map<std::string, std::string> names = {{"albedo", "albedo"},
                                                           {"N", "normal"},
                                                           {"Z", "depth"},
                                                           {"sampleCount", "sample_count"},
                                                           {"variance", "variance"}};
  const auto it = names.find(prefix);
  return it == names.end() ? prefix : it->second;
}

/// The channels of one layer as an array of H x W (one channel) or H x W x C.
py::array_t<float> layer_array(const Image& image, const std::vector<int>& channels) {
  const py::ssize_t h = image.height, w = image.width, c = py::ssize_t(channels.size());
  py::array_t<float> array = c == 1 ? py::array_t<float>({h, w}) : py::array_t<float>({h, w, c});
  float* out = array.mutable_data();
  const int stride = image.channels();
  const size_t pixels = size_t(h) * size_t(w);
  for (size_t p = 0; p < pixels; ++p) {
    const float* in = image.pixels.data() + p * stride;
    for (py::ssize_t k = 0; k < c; ++k) out[p * c + k] = in[channels[k]];
  }
  return array;
}

}  // namespace

FloatArray float_rows(const py::handle& value, const char* what, py::ssize_t columns) {
  return FloatArray::ensure(checked_rows(value, what, columns, "fiu", "real numbers"));
}

IntArray integer_rows(const py::handle& value, const char* what, py::ssize_t columns) {
  return IntArray::ensure(checked_rows(value, what, columns, "iu", "integers"));
}

std::string param_text(const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  return py::str(value);
}

std::vector<std::string> set_assignments(const py::handle& set) {
  std::vector<std::string> out;
  if (set.is_none()) return out;
  if (py::isinstance<py::dict>(set)) {
    for (const auto& [key, value] : set.cast<py::dict>()) {
      out.push_back(std::string(py::str(key)) + "=" + param_text(value));
    }
    return out;
  }
  if (py::isinstance<py::str>(set) || !py::isinstance<py::sequence>(set)) {
    throw py::type_error("set must be a dict {key: value} or a list of 'key=value' strings");
  }
  for (const auto& item : set.cast<py::sequence>()) {
    if (!py::isinstance<py::str>(item)) {
      throw py::type_error("set must be a dict {key: value} or a list of 'key=value' strings");
    }
    out.push_back(item.cast<std::string>());
  }
  return out;
}

py::dict image_layers(const Image& image) {
  // Channels in film order, grouped by layer: "R", "G", "B" (and "A") are the beauty, "N.X" is
  // channel X of layer N, a name without a dot is a layer of its own.
  std::vector<int> beauty;
  std::vector<std::pair<std::string, std::vector<int>>> layers;
  for (int c = 0; c < image.channels(); ++c) {
    const std::string& name = image.channel_names[size_t(c)];
    if (name == "R" || name == "G" || name == "B" || name == "A") {
      beauty.push_back(c);
      continue;
    }
    const std::string prefix = name.substr(0, name.find('.'));
    auto it = std::find_if(layers.begin(), layers.end(),
                           [&](const auto& layer) { return layer.first == prefix; });
    if (it == layers.end()) {
      layers.push_back({prefix, {c}});
    } else {
      it->second.push_back(c);
    }
  }
  py::dict out;
  out["image"] = layer_array(image, beauty);
  py::dict aovs;
  for (const auto& [prefix, channels] : layers) {
    aovs[py::str(layer_name(prefix))] = layer_array(image, channels);
  }
  out["aovs"] = aovs;
  return out;
}

py::dict metadata_dict(const ImageMetadata& metadata) {
  py::dict out;
  for (const auto& [name, value] : metadata) out[py::str(name)] = py::str(value);
  return out;
}

py::tuple vec3_tuple(const Vec3& v) { return py::make_tuple(v.x, v.y, v.z); }

}  // namespace prism::python
