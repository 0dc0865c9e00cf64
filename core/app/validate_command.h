#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace prism {

/// What `prism validate` checks.
struct ValidateOptions {
  /// Scene file or generated mesh (see load_scene_or_generated()); may be empty with --replay,
  /// whose file names its scene.
  std::string scene;
  size_t rays = 100000;            ///< rays per set (P, S, D1, D2, R and feature rays F)
  std::string accel = "bvh";       ///< --accel
  std::string against = "embree";  ///< --against
  /// Whether --accel / --against were given: with --replay they win over the file's backends.
  bool accel_given = false;
  bool against_given = false;
  std::vector<std::string> set;                    ///< --set key=value for both backends
  std::string replay;                              ///< re-run the rays of a failures file instead
  std::string failures = "validate_failures.txt";  ///< where non-matching rays are written
  std::string heatmap = "validate_heatmap.png";    ///< where they fall on the image
  int threads = 0;
};

/// `prism validate`: traces every ray set through both backends and sorts each disagreement,
/// with the double-precision oracle, into hard mismatch, tie or ambiguous (rounding-decided):
/// backends sharing the primitive tests and tie rule (bvh, brute) must match exactly, others
/// follow the DESIGN tolerance rule. Writes every non-matching ray to a replay file and a PNG
/// heatmap of where they fall on the image (red hard, yellow ambiguous, blue tie; camera-ray
/// descendants at their pixel, feature rays where the camera sees their target, random rays
/// not at all). With
/// --replay, re-runs the rays of such a file. Returns 0 only when no hard mismatch is found,
/// else 1; throws prism::Error on bad options or input.
int run_validate_command(const ValidateOptions& options);

}  // namespace prism
