#pragma once

// Opening image files for reading (internal to color/: read_image_file() and the state files).
// Other code uses image_output.h.

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <memory>

namespace prism {

/// Which formats open_image_file() accepts.
enum class ImageFormats {
  kAny,          ///< every format it reads
  kOpenExrOnly,  ///< OpenEXR; other bytes are "not an OpenEXR file" (the state files)
};

/// Opens an image file with the one OpenImageIO reader its first bytes name (OpenEXR, Radiance
/// HDR, PFM/PNM, PNG, JPEG, TIFF; only OpenEXR with kOpenExrOnly), after check_exr_header() for
/// an OpenEXR file and a check that a PNG's chunks fit in the file; no other reader is tried when
/// that one fails. Throws Error(kInput) naming the path for other bytes or when the reader cannot
/// open it.
std::unique_ptr<OIIO::ImageInput> open_image_file(const std::filesystem::path& path,
                                                  ImageFormats formats = ImageFormats::kAny);

}  // namespace prism
