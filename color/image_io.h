#pragma once

#include <memory>

// Where color/'s OpenImageIO code runs. Debian's OpenImageIO loads about 260 shared libraries
// (OpenVDB, GDAL, DCMTK, Poppler, ...), 0.4 s of start-up on the 2-core machines prism is
// measured on, so the `prism` program does not link it: the code of color/ that reads or writes
// image files (the EXR and display writers, the image and state file readers, the textures) is
// the module libprism_image_io.so beside the program, which loads it at the first call that
// reads or writes an image (image_io_loader.cpp). Commands that write no image (`info`, `list`,
// `bench`, `validate`, `--help`) start at once; a render loads it beside its first samples
// (ImageIoPreload). Everything else (colour management, output plans) stays in the
// program. Tests and the Python module link the same code in (prism_image_files).
// docs/ARCHITECTURE.md, "Image module".

namespace prism {

/// Throws Error(kInternal) naming the module's path when the program loads the image module at
/// run time and its file is not there, without loading it; does nothing where the image code is
/// linked in. For commands that will read or write images: they fail before their work, not
/// after it. A module that is there but does not load is reported by the first call that needs
/// it, with the same error.
void check_image_io();

/// While it lives, loads the image module on a thread of the parallel loops (run_beside()),
/// where the program loads the module at run time and `threads` (the render's thread limit) is
/// at least 2: a render then loads it beside its first samples, on one of its own threads,
/// instead of on its own before or after them. Does nothing otherwise, in particular where the
/// image code is linked in. A module that does not load is reported by the first call that needs
/// it, as without a preload. The destructor waits for a load under way and cancels one not yet
/// started, so that no load is left running when the command ends.
class ImageIoPreload {
 public:
  explicit ImageIoPreload(int threads);
  ~ImageIoPreload();
  ImageIoPreload(const ImageIoPreload&) = delete;
  ImageIoPreload& operator=(const ImageIoPreload&) = delete;

 private:
  struct State;
  std::shared_ptr<State> state_;
};

}  // namespace prism
