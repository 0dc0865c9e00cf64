// Checking the EXR encoding options (--exr-type, --exr-compression) before anything is rendered.
// Apart from the writer (color/exr_writer.cpp), which the program loads at run time with the rest
// of color/'s OpenImageIO code (color/image_io.h): a render checks its options first.

#include <string>

#include "color/image_output.h"
#include "core/error.h"

namespace prism {
namespace {

bool is_valid_pixel_type(const std::string& type) { return type == "half" || type == "float"; }

bool is_valid_compression(const std::string& compression) {
  return compression == "zip" || compression == "piz" || compression == "dwaa" ||
         compression == "none";
}

}  // namespace

bool exr_options_are_valid(const ExrOptions& options) {
  return is_valid_pixel_type(options.pixel_type) && is_valid_compression(options.compression);
}

void validate_exr_options(const ExrOptions& options) {
  if (!is_valid_pixel_type(options.pixel_type)) {
    throw Error(ErrorKind::kUsage,
                "unknown EXR pixel type '" + options.pixel_type + "'; available: half, float");
  }
  if (!is_valid_compression(options.compression)) {
    throw Error(ErrorKind::kUsage, "unknown EXR compression '" + options.compression +
                                       "'; available: zip, piz, dwaa, none");
  }
}

}  // namespace prism
