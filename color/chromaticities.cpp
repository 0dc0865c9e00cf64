// Colorimetry the config does not state directly: which colour space holds linear Rec.709, and
// the CIE xy primaries of an output space (for the EXR `chromaticities` attribute). Both are
// derived from the config's own transforms to its interchange roles, so studio configs work.

#include <cmath>

#include "color/ocio_config.h"

namespace prism::color_detail {
namespace {

using Chromaticities = std::array<double, 8>;  // Rx Ry Gx Gy Bx By Wx Wy

// Published primaries and whites (ITU-R BT.709, BT.2020, SMPTE EG 432-1, SMPTE ST 2065-1,
// S-2014-004, CIE 1931 XYZ).
constexpr Chromaticities kRec709{0.64, 0.33, 0.30, 0.60, 0.15, 0.06, 0.3127, 0.3290};
constexpr Chromaticities kRec2020{0.708, 0.292, 0.170, 0.797, 0.131, 0.046, 0.3127, 0.3290};
constexpr Chromaticities kP3D65{0.680, 0.320, 0.265, 0.690, 0.150, 0.060, 0.3127, 0.3290};
constexpr Chromaticities kAp0{0.7347, 0.2653, 0.0, 1.0, 0.0001, -0.0770, 0.32168, 0.33767};
constexpr Chromaticities kAp1{0.713, 0.293, 0.165, 0.830, 0.128, 0.044, 0.32168, 0.33767};
constexpr Chromaticities kXyz{1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0 / 3.0, 1.0 / 3.0};
constexpr Chromaticities kKnown[] = {kRec709, kRec2020, kP3D65, kAp0, kAp1, kXyz};

glm::dvec3 xy_to_xyz(double x, double y) { return {x / y, 1.0, (1.0 - x - y) / y}; }

// RGB-to-XYZ matrix of a set of primaries and white (SMPTE RP 177).
glm::dmat3 rgb_to_xyz(const Chromaticities& c) {
  const glm::dmat3 p(xy_to_xyz(c[0], c[1]), xy_to_xyz(c[2], c[3]), xy_to_xyz(c[4], c[5]));
  const glm::dvec3 s = glm::inverse(p) * xy_to_xyz(c[6], c[7]);
  return glm::dmat3(p[0] * s.x, p[1] * s.y, p[2] * s.z);
}

// Bradford chromatic adaptation between two whites, in XYZ.
glm::dmat3 bradford(double wx0, double wy0, double wx1, double wy1) {
  // Rows of the Bradford cone-response matrix, stored column-major for glm.
  const glm::dmat3 b = glm::transpose(
      glm::dmat3(0.8951, 0.2664, -0.1614, -0.7502, 1.7135, 0.0367, 0.0389, -0.0685, 1.0296));
  const glm::dvec3 from = b * xy_to_xyz(wx0, wy0);
  const glm::dvec3 to = b * xy_to_xyz(wx1, wy1);
  glm::dmat3 scale(1.0);
  for (int i = 0; i < 3; ++i) scale[i][i] = to[i] / from[i];
  return glm::inverse(b) * scale * b;
}

bool close(const Chromaticities& a, const Chromaticities& b, int count, double tolerance) {
  for (int i = 0; i < count; ++i) {
    if (std::abs(a[i] - b[i]) > tolerance) return false;
  }
  return true;
}

// xy of the columns of an RGB-to-XYZ matrix and of its white (1, 1, 1).
std::optional<Chromaticities> chromaticities_of(const glm::dmat3& to_xyz) {
  Chromaticities c{};
  const glm::dvec3 xyz[4] = {to_xyz[0], to_xyz[1], to_xyz[2], to_xyz * glm::dvec3(1.0)};
  for (size_t i = 0; i < 4; ++i) {
    const double sum = xyz[i].x + xyz[i].y + xyz[i].z;
    if (!(std::abs(sum) > 1e-9)) return std::nullopt;
    c[2 * i] = xyz[i].x / sum;
    c[2 * i + 1] = xyz[i].y / sum;
  }
  return c;
}

// Linear map from `space` to the XYZ of an interchange role: through aces_interchange (AP0, ACES
// white) or a scene-referred cie_xyz_d65_interchange. `via_aces` tells which.
struct ToXyz {
  glm::dmat3 matrix;
  bool via_aces = false;
};

std::optional<ToXyz> to_interchange_xyz(const OCIO::ConstConfigRcPtr& config,
                                        const std::string& space) {
  try {
    if (config->hasRole(OCIO::ROLE_INTERCHANGE_SCENE)) {
      const auto processor = config->getProcessor(space.c_str(), OCIO::ROLE_INTERCHANGE_SCENE);
      const auto m = linear_matrix(processor->getDefaultCPUProcessor());
      if (!m) return std::nullopt;
      return ToXyz{rgb_to_xyz(kAp0) * *m, true};
    }
    if (config->hasRole(OCIO::ROLE_INTERCHANGE_DISPLAY)) {
      const auto xyz = config->getColorSpace(OCIO::ROLE_INTERCHANGE_DISPLAY);
      // A display-referred XYZ is reached only through a view transform: not colorimetric.
      if (!xyz || xyz->getReferenceSpaceType() != OCIO::REFERENCE_SPACE_SCENE) return std::nullopt;
      const auto processor = config->getProcessor(space.c_str(), OCIO::ROLE_INTERCHANGE_DISPLAY);
      const auto m = linear_matrix(processor->getDefaultCPUProcessor());
      if (!m) return std::nullopt;
      return ToXyz{*m, false};
    }
  } catch (const OCIO::Exception&) {
    return std::nullopt;  // e.g. a space whose transform needs a missing LUT
  }
  return std::nullopt;
}

bool is_linear_rec709(const OCIO::ConstConfigRcPtr& config, const std::string& space) {
  const auto to_xyz = to_interchange_xyz(config, space);
  if (!to_xyz) return false;
  glm::dmat3 expected = rgb_to_xyz(kRec709);
  if (to_xyz->via_aces) expected = bradford(kRec709[6], kRec709[7], kAp0[6], kAp0[7]) * expected;
  // Loose enough for configs that adapt with CAT02 or von Kries instead of Bradford.
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      if (std::abs(to_xyz->matrix[j][i] - expected[j][i]) > 5e-3) return false;
    }
  }
  return true;
}

}  // namespace

