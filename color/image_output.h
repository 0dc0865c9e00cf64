#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "color/color_pipeline.h"
#include "core/image.h"

namespace prism {

/// EXR encoding choices (--exr-type, --exr-compression).
struct ExrOptions {
  std::string pixel_type = "half";  ///< half | float
  std::string compression = "zip";  ///< zip | piz | dwaa | none
};

/// Provenance recorded in the file header, as (name, value) pairs ("prism:version", ...).
using ImageMetadata = std::vector<std::pair<std::string, std::string>>;

/// Writes `image` (working-space beauty R, G, B plus AOV channels) as a scene-linear EXR in the
/// pipeline's output space, with chromaticities, oiio:ColorSpace and `metadata`. Writes to a
/// temporary file in the same folder and renames it on success, so a failure leaves any
/// previous file untouched and no partial file. Throws Error(kOutput) naming the path.
void write_exr(const std::filesystem::path& path, const Image& image, const ImageMetadata& metadata,
               const ColorPipeline& pipeline, const ExrOptions& options = {});

/// Writes the beauty channels of `image` as a display-referred 8-bit file (PNG, JPEG or TIFF by
/// extension) through the pipeline's display/view/look/exposure. Same atomicity and errors as
/// write_exr.
void write_display_image(const std::filesystem::path& path, const Image& image,
                         const ImageMetadata& metadata, const ColorPipeline& pipeline);

/// Whether `path`'s extension is one write_display_image understands (.png, .jpg, .jpeg, .tif,
/// .tiff); .exr is for write_exr.
bool is_display_image_path(const std::filesystem::path& path);

/// Throws Error(kOutput) naming the folder when `path` cannot be created there (missing folder,
/// no permission). Called before rendering so a long render does not fail at the end.
void check_output_writable(const std::filesystem::path& path);

}  // namespace prism
