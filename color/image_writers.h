#pragma once

// What the image writers of color/ share (internal to color/): the atomic write, the checks and
// the header attributes every file carries, and the writers that output plans call once the
// plan is validated (declared in image_file_writers.h). Other code uses image_output.h and
// output_plan.h.

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "color/color_pipeline.h"
#include "color/image_file_writers.h"
#include "color/image_output.h"
#include "core/error.h"
#include "core/image.h"

namespace prism::color_detail {

/// Error(kOutput) with `message`, located at `path`.
Error output_error(const std::filesystem::path& path, const std::string& message);

/// Writes interleaved `pixels` of `type` with OpenImageIO's writer for `format` to a hidden
/// temporary file beside `target`, flushes it to disk and renames it over `target`, so a failure
/// leaves any previous file untouched and no partial file. Throws Error(kOutput) naming `target`.
void write_atomically(const std::filesystem::path& target, const std::string& format,
                      const OIIO::ImageSpec& spec, const OIIO::TypeDesc& type, const void* pixels);

/// One image of a multi-image file: its header and interleaved pixels of `type`.
struct Subimage {
  OIIO::ImageSpec spec;
  OIIO::TypeDesc type;
  const void* pixels;
};
/// write_atomically() for a file of several images (a multi-part OpenEXR file), in order.
void write_atomically(const std::filesystem::path& target, const std::string& format,
                      const std::vector<Subimage>& subimages);

/// The header and float pixels of the scene-linear EXR of `image`, as write_exr writes it.
struct ExrImage {
  OIIO::ImageSpec spec;
  /// The interleaved pixels, in the file's channel order: `pixels` when the file's differ from
  /// the image's (reordered, converted to the output space or clamped to the half range), else
  /// the image's own, which must then outlive this.
  const float* data = nullptr;
  ImagePixels pixels;  ///< huge pages, as the image's own (core/huge_page_allocator.h)
};
ExrImage prepare_exr(const std::filesystem::path& path, const Image& image,
                     const ImageMetadata& metadata, const ColorPipeline& pipeline,
                     const ExrOptions& options);

/// Throws Error(kInternal) naming `path` when `values` holds a NaN or Inf: the film drops them,
/// so one here is a bug to report, not a value to patch.
void check_finite(std::span<const float> values, const std::filesystem::path& path);

/// Adds `metadata` (provenance) and the pipeline's config, working space, display, view and look
/// (prism:ocioConfig, ...) to the header.
void add_header_attributes(OIIO::ImageSpec& spec, const ImageMetadata& metadata,
                           const ColorPipeline& pipeline);

}  // namespace prism::color_detail