std::optional<std::string> find_linear_rec709(const OCIO::ConstConfigRcPtr& config) {
  // Names used by prism's, the ACES (1.x and 2.x), Blender and Nuke default configs.
  constexpr const char* kNames[] = {"Linear Rec.709 (sRGB)",
                                    "lin_rec709",
                                    "Linear Rec.709",
                                    "Utility - Linear - sRGB",
                                    "Utility - Linear - Rec.709",
                                    "lin_srgb",
                                    "Linear sRGB",
                                    "Linear",
                                    "linear"};
  const bool can_verify = config->hasRole(OCIO::ROLE_INTERCHANGE_SCENE) ||
                          config->hasRole(OCIO::ROLE_INTERCHANGE_DISPLAY);
  for (const char* name : kNames) {
    const auto space = config->getColorSpace(name);
    if (!space || space->isData()) continue;
    if (!can_verify || is_linear_rec709(config, space->getName())) return space->getName();
  }
  if (!can_verify) return std::nullopt;
  const int n = config->getNumColorSpaces(OCIO::SEARCH_REFERENCE_SPACE_SCENE, OCIO::COLORSPACE_ALL);
  for (int i = 0; i < n; ++i) {
    const std::string name = config->getColorSpaceNameByIndex(OCIO::SEARCH_REFERENCE_SPACE_SCENE,
                                                              OCIO::COLORSPACE_ALL, i);
    const auto space = config->getColorSpace(name.c_str());
    if (space && !space->isData() && is_linear_rec709(config, name)) return name;
  }
  return std::nullopt;
}

std::optional<std::array<float, 8>> derive_chromaticities(const OCIO::ConstConfigRcPtr& config,
                                                          const std::string& space) {
  const auto to_xyz = to_interchange_xyz(config, space);
  if (!to_xyz) return std::nullopt;
  auto derived = chromaticities_of(to_xyz->matrix);
  if (!derived) return std::nullopt;
  // Configs adapt every space to the reference white, so the transform alone cannot tell a
  // space's own white. The ACES spaces keep the ACES white; every other space prism meets
  // (Rec.709, Rec.2020, P3-D65, XYZ) has a D65 white, so undo the adaptation for those. A space
  // the config did not adapt keeps the white the transform shows.
  const bool aces_white =
      std::abs((*derived)[6] - kAp0[6]) < 1e-3 && std::abs((*derived)[7] - kAp0[7]) < 1e-3;
  const bool aces_primaries = close(*derived, kAp0, 6, 1e-3) || close(*derived, kAp1, 6, 1e-3);
  if (to_xyz->via_aces && aces_white && !aces_primaries) {
    derived =
        chromaticities_of(bradford(kAp0[6], kAp0[7], kRec709[6], kRec709[7]) * to_xyz->matrix);
    if (!derived) return std::nullopt;
  } else if (!to_xyz->via_aces && std::abs((*derived)[6] - kRec709[6]) < 1e-3 &&
             std::abs((*derived)[7] - kRec709[7]) < 1e-3) {
    // Through a D65 XYZ the same question the other way round: is it an ACES space?
    const auto aces =
        chromaticities_of(bradford(kRec709[6], kRec709[7], kAp0[6], kAp0[7]) * to_xyz->matrix);
    if (aces && (close(*aces, kAp0, 6, 1e-3) || close(*aces, kAp1, 6, 1e-3))) derived = aces;
  }
  for (const Chromaticities& known : kKnown) {
    if (close(*derived, known, 8, 1e-3)) {
      derived = known;
      break;
    }
  }
  std::array<float, 8> out{};
  for (int i = 0; i < 8; ++i) out[i] = float((*derived)[i]);
  return out;
}

}  // namespace prism::color_detail
