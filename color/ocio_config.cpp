#include "color/ocio_config.h"

#include <fmt/format.h>
#include <openssl/evp.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "color/color_pipeline.h"
#include "core/error.h"
#include "core/strings.h"

namespace prism::color_detail {
namespace {

// Lower-case hex, as sha1sum prints it, so the header value can be checked against the file.
// OpenSSL's digest (libcrypto, a few milliseconds to load), not OpenImageIO's: the program loads
// OpenImageIO only when it reads or writes an image (color/image_io.h), after the config.
std::string sha1_of(const std::string& bytes) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  if (EVP_Digest(bytes.data(), bytes.size(), digest, &length, EVP_sha1(), nullptr) != 1) {
    throw Error(ErrorKind::kInternal, "OpenSSL could not compute the SHA-1 of the OCIO config");
  }
  std::string hex = "sha1:";
  for (unsigned int i = 0; i < length; ++i) hex += fmt::format("{:02x}", digest[i]);
  return hex;
}

std::string read_config_file(const std::string& path, const std::string& origin) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw Error(ErrorKind::kUsage,
                "OCIO config '" + path + "' (" + origin + ") does not exist or is not a file");
  }
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in)
    throw Error(ErrorKind::kUsage, "cannot read OCIO config '" + path + "' (" + origin + ")");
  return text.str();
}

// Parses and validates; OCIO reports both kinds of problem as OCIO::Exception.
OCIO::ConstConfigRcPtr parse_config(const std::string& path, const std::string& text) {
  try {
    OCIO::ConstConfigRcPtr config;
    if (path.empty()) {
      std::istringstream stream(text);
      config = OCIO::Config::CreateFromStream(stream);
    } else {
      // From the file, so search paths of LUT-based configs resolve beside it.
      config = OCIO::Config::CreateFromFile(path.c_str());
    }
    config->validate();
    return config;
  } catch (const OCIO::Exception& e) {
    throw Error(ErrorKind::kInput, std::string("invalid OCIO config: ") + e.what(),
                ErrorLocation{path.empty() ? std::string("bundled OCIO config") : path, 0, {}});
  }
}

std::string trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t");
  if (begin == std::string::npos) return {};
  const auto end = s.find_last_not_of(" \t");
  return s.substr(begin, end - begin + 1);
}

}  // namespace

LoadedConfig load_config(const std::string& ocio_config) {
  std::string path;
  std::string origin;
  if (!ocio_config.empty()) {
    path = ocio_config;
    origin = "--ocio-config";
  } else if (const char* env = std::getenv("OCIO"); env != nullptr && env[0] != '\0') {
    path = env;
    origin = "$OCIO";
  }
  LoadedConfig loaded;
  if (path.empty()) {
    loaded.config = parse_config({}, bundled_color_config_text());
    loaded.source = "bundled";
    loaded.hash = sha1_of(bundled_color_config_text());
    return loaded;
  }
  const std::string text = read_config_file(path, origin);
  loaded.config = parse_config(path, text);
  loaded.source = path;
  loaded.hash = sha1_of(text);
  return loaded;
}

std::string join_names(const std::vector<std::string>& names) {
  return join(names, ", ", "(none)");
}

std::vector<std::string> color_space_names(const OCIO::Config& config) {
  std::vector<std::string> names;
  const int n = config.getNumColorSpaces(OCIO::SEARCH_REFERENCE_SPACE_ALL, OCIO::COLORSPACE_ACTIVE);
  for (int i = 0; i < n; ++i) {
    names.emplace_back(config.getColorSpaceNameByIndex(OCIO::SEARCH_REFERENCE_SPACE_ALL,
                                                       OCIO::COLORSPACE_ACTIVE, i));
  }
  return names;
}

std::vector<std::string> display_names(const OCIO::Config& config) {
  std::vector<std::string> names;
  for (int i = 0; i < config.getNumDisplays(); ++i) names.emplace_back(config.getDisplay(i));
  return names;
}

