#pragma once

// Where color/'s OpenImageIO code runs. Debian's OpenImageIO loads about 260 shared libraries
// (OpenVDB, GDAL, DCMTK, Poppler, ...), 0.4 s of start-up on the 2-core machines prism is
// measured on, so the `prism` program does not link it: the code of color/ that reads or writes
// image files (the EXR and display writers, the image and state file readers, the textures) is
// the module libprism_image_io.so beside the program, which loads it at the first call that
// reads or writes an image (image_io_loader.cpp). Commands that write no image (`info`, `list`,
// `bench`, `validate`, `--help`) start at once; a render pays the load when it writes, as it
// paid it at start-up before. Everything else (colour management, output plans) stays in the
// program. Tests and the Python module link the same code in (prism_image_files).
// docs/ARCHITECTURE.md, "Image module".

namespace prism {

/// Throws Error(kInternal) naming the module's path when the program loads the image module at
/// run time and its file is not there, without loading it; does nothing where the image code is
/// linked in. For commands that will read or write images: they fail before their work, not
/// after it. A module that is there but does not load is reported by the first call that needs
/// it, with the same error.
void check_image_io();

}  // namespace prism
