// check_image_io() where color/'s OpenImageIO code is linked in (prism_image_files: the
// tests, the fuzz targets and the Python module): nothing to check (color/image_io.h).

#include "color/image_io.h"

namespace prism {

void check_image_io() {}

}  // namespace prism
