#pragma once

#include <filesystem>
#include <string>

#include "color/color_pipeline.h"
#include "color/image_output.h"
#include "core/film.h"

namespace prism {

/// A render's state as a file: the checkpoint of a render to resume, or a part (--crop,
/// --samples) to merge. An OpenEXR file of two images:
/// 1. the render's image as write_exr writes `image` (any EXR viewer shows it), with `metadata`;
/// 2. "prism.state": every pixel's FilmPixel over the same data window, as FilmPixel::kWords
///    32-bit unsigned channels state.00, state.01, ... (little-endian words of the struct),
///    with prism:stateVersion (2), prism:stateChecksum (hex64 of fnv1a64_words() of the words,
///    RLE-compressed) and
///    prism:nonFiniteSamples.
/// Written atomically like every output. Throws as write_exr.
void write_state_file(const std::filesystem::path& path, const Image& image, const Film& film,
                      const ImageMetadata& metadata, const ColorPipeline& pipeline,
                      const ExrOptions& options);

/// What read_state_file() found.
struct StateFileContents {
  Film film;
  ImageMetadata attributes;  ///< of the first image: the metadata given to write_state_file
  /// Value of an attribute of the first image as text, or "" when absent.
  std::string attribute(const std::string& name) const;
};

/// Reads a file write_state_file() wrote, checking everything a damaged or foreign file could
/// get wrong: an EXR with a second image "prism.state" of state version 1, FilmPixel::kWords
/// unsigned channels, sizes within prism's limits, a data window inside the display window, the
/// checksum of the words. Throws Error(kInput) naming the file and what is wrong.
StateFileContents read_state_file(const std::filesystem::path& path);

/// The attributes of a state file's first image (StateFileContents::attributes) without reading
/// any pixel: for a quick look at many large files before reading them. Checks what
/// read_state_file() checks before the state's pixels (an OpenEXR file whose second image is
/// "prism.state"); throws Error(kInput) naming the file.
ImageMetadata read_state_file_attributes(const std::filesystem::path& path);

}  // namespace prism
