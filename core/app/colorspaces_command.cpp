// `prism colorspaces`: what the OpenColorIO config offers, for --working-space, --display, ...

#include <cstdio>

#include "color/color_pipeline.h"
#include "core/app/commands.h"
#include "core/error.h"

namespace prism {

int run_colorspaces_command(const std::string& ocio_config) {
  std::fputs(format_color_config(list_color_config(ocio_config)).c_str(), stdout);
  return kExitSuccess;
}

}  // namespace prism
