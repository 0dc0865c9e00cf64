#pragma once

// The table of functions the image module (color/image_io.h) hands the program: the entry
// points of color/'s OpenImageIO code that the rest of prism calls. The program's forwarders of
// the same names (image_io_loader.cpp) call through it. Internal to color/.

#include <cstddef>

#include "color/image_file_writers.h"
#include "color/image_output.h"
#include "color/state_file.h"
#include "color/texture_set.h"

namespace prism {

/// Changes whenever ImageIoFunctions does: a module from another build is refused.
inline constexpr int kImageIoFunctionsVersion = 1;

/// The types of the functions in the table, named before the members that share their names.
namespace image_io_types {
using WriteExrFile = decltype(&color_detail::write_exr_file);
using WriteDisplayFile = decltype(&color_detail::write_display_file);
using WriteDisplayImage = decltype(&write_display_image);
using ReadImageFile = decltype(&read_image_file);
using WriteStateFile = decltype(&write_state_file);
using ReadStateFile = decltype(&read_state_file);
using ReadStateFileAttributes = decltype(&read_state_file_attributes);
using LoadSceneTextures = decltype(&load_scene_textures);
}  // namespace image_io_types

struct ImageIoFunctions {
  int version = kImageIoFunctionsVersion;
  size_t size = sizeof(ImageIoFunctions);
  image_io_types::WriteExrFile write_exr_file = nullptr;
  image_io_types::WriteDisplayFile write_display_file = nullptr;
  image_io_types::WriteDisplayImage write_display_image = nullptr;
  image_io_types::ReadImageFile read_image_file = nullptr;
  image_io_types::WriteStateFile write_state_file = nullptr;
  image_io_types::ReadStateFile read_state_file = nullptr;
  image_io_types::ReadStateFileAttributes read_state_file_attributes = nullptr;
  image_io_types::LoadSceneTextures load_scene_textures = nullptr;
};

}  // namespace prism

/// The module's one exported symbol: its table, valid while the module stays loaded (it is
/// never unloaded).
extern "C" const prism::ImageIoFunctions* prism_image_io_functions();

/// The name the program looks the table up by (dlsym).
inline constexpr const char* kImageIoFunctionsSymbol = "prism_image_io_functions";
