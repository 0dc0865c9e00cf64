// The lookups of what the image and state file readers return (color/image_output.h,
// color/state_file.h). Apart from the readers, which the program loads at run time with the rest
// of color/'s OpenImageIO code (color/image_io.h).

#include <algorithm>
#include <string>

#include "color/image_output.h"
#include "color/state_file.h"

namespace prism {
namespace {

/// The value of the header attribute `name` in `attributes`, or "" when absent.
std::string attribute_in(const ImageMetadata& attributes, const std::string& name) {
  for (const auto& [key, value] : attributes) {
    if (key == name) return value;
  }
  return {};
}

}  // namespace

std::string ImageFileContents::attribute(const std::string& name) const {
  return attribute_in(attributes, name);
}

int ImageFileContents::channel(const std::string& name) const {
  const auto& names = image.channel_names;
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : int(it - names.begin());
}

std::string StateFileContents::attribute(const std::string& name) const {
  return attribute_in(attributes, name);
}

}  // namespace prism
