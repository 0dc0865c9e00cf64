#pragma once

// Internal to color/: loading an OpenColorIO config and looking names up in it. Only color/*.cpp
// include this header (it brings in OpenColorIO).

#include <OpenColorIO/OpenColorIO.h>

#include <optional>
#include <string>
#include <vector>

#include "core/math.h"

namespace prism::color_detail {

namespace OCIO = OCIO_NAMESPACE;

/// A loaded config and where it came from.
struct LoadedConfig {
  OCIO::ConstConfigRcPtr config;
  std::string source;  ///< file path, or "bundled"
  std::string hash;    ///< "sha1:<hex>" of the config file's bytes
};

/// Loads `ocio_config` if non-empty, else the file named by $OCIO if set and non-empty, else the
/// bundled config. A missing file is Error(kUsage) naming the option or variable; a config that
/// does not parse or validate is Error(kInput) naming the file.
LoadedConfig load_config(const std::string& ocio_config);

/// "a, b, c" (or "(none)" for an empty list).
std::string join_names(const std::vector<std::string>& names);

/// Active colour spaces (scene- and display-referred), in config order.
std::vector<std::string> color_space_names(const OCIO::Config& config);
std::vector<std::string> display_names(const OCIO::Config& config);
std::vector<std::string> view_names(const OCIO::Config& config, const std::string& display);
std::vector<std::string> look_names(const OCIO::Config& config);
std::vector<std::string> role_names(const OCIO::Config& config);

/// The canonical colour-space name for a name, alias or role. Throws Error(kUsage) "unknown
/// colour space 'X' (<what>); available: ..." otherwise.
std::string resolve_color_space(const OCIO::Config& config, const std::string& name,
                                const std::string& what);

/// Checks a look string ("a, +b, -c") against the config's looks; Error(kUsage) lists them.
void check_looks(const OCIO::Config& config, const std::string& looks);

/// The 3x3 matrix of a processor when it is linear (checked on a few colours, relative error
/// 1e-4), else nothing. Column j is the image of the j-th unit colour.
std::optional<glm::dmat3> linear_matrix(const OCIO::ConstCPUProcessorRcPtr& processor);

/// Applies `processor` in place to the RGB triples at `channels` of an interleaved float image.
void apply_rgb(const OCIO::ConstCPUProcessorRcPtr& processor, float* pixels, size_t pixel_count,
               int channel_count, const int channels[3]);

/// A colour space of the config that holds linear Rec.709 (D65) values: found by the usual
/// names and aliases, else by comparing each scene-linear space against the published
/// Rec.709-to-ACES2065-1 matrix through the aces_interchange role. Nothing when none matches.
std::optional<std::string> find_linear_rec709(const OCIO::ConstConfigRcPtr& config);

/// CIE xy chromaticities (Rx Ry Gx Gy Bx By Wx Wy) of a linear scene-referred colour space; see
/// ColorPipeline::output_chromaticities.
std::optional<std::array<float, 8>> derive_chromaticities(const OCIO::ConstConfigRcPtr& config,
                                                          const std::string& space);

}  // namespace prism::color_detail
