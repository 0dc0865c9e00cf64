// Colour management for prism: every colour conversion goes through OpenColorIO here.
//
// Which config: --ocio-config, else $OCIO, else the bundled config (color/ocio/config.ocio,
// compiled into the program). Any OCIO 2.x config works without code changes, because prism asks
// a config only for roles, colour-space names, displays, views and looks:
//
//   * working space  --working-space, else the `scene_linear` role. It must be scene-referred,
//                    not data, and linear (checked on the transform); a config without
//                    scene_linear and no --working-space is a usage error that lists the spaces.
//   * output space   --output-space (EXR), else `scene_linear`, else the working space.
//   * display/view   --display / --view, else the config's default display and its default
//                    view; --look adds looks after the view's own; --exposure scales (in stops)
//                    the linear working values before the view.
//   * scene colours  scene files are authored in linear Rec.709; prism finds that space by its
//                    usual names ("Linear Rec.709 (sRGB)", "lin_rec709", "Utility - Linear - sRGB",
//                    Blender's "Linear Rec.709"/"Linear", ...), checking it against the published
//                    Rec.709 matrix when the config has an `aces_interchange` role, else by
//                    testing every scene-linear space against that matrix. None found: usage error.
//   * chromaticities derived from the output space's transform to `aces_interchange` (else to a
//                    scene-referred `cie_xyz_d65_interchange`); without either the EXR simply
//                    carries no chromaticities attribute.
//
// ACES studio/CG configs (OCIO 2.1+): scene_linear = ACEScg, aces_interchange = ACES2065-1,
// displays "sRGB - Display", "Rec.1886 Rec.709 - Display", ... with views "ACES 1.0 - SDR
// Video", "Un-tone-mapped", "Raw". `OCIO=/path/studio-config.ocio prism render ...` then renders
// in ACEScg, writes an ACEScg EXR with AP1 chromaticities, and a PNG through the ACES view.
// Blender's config (3.x/4.x): scene_linear = "Linear Rec.709" ("Linear" in 3.x), display
// "sRGB", views "Standard", "Filmic"/"AgX", "Raw"; Blender 3.x has no interchange roles, so
// its EXRs carry no chromaticities and its Rec.709 space is found by name.
// Data AOVs (normals, depth, sample counts, variance) are never converted; colour AOVs (albedo,
// diffuse, ...) are converted exactly like the beauty. Material eta/k (spectral optical
// constants, not colours) are left alone.

#include "color/color_pipeline.h"

#include <OpenColorIO/OpenColorIO.h>
#if defined(__SANITIZE_THREAD__)
// Only ThreadSanitizer builds call OpenImageIO here (below); elsewhere the program does not link
// it (color/image_io.h).
#include <OpenImageIO/imageio.h>
#endif

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>

#include "color/ocio_config.h"
#include "core/error.h"
#include "core/strings.h"

namespace prism {

using namespace color_detail;

struct ColorPipeline::Impl {
  LoadedConfig loaded;
  std::string working, output, display, view, look, display_space, scene_space;
  float exposure = 0.0f;
  OCIO::ConstCPUProcessorRcPtr to_output;   // null when the output space is the working space
  OCIO::ConstCPUProcessorRcPtr to_display;  // null when the config has no displays
  std::optional<std::array<float, 8>> chromaticities;

