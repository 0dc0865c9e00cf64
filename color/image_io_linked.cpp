// check_image_io() and ImageIoPreload where color/'s OpenImageIO code is linked in
// (prism_image_files: the tests, the fuzz targets and the Python module): nothing to check or
// load (color/image_io.h).

#include "color/image_io.h"

namespace prism {

void check_image_io() {}

struct ImageIoPreload::State {};

ImageIoPreload::ImageIoPreload(int) {}

ImageIoPreload::~ImageIoPreload() = default;

}  // namespace prism
