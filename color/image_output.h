#pragma once

#include <array>
#include <filesystem>
#include <optional>
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

/// Throws Error(kUsage) naming the bad value unless pixel_type is half|float and compression is
/// zip|piz|dwaa|none. write_exr calls it; the driver may call it before rendering.
void validate_exr_options(const ExrOptions& options);

/// Provenance recorded in the file header, as (name, value) pairs ("prism:version", ...).
using ImageMetadata = std::vector<std::pair<std::string, std::string>>;

/// Writes `image` (working-space beauty R, G, B plus AOV channels) as a scene-linear EXR in the
/// pipeline's output space, with chromaticities, oiio:ColorSpace and `metadata`. Writes to a
/// temporary file in the same folder and renames it on success, so a failure leaves any
/// previous file untouched and no partial file. Throws Error(kOutput) naming the path.
///
/// Layout: R, G, B, A (A = 1 unless the image has an "A" channel), then every other channel
/// under its own name (albedo.R, N.X, Z, sampleCount.Y, variance.R, ...). Colour layers (see
/// is_color_layer) are converted to the output space like the beauty; data layers are written
/// as they are. With half pixels, Z/depth/P/position/sampleCount/id layers stay float (half
/// cannot hold depths or counts above 2048 exactly) and values of half channels beyond the
/// half range are clamped to +-65504, counted in the attribute "prism:halfClampedValues".
/// Added attributes: prism:colorSpace (output space; OpenImageIO does not store
/// oiio:ColorSpace in EXR headers), prism:workingSpace, prism:ocioConfig,
/// prism:ocioConfigHash (sha1 of the config file), prism:ocioConfigSource (its path or
/// "bundled"), prism:display, prism:view, prism:look. A NaN or Inf in the image is an internal
/// error (Error(kInternal)): the film drops them, so one here is a bug, and nothing is written.
void write_exr(const std::filesystem::path& path, const Image& image, const ImageMetadata& metadata,
               const ColorPipeline& pipeline, const ExrOptions& options = {});

/// Writes the beauty channels of `image` as a display-referred 8-bit file (PNG, JPEG or TIFF by
/// extension) through the pipeline's display/view/look/exposure. Same atomicity and errors as
/// write_exr; an unknown extension is Error(kUsage).
void write_display_image(const std::filesystem::path& path, const Image& image,
                         const ImageMetadata& metadata, const ColorPipeline& pipeline);

/// Whether `path`'s extension is one write_display_image understands (.png, .jpg, .jpeg, .tif,
/// .tiff); .exr is for write_exr.
bool is_display_image_path(const std::filesystem::path& path);

/// Throws Error(kOutput) naming the folder when `path` cannot be created there (missing folder,
/// no permission). Called before rendering so a long render does not fail at the end.
void check_output_writable(const std::filesystem::path& path);

/// An image file read back through OpenImageIO.
struct ImageFileContents {
  Image image;                               ///< every channel as float, file channel order
  std::string format;                        ///< "openexr", "png", "jpeg", "tiff"
  std::vector<std::string> channel_formats;  ///< per channel: "half", "float", "uint8", ...
  std::string compression;                   ///< "" when the format has none
  std::optional<std::array<float, 8>> chromaticities;
  ImageMetadata attributes;  ///< every header attribute, as text

  /// Value of a header attribute as text, or "" when absent.
  std::string attribute(const std::string& name) const;
  /// Index of a channel by name, or -1.
  int channel(const std::string& name) const;
};

/// Reads an image file (for tests and comparisons). Throws Error(kInput) naming the path.
ImageFileContents read_image_file(const std::filesystem::path& path);

}  // namespace prism