  [[noreturn]] void fail(const std::exception& e) const {
    throw Error(ErrorKind::kInput, std::string("OCIO: ") + e.what(),
                ErrorLocation{loaded.source, 0, {}});
  }
};

namespace {

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

// Rendering needs a space where light adds linearly; reject data, display-referred and curved
// spaces with the reason.
void check_working_space(const OCIO::ConstConfigRcPtr& config, const std::string& name) {
  const auto space = config->getColorSpace(name.c_str());
  if (space->isData()) {
    throw Error(ErrorKind::kUsage, "working space '" + name + "' holds non-colour data");
  }
  if (space->getReferenceSpaceType() != OCIO::REFERENCE_SPACE_SCENE) {
    throw Error(ErrorKind::kUsage,
                "working space '" + name + "' is display-referred; choose a scene-linear space");
  }
  const std::string encoding = space->getEncoding();
  bool linear = encoding.empty() || encoding == "scene-linear";
  const char* reference =
      config->hasRole(OCIO::ROLE_INTERCHANGE_SCENE)
          ? OCIO::ROLE_INTERCHANGE_SCENE
          : (config->hasRole(OCIO::ROLE_SCENE_LINEAR) ? OCIO::ROLE_SCENE_LINEAR : nullptr);
  if (linear && reference != nullptr) {
    const auto processor = config->getProcessor(name.c_str(), reference);
    linear = linear_matrix(processor->getDefaultCPUProcessor()).has_value();
  }
  if (!linear) {
    throw Error(ErrorKind::kUsage, "working space '" + name + "' is not linear" +
                                       (encoding.empty() ? "" : " (encoding " + encoding + ")") +
                                       "; rendering needs a scene-linear space");
  }
}

void check_output_space(const OCIO::ConstConfigRcPtr& config, const std::string& name) {
  const auto space = config->getColorSpace(name.c_str());
  if (space->isData() || space->getReferenceSpaceType() != OCIO::REFERENCE_SPACE_SCENE) {
    throw Error(ErrorKind::kUsage,
                "output space '" + name +
                    "' is not a scene-referred colour space; EXR files hold scene-referred "
                    "colour (use --display/--view for display-referred images)");
  }
}

#if defined(__SANITIZE_THREAD__)
/// ThreadSanitizer builds (docs/RELIABILITY.md): OpenImageIO's own thread pool (MIP-mapping
/// textures, converting and writing images) and OpenEXR's are not instrumented, so TSan cannot
/// see how they hand results back; with no pool their work runs on the caller, where TSan sees
/// every access prism makes. Other builds leave OpenImageIO's threads alone.
[[gnu::noinline]] bool configure_openimageio_threads() {
  OIIO::attribute("threads", 1);
  OIIO::attribute("exr_threads", -1);
  return true;
}

/// configure_openimageio_threads(), once per process. TSan names a thread by the call sites on
/// its creation stack, so every thread started below this function's call is OpenImageIO's:
/// tests/support/tsan.supp names it for the worker OpenImageIO stops without joining.
[[gnu::noinline]] void keep_openimageio_on_the_calling_thread() {
  static const bool configured = configure_openimageio_threads();
  (void)configured;
}
#endif

Rgb apply_one(const OCIO::ConstCPUProcessorRcPtr& processor, const Rgb& color) {
  float v[3] = {color.x, color.y, color.z};
  processor->applyRGB(v);
  return Rgb(v[0], v[1], v[2]);
}

}  // namespace

ColorPipeline::ColorPipeline(const ColorOptions& options) : impl_(std::make_unique<Impl>()) {
#if defined(__SANITIZE_THREAD__)
  keep_openimageio_on_the_calling_thread();
#endif
  Impl& d = *impl_;
  d.loaded = load_config(options.ocio_config);
  const OCIO::ConstConfigRcPtr& config = d.loaded.config;
  const std::string config_label =
      std::string("OCIO config '") + config->getName() + "' (" + d.loaded.source + ")";
  try {
    if (options.working_space.empty() && !config->hasRole(OCIO::ROLE_SCENE_LINEAR)) {
      throw Error(ErrorKind::kUsage, config_label +
                                         " has no scene_linear role; choose a working space "
                                         "with --working-space; available: " +
                                         join_names(color_space_names(*config)));
    }
    d.working = resolve_color_space(
        *config, options.working_space.empty() ? OCIO::ROLE_SCENE_LINEAR : options.working_space,
        "working space");
    check_working_space(config, d.working);

    if (!options.output_space.empty()) {
      d.output = resolve_color_space(*config, options.output_space, "output space");
    } else {
      d.output = config->hasRole(OCIO::ROLE_SCENE_LINEAR)
                     ? resolve_color_space(*config, OCIO::ROLE_SCENE_LINEAR, "output space")
                     : d.working;
    }
    check_output_space(config, d.output);
    if (d.output != d.working) {
      d.to_output =
          config->getProcessor(d.working.c_str(), d.output.c_str())->getDefaultCPUProcessor();
    }
    d.chromaticities = derive_chromaticities(config, d.output);

    const std::vector<std::string> displays = display_names(*config);
    if (!options.display.empty() && !contains(displays, options.display)) {
      throw Error(ErrorKind::kUsage,
                  "unknown display '" + options.display + "'; available: " + join_names(displays));
    }
    d.display = options.display.empty() ? config->getDefaultDisplay() : options.display;
    if (d.display.empty() && (!options.view.empty() || !options.look.empty())) {
      throw Error(ErrorKind::kUsage, config_label + " has no displays");
    }
    if (!d.display.empty()) {
      const std::vector<std::string> views = view_names(*config, d.display);
      d.view = options.view.empty() ? config->getDefaultView(d.display.c_str()) : options.view;
      if (!contains(views, d.view)) {
        throw Error(ErrorKind::kUsage, "unknown view '" + d.view + "' for display '" + d.display +
                                           "'; available: " + join_names(views));
      }
    }
    if (!options.look.empty()) check_looks(*config, options.look);
    d.look = options.look;
    if (!std::isfinite(options.exposure)) {
      throw Error(ErrorKind::kUsage, "exposure must be a finite number of stops");
    }
    d.exposure = options.exposure;

    if (!d.display.empty()) {
      auto transform = OCIO::DisplayViewTransform::Create();
      transform->setSrc(d.working.c_str());
      transform->setDisplay(d.display.c_str());
      transform->setView(d.view.c_str());
      auto viewing = OCIO::LegacyViewingPipeline::Create();
      viewing->setDisplayViewTransform(transform);
      if (!d.look.empty()) {
        // The user's look comes after the looks the view already applies, not instead of them.
        const std::string view_looks =
            config->getDisplayViewLooks(d.display.c_str(), d.view.c_str());
        viewing->setLooksOverrideEnabled(true);
        viewing->setLooksOverride(
            (view_looks.empty() ? d.look : view_looks + ", " + d.look).c_str());
      }
      d.to_display = viewing->getProcessor(config)->getDefaultCPUProcessor();
      d.display_space = config->getDisplayViewColorSpaceName(d.display.c_str(), d.view.c_str());
    }

    const auto rec709 = find_linear_rec709(config);
    if (!rec709) {
      throw Error(ErrorKind::kUsage,
                  config_label +
                      " has no linear Rec.709 colour space, which scene colours are authored "
                      "in (looked for 'Linear Rec.709 (sRGB)', 'lin_rec709', 'Linear Rec.709', "
                      "'Utility - Linear - sRGB' and spaces matching the Rec.709 matrix)");
    }
    d.scene_space = *rec709;
  } catch (const OCIO::Exception& e) {
    d.fail(e);
  }
}

ColorPipeline::~ColorPipeline() = default;

void ColorPipeline::convert_scene_to_working(Scene& scene, const std::string& scene_space) const {
  const OCIO::ConstConfigRcPtr& config = impl_->loaded.config;
  const std::string from = resolve_color_space(*config, scene_space, "scene colours");
  if (from == impl_->working) return;
  OCIO::ConstCPUProcessorRcPtr processor;
  try {
    processor =
        config->getProcessor(from.c_str(), impl_->working.c_str())->getDefaultCPUProcessor();
  } catch (const OCIO::Exception& e) {
    impl_->fail(e);
  }
  // Reflectances, transmittances and emitted radiance are colours; eta and k are optical
  // constants sampled at three wavelengths and would lose their meaning under a matrix.
  for (Material& m : scene.materials) {
    m.reflectance = apply_one(processor, m.reflectance);
    m.transmittance = apply_one(processor, m.transmittance);
    m.radiance = apply_one(processor, m.radiance);
  }
  for (Light& light : scene.lights) light.color = apply_one(processor, light.color);
}

std::string ColorPipeline::scene_file_space() const { return impl_->scene_space; }
std::string ColorPipeline::working_space() const { return impl_->working; }
std::string ColorPipeline::output_space() const { return impl_->output; }
std::string ColorPipeline::display() const { return impl_->display; }
std::string ColorPipeline::view() const { return impl_->view; }
std::string ColorPipeline::look() const { return impl_->look; }
float ColorPipeline::exposure() const { return impl_->exposure; }
std::string ColorPipeline::config_name() const { return impl_->loaded.config->getName(); }
std::string ColorPipeline::config_hash() const { return impl_->loaded.hash; }
std::string ColorPipeline::config_source() const { return impl_->loaded.source; }
std::string ColorPipeline::display_color_space() const { return impl_->display_space; }

std::optional<std::array<float, 8>> ColorPipeline::output_chromaticities() const {
  return impl_->chromaticities;
}

bool ColorPipeline::converts_to_output() const { return impl_->to_output != nullptr; }

void ColorPipeline::working_to_output(Image& image) const {
  PRISM_CHECK(image.pixels.size() == size_t(image.width) * image.height * image.channels());
  if (!impl_->to_output) return;
  for (const auto& triple : color_channel_triples(image)) {
    apply_rgb(impl_->to_output, image.pixels.data(), size_t(image.width) * image.height,
              image.channels(), triple.data());
  }
}

void ColorPipeline::convert_image_to_working(Image& image, const std::string& from) const {
  PRISM_CHECK(image.pixels.size() == size_t(image.width) * image.height * image.channels());
  const OCIO::ConstConfigRcPtr& config = impl_->loaded.config;
  const std::string src = resolve_color_space(*config, from, "input space");
  if (src == impl_->working) return;
  OCIO::ConstCPUProcessorRcPtr processor;
  try {
    processor = config->getProcessor(src.c_str(), impl_->working.c_str())->getDefaultCPUProcessor();
  } catch (const OCIO::Exception& e) {
    impl_->fail(e);
  }
  for (const auto& triple : color_channel_triples(image)) {
    apply_rgb(processor, image.pixels.data(), size_t(image.width) * image.height, image.channels(),
              triple.data());
  }
}

Image ColorPipeline::working_to_display(const Image& image) const {
  if (!impl_->to_display) {
    throw Error(ErrorKind::kUsage, "the OCIO config (" + impl_->loaded.source +
                                       ") has no displays; display-referred images need one");
  }
  PRISM_CHECK(image.pixels.size() == size_t(image.width) * image.height * image.channels());
  const auto triples = color_channel_triples(image);
  PRISM_CHECK(!triples.empty() && image.channel_names[triples[0][0]] == "R");
  Image out;
  out.width = image.width;
  out.height = image.height;
  out.channel_names = {"R", "G", "B"};
  const size_t count = size_t(image.width) * image.height;
  out.pixels.resize(count * 3);
  const float scale = std::exp2(impl_->exposure);
  for (size_t i = 0; i < count; ++i) {
    for (int c = 0; c < 3; ++c) {
      out.pixels[i * 3 + c] = image.pixels[i * image.channels() + triples[0][c]] * scale;
    }
  }
  const int rgb[3] = {0, 1, 2};
  apply_rgb(impl_->to_display, out.pixels.data(), count, 3, rgb);
  // Display code values live in [0, 1]; a NaN here would be a bug upstream, caught by the writer.
  for (float& v : out.pixels) v = std::isnan(v) ? v : std::clamp(v, 0.0f, 1.0f);
  return out;
}

Rgb ColorPipeline::convert(const Rgb& color, const std::string& from, const std::string& to) const {
  const OCIO::ConstConfigRcPtr& config = impl_->loaded.config;
  const std::string src = resolve_color_space(*config, from, "source");
  const std::string dst = resolve_color_space(*config, to, "destination");
  try {
    return apply_one(config->getProcessor(src.c_str(), dst.c_str())->getDefaultCPUProcessor(),
                     color);
  } catch (const OCIO::Exception& e) {
    impl_->fail(e);
  }
}

std::optional<std::string> ColorPipeline::find_color_space(const std::string& name) const {
  if (name.empty()) return std::nullopt;
  const auto space = impl_->loaded.config->getColorSpace(name.c_str());
  if (!space) return std::nullopt;
  return std::string(space->getName());
}

Rgb ColorPipeline::working_to_display(const Rgb& color) const {
  if (!impl_->to_display) {
    throw Error(ErrorKind::kUsage, "the OCIO config (" + impl_->loaded.source +
                                       ") has no displays; display-referred images need one");
  }
  return apply_one(impl_->to_display, color * std::exp2(impl_->exposure));
}

bool is_color_layer(const std::string& layer) {
  constexpr const char* kColorLayers[] = {
      "",       "albedo",   "diffuse",    "specular", "glossy",         "transmission", "emission",
      "direct", "indirect", "background", "beauty",   "diffuse_albedo", "diffuseColor"};
  const std::string l = to_lower(layer);
  for (const char* name : kColorLayers) {
    if (l == to_lower(name)) return true;
  }
  return false;
}

std::vector<std::array<int, 3>> color_channel_triples(const Image& image) {
  std::map<std::string, int> index;
  for (int i = 0; i < image.channels(); ++i) index.emplace(image.channel_names[i], i);
  std::vector<std::array<int, 3>> triples;
  auto add = [&](const std::string& prefix) {
    const auto r = index.find(prefix + "R"), g = index.find(prefix + "G"),
               b = index.find(prefix + "B");
    if (r != index.end() && g != index.end() && b != index.end()) {
      triples.push_back({r->second, g->second, b->second});
    }
  };
  add("");
  for (const std::string& name : image.channel_names) {
    if (name.size() < 3 || name.compare(name.size() - 2, 2, ".R") != 0) continue;
    const std::string layer = name.substr(0, name.size() - 2);
    if (!layer.empty() && is_color_layer(layer)) add(layer + ".");
  }
  return triples;
}

ColorConfigListing list_color_config(const std::string& ocio_config) {
  const LoadedConfig loaded = load_config(ocio_config);
  const OCIO::Config& config = *loaded.config;
  ColorConfigListing listing;
  listing.config_source = loaded.source;
  listing.config_name = config.getName();
  listing.color_spaces = color_space_names(config);
  listing.displays = display_names(config);
  listing.looks = look_names(config);
  listing.roles = role_names(config);
  listing.default_display = config.getDefaultDisplay();
  for (const auto& display : listing.displays) {
    listing.views.emplace_back(display, view_names(config, display));
  }
  for (int i = 0; i < config.getNumRoles(); ++i) {
    listing.role_spaces.emplace_back(config.getRoleName(i), config.getRoleColorSpace(i));
  }
  return listing;
}

std::string format_color_config(const ColorConfigListing& listing) {
  std::string out =
      "OCIO config: " + (listing.config_name.empty() ? "(unnamed)" : listing.config_name) + " (" +
      listing.config_source + ")\n";
  out += "roles:\n";
  for (const auto& [role, space] : listing.role_spaces) out += "  " + role + ": " + space + "\n";
  out += "colour spaces:\n";
  for (const auto& space : listing.color_spaces) out += "  " + space + "\n";
  out += "displays and views:\n";
  for (const auto& [display, views] : listing.views) {
    out += "  " + display + (display == listing.default_display ? " (default)" : "") + ": " +
           join_names(views) + "\n";
  }
  out += "looks:\n";
  for (const auto& look : listing.looks) out += "  " + look + "\n";
  if (listing.looks.empty()) out += "  (none)\n";
  return out;
}

}  // namespace prism
