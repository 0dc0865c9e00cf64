// The image module's entry point (color/image_io.h): built into libprism_image_io.so only, with
// color/'s OpenImageIO code, and exported as its only symbol (color/image_io_module.map).

#include "color/image_io_functions.h"

extern "C" const prism::ImageIoFunctions* prism_image_io_functions() {
  using namespace prism;
  static const ImageIoFunctions table = [] {
    ImageIoFunctions t;
    t.write_exr_file = &color_detail::write_exr_file;
    t.write_display_file = &color_detail::write_display_file;
    t.write_display_image = &write_display_image;
    t.read_image_file = &read_image_file;
    t.write_state_file = &write_state_file;
    t.read_state_file = &read_state_file;
    t.read_state_file_attributes = &read_state_file_attributes;
    t.load_scene_textures = &load_scene_textures;
    return t;
  }();
  return &table;
}
