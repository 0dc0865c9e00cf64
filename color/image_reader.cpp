// Reading image files back through OpenImageIO (tests, comparisons, `prism convert`, environment
// maps).

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

#include "color/image_output.h"
#include "core/error.h"

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

void check_exr_header(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return;  // OpenImageIO says why it cannot read it
  in.seekg(0, std::ios::end);
  const std::streamoff file_size = in.tellg();
  in.seekg(0);
  unsigned char start[8] = {};
  if (!in.read(reinterpret_cast<char*>(start), 8)) return;
  if (start[0] != 0x76 || start[1] != 0x2f || start[2] != 0x31 || start[3] != 0x01) return;
  const bool multipart = (start[5] & 0x10) != 0;  // version flags, bit 12
  const auto bad = [&](const std::string& what) {
    return Error(ErrorKind::kInput, "not a valid OpenEXR file: " + what,
                 ErrorLocation{path.string(), 0, {}});
  };
  // A null-terminated name of at most 255 characters; empty at the end of a header.
  const auto read_name = [&](const char* what) {
    std::string name;
    for (char c; in.get(c);) {
      if (c == '\0') return name;
      if (name.size() == 255) throw bad(std::string(what) + " longer than 255 characters");
      name.push_back(c);
    }
    throw bad("the header ends early, in an attribute's " + std::string(what));
  };
  for (int part = 0;; ++part) {
    int attributes = 0;
    for (std::string name; !(name = read_name("name")).empty(); ++attributes) {
      const std::string type = read_name("type");
      unsigned char bytes[4];
      if (!in.read(reinterpret_cast<char*>(bytes), 4)) {
        throw bad("the header ends early, in the size of attribute '" + name + "'");
      }
      const int32_t size = int32_t(uint32_t(bytes[0]) | uint32_t(bytes[1]) << 8 |
                                   uint32_t(bytes[2]) << 16 | uint32_t(bytes[3]) << 24);
      const std::streamoff left = file_size - std::streamoff(in.tellg());
      if (size < 0 || size > left) {
        throw bad("attribute '" + name + "' (" + type + ") claims " + std::to_string(size) +
                  " bytes, the file has " + std::to_string(left) + " left");
      }
      in.seekg(size, std::ios::cur);
    }
    // A single-part file has one header; a multipart file's list ends with an empty header.
    if (!multipart || attributes == 0) return;
  }
}

ImageFileContents read_image_file(const std::filesystem::path& path) {
  check_exr_header(path);
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) {
    throw Error(ErrorKind::kInput, "cannot read the image: " + OIIO::geterror(),
                ErrorLocation{path.string(), 0, {}});
  }
  const OIIO::ImageSpec& spec = in->spec();
  ImageFileContents contents;
  contents.format = in->format_name();
  contents.image.width = spec.width;
  contents.image.height = spec.height;
  contents.image.x = spec.x;
  contents.image.y = spec.y;
  contents.image.full_width = spec.full_width;
  contents.image.full_height = spec.full_height;
  contents.image.channel_names = spec.channelnames;
  contents.image.pixels.resize(size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT,
                      contents.image.pixels.data())) {
    throw Error(ErrorKind::kInput, "cannot read the pixels: " + in->geterror(),
                ErrorLocation{path.string(), 0, {}});
  }
  for (int c = 0; c < spec.nchannels; ++c) {
    contents.channel_formats.push_back(spec.channelformat(c).c_str());
  }
  contents.compression = spec.get_string_attribute("compression");
  if (const auto* chroma =
          spec.find_attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8))) {
    std::array<float, 8> values{};
    std::memcpy(values.data(), chroma->data(), sizeof(values));
    contents.chromaticities = values;
  }
  for (const auto& p : spec.extra_attribs) {
    contents.attributes.emplace_back(p.name().string(), p.get_string());
  }
  return contents;
}

}  // namespace prism
