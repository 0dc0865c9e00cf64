#pragma once

#include <string>
#include <utility>
#include <vector>

#include "accel/accelerator.h"
#include "core/app/render_options.h"
#include "core/app/scene_summary.h"

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

/// What `prism info` reports: the scene's summary, then each accelerator's build statistics.
struct InfoReport {
  SceneSummary scene;
  size_t primitives = 0;  ///< triangles and spheres
  int threads = 0;        ///< the builds ran on this many threads
  std::vector<std::pair<std::string, AccelStats>> accelerators;  ///< in the order asked for
  std::vector<std::string> warnings;  ///< what the loader tolerated (Scene::warnings)
};

/// Collects what `prism info` prints: checks the options and creates every accelerator (an
/// unknown name or --set key fails before the scene loads), loads the scene and builds each
/// accelerator over it in turn. Throws prism::Error on bad input. prism.info() returns it.
InfoReport collect_info(const InfoOptions& options);

/// `prism info`: collect_info() on stdout, the scene's contents, camera and settings, then the
/// build statistics of each accelerator. Throws prism::Error on bad input.
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
