// Reading image files back through OpenImageIO (tests, comparisons, `prism convert`, environment
// maps).

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <new>
#include <string>
#include <string_view>
#include <vector>

#include "color/image_output.h"
#include "color/image_reader.h"
#include "core/error.h"

namespace prism {

namespace {
/// The largest side of an EXR prism reads: far above any film (kMaxFilmSide) or environment map.
constexpr int64_t kMaxExrSide = int64_t(1) << 20;

/// The most OpenImageIO may allocate for one read of rows: 256 rows of a 16384-wide image of 64
/// float channels.
constexpr uint64_t kMaxImageReadBytes = uint64_t(1) << 30;

/// The most bytes of one EXR scanline, all channels: a 16384-wide film of 64 float channels.
constexpr uint64_t kMaxExrScanlineBytes = uint64_t(4) << 20;

/// The sizes of OpenEXR's fixed-size attribute types.
const std::map<std::string, int32_t> kFixedSizes = {
    {"box2i", 16},
    {"box2f", 16},
    {"chromaticities", 32},
    {"compression", 1},
    {"deepImageState", 1},
    {"double", 8},
    {"envmap", 1},
    {"float", 4},
    {"int", 4},
    {"keycode", 28},
    {"lineOrder", 1},
    {"m33d", 72},
    {"m33f", 36},
    {"m44d", 128},
    {"m44f", 64},
    {"rational", 8},
    {"tiledesc", 9},
    {"timecode", 8},
    {"v2d", 16},
    {"v2f", 8},
    {"v2i", 8},
    {"v3d", 24},
    {"v3f", 12},
    {"v3i", 12},
};
}  // namespace

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
    std::vector<std::string> required = {"channels", "compression", "dataWindow", "displayWindow",
                                         "lineOrder"};
    int64_t data_width = 0;    // of dataWindow
    uint64_t pixel_bytes = 0;  // of all channels
    for (std::string name; !(name = read_name("name")).empty(); ++attributes) {
      std::erase(required, name);
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
      // OpenEXR reads a fixed-size type's own size whatever the header says: a different size
      // would put it elsewhere in the file than this walk.
      const auto fixed = kFixedSizes.find(type);
      if (fixed != kFixedSizes.end() && size != fixed->second) {
        throw bad("attribute '" + name + "' (" + type + ") has " + std::to_string(size) +
                  " bytes, not " + std::to_string(fixed->second));
      }
      std::string value(size_t(size), '\0');
      in.read(value.data(), size);
      const auto u32 = [&](size_t at) {
        return uint32_t(uint8_t(value[at])) | uint32_t(uint8_t(value[at + 1])) << 8 |
               uint32_t(uint8_t(value[at + 2])) << 16 | uint32_t(uint8_t(value[at + 3])) << 24;
      };
      if (type == "box2i" && (name == "dataWindow" || name == "displayWindow")) {
        // OpenEXR sizes its tables by the windows before it reads a pixel.
        const int64_t width = int64_t(int32_t(u32(8))) - int32_t(u32(0)) + 1;
        const int64_t height = int64_t(int32_t(u32(12))) - int32_t(u32(4)) + 1;
        if (width < 1 || height < 1 || width > kMaxExrSide || height > kMaxExrSide) {
          throw bad(name + " of " + std::to_string(width) + " x " + std::to_string(height) +
                    " pixels (at most " + std::to_string(kMaxExrSide) + " a side)");
        }
        if (name == "dataWindow") data_width = width;
      } else if (type == "chlist") {
        // Channels: a name, 16 bytes (type, linear, reserved, sampling), ...; an empty name last.
        // OpenImageIO aborts on a pixel type it does not know (fuzzing found it). prism writes
        // and reads channels sampled 1 x 1 only.
        size_t at = 0;
        for (;;) {
          const size_t end = value.find('\0', at);
          if (end == std::string::npos || (end > at && end + 17 > value.size())) {
            throw bad("attribute '" + name + "' (chlist) is cut");
          }
          if (end == at) break;
          const std::string channel = value.substr(at, end - at);
          const uint32_t pixel_type = u32(end + 1);  // 0 uint, 1 half, 2 float
          const auto x_sampling = int32_t(u32(end + 9));
          const auto y_sampling = int32_t(u32(end + 13));
          if (pixel_type > 2) {
            throw bad("channel '" + channel + "' has pixel type " + std::to_string(pixel_type) +
                      " (0 uint, 1 half and 2 float are the types OpenEXR defines)");
          }
          if (x_sampling != 1 || y_sampling != 1) {
            throw bad("channel '" + channel + "' is sampled " + std::to_string(x_sampling) + " x " +
                      std::to_string(y_sampling) + " (prism reads channels sampled 1 x 1 only)");
          }
          pixel_bytes += pixel_type == 1 ? 2 : 4;
          at = end + 1 + 16;
        }
        if (at + 1 != value.size()) {
          throw bad("attribute '" + name + "' (chlist) does not fill its " + std::to_string(size) +
                    " bytes");
        }
      } else if (type == "preview") {
        // Width, height, then 4 bytes a pixel, allocated from the two numbers.
        if (size < 8 || 8 + 4 * uint64_t(u32(0)) * u32(4) != uint64_t(size)) {
          throw bad("attribute '" + name + "' (preview) does not hold its pixels");
        }
      }
    }
    // OpenEXR allocates its line buffers from the width and the channels before reading a
    // pixel: a part 524290 pixels wide with 48 channels had it map 13 GB (fuzzing merge).
    if (uint64_t(data_width) * pixel_bytes > kMaxExrScanlineBytes) {
      throw bad("part " + std::to_string(part) + " has scanlines of " + std::to_string(data_width) +
                " pixels x " + std::to_string(pixel_bytes) + " bytes, more than the " +
                std::to_string(kMaxExrScanlineBytes) + " bytes a scanline prism reads");
    }
    if (attributes > 0 && !required.empty()) {
      throw bad("part " + std::to_string(part) + " has no '" + required.front() + "' attribute");
    }
    // A single-part file has one header; a multipart file's list ends with an empty header.
    if (!multipart || attributes == 0) return;
  }
}

