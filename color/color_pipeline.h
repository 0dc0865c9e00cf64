#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <utility>
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
/// How configs are chosen and studio configs ($OCIO) are used: README.md, "Colour".
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
  /// the output space, in place, and likewise every colour AOV ("albedo.R/G/B", see
  /// is_color_layer); other channels (AOVs that are data) are left alone.
  void working_to_output(Image& image) const;
  /// Whether working_to_output() changes any value (false when the output space is the working
  /// space).
  bool converts_to_output() const;
  /// Converts the beauty and every colour AOV of an image (as working_to_output selects them)
  /// from the colour space `from` (name, alias or role) to the working space, in place; data
  /// channels are left alone. For images read back from files (`prism convert`). Throws
  /// Error(kUsage) listing the colour spaces when `from` is unknown.
  void convert_image_to_working(Image& image, const std::string& from) const;
  /// Display-referred 8-bit-ready values in [0,1]: the beauty channels through exposure, look,
  /// display and view. Returns an RGB image.
  Image working_to_display(const Image& image) const;

  /// The canonical name of the colour space that `name` (a name, alias or role, as OCIO
  /// matches them) denotes in the active config, or nothing when the config has none by that
  /// name. For names read from files, which may come from another config.
  std::optional<std::string> find_color_space(const std::string& name) const;
  /// Converts one colour between two colour spaces (names, aliases or roles) of the config.
  /// Throws Error(kUsage) listing the colour spaces when a name is unknown.
  Rgb convert(const Rgb& color, const std::string& from, const std::string& to) const;
  /// One working-space colour through exposure, look, display and view (not clamped).
  Rgb working_to_display(const Rgb& color) const;
  /// CIE xy of the output space's red, green, blue primaries and white point (OpenEXR order
  /// Rx Ry Gx Gy Bx By Wx Wy), derived from the config through its aces_interchange (else a
  /// scene-referred cie_xyz_d65_interchange) role; nothing when the config offers neither or the
  /// output space is not linear. Published values replace derived ones within 1e-3.
  std::optional<std::array<float, 8>> output_chromaticities() const;
  /// Name of the display's colour space the view ends in (e.g. "sRGB - Display").
  std::string display_color_space() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

/// Lists of what the active config offers, for `prism colorspaces` and error messages.
struct ColorConfigListing {
  std::string config_source;
  std::vector<std::string> color_spaces, displays, looks, roles;
  std::vector<std::pair<std::string, std::vector<std::string>>> views;  ///< per display
  std::string config_name;                                              ///< the config's `name:`
  std::string default_display;                                          ///< empty when none
  std::vector<std::pair<std::string, std::string>> role_spaces;         ///< (role, colour space)
};
/// Loads the config chosen as ColorOptions::ocio_config would be (`ocio_config`, else $OCIO,
/// else the bundled config) and lists it. Throws Error(kUsage/kInput) when it cannot be loaded.
ColorConfigListing list_color_config(const std::string& ocio_config);
/// The listing as the text `prism colorspaces` prints.
std::string format_color_config(const ColorConfigListing& listing);

/// Text of the bundled config (color/ocio/config.ocio), compiled into the program so an installed
/// binary needs no source tree.
const std::string& bundled_color_config_text();

/// Whether an AOV layer holds colour that follows the beauty through colour conversions
/// ("" for the beauty itself, "albedo", "diffuse", "specular", "emission", ...). Data layers
/// (N, Z, P, depth, sampleCount, variance, ...) are never colour-converted.
bool is_color_layer(const std::string& layer);
/// Indices of every (R, G, B) channel triple of a colour layer of `image`: the beauty first
/// ("R", "G", "B"), then "<layer>.R/G/B" of each colour layer in channel order.
std::vector<std::array<int, 3>> color_channel_triples(const Image& image);

}  // namespace prism
