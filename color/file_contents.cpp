// The lookups of what the image and state file readers return (color/image_output.h,
// color/state_file.h). Apart from the readers, which the program loads at run time with the rest
// of color/'s OpenImageIO code (color/image_io.h).

#include <algorithm>
#include <string>

#include "color/image_output.h"
#include "color/state_file.h"

namespace prism {

std::string ImageFileContents::attribute(const std::string& name) const {
  for (const auto& [key, value] : attributes) {
    if (key == name) return value;
  }
  return {};
}

int ImageFileContents::channel(const std::string& name) const {
  const auto& names = image.channel_names;
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : int(it - names.begin());
}

std::string StateFileContents::attribute(const std::string& name) const {
  for (const auto& [key, value] : attributes) {
    if (key == name) return value;
  }
  return {};
}

}  // namespace prism