std::vector<std::string> view_names(const OCIO::Config& config, const std::string& display) {
  std::vector<std::string> names;
  const int n = config.getNumViews(display.c_str());
  for (int i = 0; i < n; ++i) names.emplace_back(config.getView(display.c_str(), i));
  return names;
}

std::vector<std::string> look_names(const OCIO::Config& config) {
  std::vector<std::string> names;
  for (int i = 0; i < config.getNumLooks(); ++i) names.emplace_back(config.getLookNameByIndex(i));
  return names;
}

std::vector<std::string> role_names(const OCIO::Config& config) {
  std::vector<std::string> names;
  for (int i = 0; i < config.getNumRoles(); ++i) names.emplace_back(config.getRoleName(i));
  return names;
}

std::string resolve_color_space(const OCIO::Config& config, const std::string& name,
                                const std::string& what) {
  // getColorSpace also accepts roles and aliases, as every OCIO application does.
  const auto space = name.empty() ? nullptr : config.getColorSpace(name.c_str());
  if (!space) {
    throw Error(ErrorKind::kUsage, "unknown colour space '" + name + "' (" + what +
                                       "); available: " + join_names(color_space_names(config)) +
                                       "; roles: " + join_names(role_names(config)));
  }
  return space->getName();
}

void check_looks(const OCIO::Config& config, const std::string& looks) {
  std::string item;
  std::istringstream stream(looks);
  // OCIO separates looks with ',' or ':' and marks the direction with a '+' or '-' prefix.
  while (std::getline(stream, item, ',')) {
    std::istringstream inner(item);
    std::string part;
    while (std::getline(inner, part, ':')) {
      std::string name = trim(part);
      if (!name.empty() && (name[0] == '+' || name[0] == '-')) name = trim(name.substr(1));
      if (name.empty() || !config.getLook(name.c_str())) {
        throw Error(ErrorKind::kUsage,
                    "unknown look '" + name + "'; available: " + join_names(look_names(config)));
      }
    }
  }
}

std::optional<glm::dmat3> linear_matrix(const OCIO::ConstCPUProcessorRcPtr& processor) {
  glm::dmat3 m(1.0);
  for (int j = 0; j < 3; ++j) {
    float v[3] = {0.0f, 0.0f, 0.0f};
    v[j] = 1.0f;
    processor->applyRGB(v);
    m[j] = glm::dvec3(v[0], v[1], v[2]);
  }
  // A curve shows up as a mismatch on scaled and mixed colours, including values above 1.
  const glm::dvec3 probes[] = {{0.18, 0.18, 0.18}, {4.0, 0.5, 0.02}, {0.01, 2.0, 9.0}};
  for (const glm::dvec3& p : probes) {
    float v[3] = {float(p.x), float(p.y), float(p.z)};
    processor->applyRGB(v);
    const glm::dvec3 expected = m * p;
    for (int c = 0; c < 3; ++c) {
      const double tolerance = 1e-4 * std::max({1.0, std::abs(expected[c]), glm::length(p)});
      if (!std::isfinite(v[c]) || std::abs(v[c] - expected[c]) > tolerance) return std::nullopt;
    }
  }
  return m;
}

void apply_rgb(const OCIO::ConstCPUProcessorRcPtr& processor, float* pixels, size_t pixel_count,
               int channel_count, const int channels[3]) {
  // Copy to a packed buffer in blocks: the triples need not be adjacent or in R, G, B order.
  constexpr size_t kBlock = 4096;
  std::vector<float> rgb(kBlock * 3);
  for (size_t begin = 0; begin < pixel_count; begin += kBlock) {
    const size_t count = std::min(kBlock, pixel_count - begin);
    for (size_t i = 0; i < count; ++i) {
      const float* px = pixels + (begin + i) * channel_count;
      for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = px[channels[c]];
    }
    OCIO::PackedImageDesc desc(rgb.data(), long(count), 1, 3);
    processor->apply(desc);
    for (size_t i = 0; i < count; ++i) {
      float* px = pixels + (begin + i) * channel_count;
      for (int c = 0; c < 3; ++c) px[channels[c]] = rgb[i * 3 + c];
    }
  }
}

}  // namespace prism::color_detail
