#pragma once

#include <string>
#include <vector>

#include "core/app/render_options.h"

namespace prism {

/// `prism render`: loads, builds, renders and writes the files RenderOptions asks for; prints a
/// summary line on stdout. Returns the exit code; throws prism::Error on failure, before any
/// file is written when the failure is in the input or options.
int run_render_command(const RenderOptions& options);

/// What `prism info` reports on.
struct InfoOptions {
  std::string scene;
  std::vector<std::string> accelerators;  ///< empty: every registered accelerator
  std::vector<std::string> set;           ///< --set key=value
  int threads = 0;
  bool literal_camera = false;
};

/// `prism info`: the scene's contents, camera and settings, then build statistics of each
/// accelerator, on stdout. Throws prism::Error on bad input.
int run_info_command(const InfoOptions& options);

/// `prism list`: every registry's names with descriptions, on stdout.
int run_list_command();

/// `prism colorspaces`: what the OpenColorIO config (`ocio_config`, empty: the default) offers.
int run_colorspaces_command(const std::string& ocio_config);

/// What `prism convert` reads and writes.
struct ConvertOptions {
  std::string input;        ///< an EXR (its beauty R, G, B; AOV layers are ignored)
  std::string output;       ///< .png, .jpg/.jpeg or .tif/.tiff
  std::string input_space;  ///< empty: the EXR's prism:colorSpace, else scene_linear
  ColorOptions color;       ///< --ocio-config, --display, --view, --look, --exposure
};

/// `prism convert`: a display-referred image of an existing EXR through an OCIO display/view,
/// written atomically; prints a summary line on stdout. Throws prism::Error before writing
/// anything when a name, the input or the output folder is bad.
int run_convert_command(const ConvertOptions& options);

}  // namespace prism