namespace {
/// OpenImageIO's reader for a file that starts with `start`, or "" for none prism reads. Only
/// formats that hold radiance or a texture are read: fewer readers, fewer third-party bugs
/// within reach (an exception inside OpenImageIO 2.4's GIF reader, on a 24-byte file, ends the
/// process in std::terminate, past any handler: fuzzing environment_map).
std::string format_by_magic(const std::string& start) {
  const auto starts_with = [&](std::string_view magic, size_t at = 0) {
    return start.size() >= at + magic.size() && start.compare(at, magic.size(), magic) == 0;
  };
  using namespace std::string_view_literals;
  if (starts_with("\x76\x2f\x31\x01"sv)) return "openexr";
  if (starts_with("\x89PNG"sv)) return "png";
  if (starts_with("#?"sv)) return "hdr";  // #?RADIANCE, #?RGBE
  if (start.size() >= 3 && start[0] == 'P' && std::strchr("123456Ff", start[1]) != nullptr &&
      std::isspace(static_cast<unsigned char>(start[2]))) {
    return "pnm";  // PNM and PFM
  }
  if (starts_with("\xff\xd8\xff"sv)) return "jpeg";
  if (starts_with("II*\0"sv) || starts_with("MM\0*"sv)) return "tiff";
  return "";
}

/// Walks a PNG's chunks: each must fit in what is left of the file. libpng allocates a chunk's
/// stated length before reading it (a 330-byte file whose tEXt chunk claims 1.8 GB: fuzzing
/// environment_map). Throws Error(kInput) naming the chunk.
void check_png_chunks(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  in.seekg(0, std::ios::end);
  const std::streamoff file_size = in.tellg();
  for (std::streamoff at = 8; at < file_size;) {
    in.seekg(at);
    unsigned char header[8];
    if (!in.read(reinterpret_cast<char*>(header), 8)) return;  // libpng says it is cut
    const uint64_t length = uint64_t(header[0]) << 24 | uint64_t(header[1]) << 16 |
                            uint64_t(header[2]) << 8 | uint64_t(header[3]);
    const std::string type(reinterpret_cast<const char*>(header + 4), 4);
    const uint64_t left = uint64_t(file_size - at - 8);
    if (length + 4 > left) {
      std::string printable = type;
      for (char& c : printable) {
        if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
      }
      throw Error(ErrorKind::kInput,
                  "not a valid PNG file: chunk '" + printable + "' at byte " + std::to_string(at) +
                      " claims " + std::to_string(length) + " bytes, the file has " +
                      std::to_string(left) + " left",
                  ErrorLocation{path.string(), 0, {}});
    }
    if (type == "IEND") return;
    at += std::streamoff(8 + length + 4);
  }
}

}  // namespace

