#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "color/color_pipeline.h"
#include "core/atomic_file.h"
#include "core/image.h"

// Image files one at a time: the atomic writers and the reader. A render plans and writes all
// its files through output_plan.h.

namespace prism {

/// EXR encoding choices (--exr-type, --exr-compression).
struct ExrOptions {
  std::string pixel_type = "half";  ///< half | float
  std::string compression = "zip";  ///< zip | piz | dwaa | none
};

/// Throws Error(kUsage) naming the bad value unless pixel_type is half|float and compression is
/// zip|piz|dwaa|none. write_exr and validate_outputs (output_plan.h) call it.
void validate_exr_options(const ExrOptions& options);
/// Whether validate_exr_options() accepts `options`.
bool exr_options_are_valid(const ExrOptions& options);

/// Provenance recorded in the file header, as (name, value) pairs ("prism:version", ...).
using ImageMetadata = std::vector<std::pair<std::string, std::string>>;

/// Writes `image` (working-space beauty R, G, B plus AOVs) as a scene-linear EXR in the
/// pipeline's output space, encoded as `options` says, with `metadata` and the colour
/// attributes; channel layout, half/float rules and attributes: docs/OUTPUT.md ("EXR output").
/// Atomic: a failure leaves any previous file untouched and no partial file. Throws
/// Error(kUsage) for bad `options`, Error(kOutput) naming the path when it cannot be written,
/// and Error(kInternal), writing nothing, for a NaN or Inf in the image.
void write_exr(const std::filesystem::path& path, const Image& image, const ImageMetadata& metadata,
               const ColorPipeline& pipeline, const ExrOptions& options = {});

/// Writes the beauty channels of `image` as a display-referred 8-bit file (PNG, JPEG or TIFF by
/// extension, see plan_image_file) through the pipeline's display/view/look/exposure. Same
/// atomicity and errors as write_exr; an extension that is not a display image's is
/// Error(kUsage).
void write_display_image(const std::filesystem::path& path, const Image& image,
                         const ImageMetadata& metadata, const ColorPipeline& pipeline);

/// Whether `path`'s extension is one write_display_image understands (.png, .jpg, .jpeg, .tif,
/// .tiff, any case); .exr is for write_exr.
bool is_display_image_path(const std::filesystem::path& path);

// check_output_writable(), which the writers use, is in core/atomic_file.h.

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

/// Most values (width x height x channels) read_image_file reads from one file: 2^28 floats,
/// 1 GiB, e.g. an 8192 x 8192 RGBA image.
inline constexpr uint64_t kMaxImageFileValues = uint64_t(1) << 28;

/// Reads an image file (environment maps, `prism convert`, tests) opened by open_image_file()
/// (color/image_reader.h: only OpenEXR, Radiance HDR, PFM/PNM, PNG, JPEG and TIFF, by their
/// first bytes). Throws Error(kInput) naming the path when the file cannot be read or its header
/// declares no pixels or more than kMaxImageFileValues values, or rows so wide that
/// OpenImageIO's read buffer (256 scanlines or a row of tiles) would pass 1 GiB; Error(kResource)
/// when the pixels do not fit in memory.
ImageFileContents read_image_file(const std::filesystem::path& path);

/// When `path` starts with the OpenEXR magic number: checks that its headers (every part's) are
/// whole, each attribute's name and type ending within 256 bytes and its value within the file
/// and of its type's size (channel lists and previews parsed; each channel of pixel type 0, 1
/// or 2 and sampled 1 x 1; at most 4 MiB a scanline), that each part has the attributes
/// every EXR has (channels, compression, dataWindow, displayWindow, lineOrder) and windows of at
/// most 2^20 pixels a side, before OpenEXR allocates what the header claims (OpenEXR 3.1 sizes a
/// string attribute by its stated length, up to 2 GB, whatever the file holds). Throws
/// Error(kInput) naming the path and the attribute. Other files pass unread.
void check_exr_header(const std::filesystem::path& path);

}  // namespace prism
