#pragma once

// The writers an output plan calls once it is validated (internal to color/: output_plan.cpp).
// Declared apart from image_writers.h, which needs OpenImageIO's headers, because the plan is
// made and checked in the program itself and the writers run in the image module the program
// loads at run time (color/image_io.h).

#include <filesystem>
#include <string>

#include "color/color_pipeline.h"
#include "color/image_output.h"
#include "core/image.h"

namespace prism::color_detail {

/// write_exr without its checks: `options` is valid and the path was checked writable (an
/// output plan validated both).
void write_exr_file(const std::filesystem::path& path, const Image& image,
                    const ImageMetadata& metadata, const ColorPipeline& pipeline,
                    const ExrOptions& options);

/// write_display_image without its checks: `format` ("png", "jpeg" or "tiff") comes from the
/// output plan, whose validation checked the path writable.
void write_display_file(const std::filesystem::path& path, const std::string& format,
                        const Image& image, const ImageMetadata& metadata,
                        const ColorPipeline& pipeline);

}  // namespace prism::color_detail
