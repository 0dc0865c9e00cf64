#pragma once

#include <string>
#include <vector>

#include "core/film.h"
#include "core/render_schedule.h"

namespace prism {

/// What `prism merge` reads and writes.
struct MergeOptions {
  std::vector<std::string> parts;  ///< part files (EXR state files of render --crop/--samples)
  std::string output;              ///< -f: the merged image, or a larger part (then an EXR)
  bool png = false;                ///< also write <output stem>.png
  bool quiet = false;              ///< no progress output
  std::string command_line;        ///< for provenance metadata
};

/// `prism merge`: adds up the exact film sums of parts of one frame (crops, sample ranges, or
/// both, in any order) and writes the image through the same path as a render when they make up
/// the whole frame (bit for bit the single render's), else a part again that can be merged
/// further. Checks, before reading any part's pixels, that the output can be written, that the
/// parts belong to one render (identity, resolution, spp) and that they tile a box of (pixel,
/// sample) space exactly (check_part_coverage()); then that each part is complete. Prints a
/// summary line on stdout. Throws Error(kInput) naming the file (exit 2) for a part that does not
/// fit, Error(kUsage) for a partial result into a non-EXR file, Error(kOutput) when the output
/// cannot be written; nothing is written on any error.
int run_merge_command(const MergeOptions& options);

/// Where one part of a frame lies in (pixel, sample) space: the pixels `window` times the sample
/// indices `samples` of each.
struct PartExtent {
  std::string file;  ///< named in errors
  PixelRect window;
  SampleRange samples;
};

/// The box of (pixel, sample) space the parts make up together.
struct PartsCoverage {
  PixelRect window;
  SampleRange samples;
};

/// Checks that `parts` (at least one, each non-empty, inside an image of at most kMaxFilmSide
/// pixels a side) cover every (pixel, sample) of their bounding box exactly once, and returns
/// that box. Exact, in integers: any two parts are compared for an overlap (Error(kInput) naming
/// the later file, the earlier one and the pixels and samples in both); disjoint parts leave no
/// gap exactly when their volumes add up to the box's. A gap is Error(kInput) naming a box of
/// pixels and samples in no part, found on the grid the parts' edges make. Cost: n^2 box
/// comparisons; on a gap, a search of the grid's cells (each against every part) up to the first
/// empty one.
PartsCoverage check_part_coverage(const std::vector<PartExtent>& parts);

/// "x in [X0, X1), y in [Y0, Y1)" and ", samples [FIRST, LAST)": how merge names pixels and
/// samples in messages.
std::string describe_extent(const PixelRect& window, SampleRange samples);

}  // namespace prism