// OpenImageIO's own open() would, when the reader for the extension fails, try every reader it
// has (its DICOM reader loads a dictionary of several MB: seconds, found by fuzzing
// environment_map); a file is read as what its first bytes say it is.
std::unique_ptr<OIIO::ImageInput> open_image_file(const std::filesystem::path& path,
                                                  ImageFormats formats) {
  const ErrorLocation where{path.string(), 0, {}};
  std::string start(12, '\0');
  {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw Error(ErrorKind::kInput, "cannot open the image for reading", where);
    file.read(start.data(), std::streamsize(start.size()));
    start.resize(size_t(file.gcount()));
  }
  const std::string format = format_by_magic(start);
  if (formats == ImageFormats::kOpenExrOnly && format != "openexr") {
    throw Error(ErrorKind::kInput, "not an OpenEXR file", where);
  }
  if (format.empty()) {
    throw Error(ErrorKind::kInput,
                "cannot read the image: not a format prism reads (by its first bytes: OpenEXR, "
                "Radiance HDR, PFM or PNM, PNG, JPEG or TIFF)",
                where);
  }
  // Headers that make the readers allocate what they claim are checked first.
  if (format == "openexr") check_exr_header(path);
  if (format == "png") check_png_chunks(path);
  auto in = OIIO::ImageInput::create(format);
  if (!in) {
    throw Error(ErrorKind::kInput,
                "cannot read the image: OpenImageIO has no " + format + " reader here (" +
                    OIIO::geterror() + ")",
                where);
  }
  OIIO::ImageSpec spec;
  if (!in->open(path.string(), spec)) {
    throw Error(ErrorKind::kInput, "cannot read the image (" + format + "): " + in->geterror(),
                where);
  }
  return in;
}

ImageFileContents read_image_file(const std::filesystem::path& path) {
  const std::unique_ptr<OIIO::ImageInput> in = open_image_file(path);
  const OIIO::ImageSpec& spec = in->spec();
  const ErrorLocation where{path.string(), 0, {}};
  // The header's sizes are checked before anything is allocated: a file may declare any size
  // (a negative one, or 100000 x 100000 in a few bytes).
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth != 1) {
    throw Error(ErrorKind::kInput,
                "the header declares " + std::to_string(spec.width) + " x " +
                    std::to_string(spec.height) + " pixels of " + std::to_string(spec.nchannels) +
                    " channels: not an image",
                where);
  }
  const uint64_t values = uint64_t(spec.width) * uint64_t(spec.height) * uint64_t(spec.nchannels);
  if (values > kMaxImageFileValues) {
    throw Error(ErrorKind::kInput,
                "the header declares " + std::to_string(spec.width) + " x " +
                    std::to_string(spec.height) + " pixels of " + std::to_string(spec.nchannels) +
                    " channels, more than the " + std::to_string(kMaxImageFileValues) +
                    " values prism reads from one image",
                where);
  }
  // OpenImageIO reads a scanline file through a buffer of at least 256 of its rows and a tiled
  // one a row of tiles at a time, whatever the image's height: a 55555555 x 1 image asks it for
  // 170 GB (fuzzing found it). The buffer is bounded before it is asked for.
  const uint64_t rows_per_read = spec.tile_width > 0 ? uint64_t(spec.tile_height) : 256;
  const uint64_t row_pixels = spec.tile_width > 0
                                  ? (uint64_t(spec.width) + uint64_t(spec.tile_width) - 1) /
                                        uint64_t(spec.tile_width) * uint64_t(spec.tile_width)
                                  : uint64_t(spec.width);
  const uint64_t read_bytes = rows_per_read * row_pixels * uint64_t(spec.pixel_bytes(true));
  if (spec.tile_height > kMaxExrSide || spec.tile_width > kMaxExrSide ||
      read_bytes > kMaxImageReadBytes) {
    throw Error(ErrorKind::kInput,
                "the header declares " + std::to_string(spec.width) + " x " +
                    std::to_string(spec.height) + " pixels of " + std::to_string(spec.nchannels) +
                    " channels in " +
                    (spec.tile_width > 0 ? std::to_string(spec.tile_width) + " x " +
                                               std::to_string(spec.tile_height) + " tiles"
                                         : std::string("scanlines")) +
                    ": reading it would take buffers of " + std::to_string(read_bytes) +
                    " bytes, more than the " + std::to_string(kMaxImageReadBytes) +
                    " prism allows (rows too wide)",
                where);
  }
  ImageFileContents contents;
  contents.format = in->format_name();
  contents.image.width = spec.width;
  contents.image.height = spec.height;
  contents.image.x = spec.x;
  contents.image.y = spec.y;
  contents.image.full_width = spec.full_width;
  contents.image.full_height = spec.full_height;
  contents.image.channel_names = spec.channelnames;
  try {
    contents.image.pixels.resize(size_t(values));
  } catch (const std::bad_alloc&) {
    throw Error(ErrorKind::kResource,
                "out of memory for the " + std::to_string(spec.width) + " x " +
                    std::to_string(spec.height) + " pixels of the image",
                where);
  }
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
