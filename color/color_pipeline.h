#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/math.h"
#include "core/scene.h"

namespace prism {

/// User choices for colour management (command line: --ocio-config, --working-space, ...).
/// Empty strings mean "the default" described on each field.
struct ColorOptions {
  std::string ocio_config;    ///< config file; empty: $OCIO, else the bundled config
  std::string working_space;  ///< rendering space; empty: the config's scene_linear role
  std::string output_space;   ///< EXR space; empty: the config's scene_linear role
  std::string display;        ///< display for PNG/JPEG/TIFF; empty: the config's default
  std::string view;           ///< view of that display; empty: the display's default view
  std::string look;           ///< optional look applied with the view
  float exposure = 0.0f;      ///< stops, applied before the view for display-referred files
};

/// The active OpenColorIO configuration and the processors prism needs from it. Every colour
/// conversion in prism goes through this class. Construction validates every name and throws
/// Error(kUsage) listing what the config offers; after that, methods are thread-safe.
class ColorPipeline {
 public:
  explicit ColorPipeline(const ColorOptions& options);
  ~ColorPipeline();
  ColorPipeline(const ColorPipeline&) = delete;
  ColorPipeline& operator=(const ColorPipeline&) = delete;

  /// Converts every colour of the scene (materials, lights), authored in `scene_space`
  /// (CS184 and prism JSON scenes: linear Rec.709), into the working space, in place.
  void convert_scene_to_working(Scene& scene, const std::string& scene_space) const;

  /// Name of the colour space scene files are authored in (linear Rec.709 in this config).
  std::string scene_file_space() const;
  std::string working_space() const;
  std::string output_space() const;
  std::string display() const;
  std::string view() const;
  std::string look() const;
  float exposure() const;
  /// The config's name and a hash of its content, for provenance metadata.
  std::string config_name() const;
  std::string config_hash() const;
  /// Path of the config file in use, or "bundled".
  std::string config_source() const;

  /// Converts the RGB(A) beauty channels of an image (named R, G, B) from the working space to
  /// the output space, in place; other channels (AOVs that are data) are left alone.
  void working_to_output(Image& image) const;
  /// Display-referred 8-bit-ready values in [0,1]: the beauty channels through exposure, look,
  /// display and view. Returns an RGB image.
  Image working_to_display(const Image& image) const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

/// Lists of what the active config offers, for `prism colorspaces` and error messages.
struct ColorConfigListing {
  std::string config_source;
  std::vector<std::string> color_spaces, displays, looks, roles;
  std::vector<std::pair<std::string, std::vector<std::string>>> views;  ///< per display
};
ColorConfigListing list_color_config(const std::string& ocio_config);

}  // namespace prism
