// A scene's textures: MIP-mapped in memory and looked up through OpenImageIO's TextureSystem.

#include "color/texture_set.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <new>

#include "color/texture_image.h"
#include "core/error.h"
#include "core/hash.h"

namespace prism {
namespace {

/// Largest value a half float holds.
constexpr float kHalfMax = 65504.0f;
/// Tile side of the in-memory textures (the TextureSystem caches tiles).
constexpr int kTileSide = 64;

/// The image as a tiled, MIP-mapped OpenEXR file in memory: half floats unless a value needs
/// float, no compression (lookups decode tiles often; memory is the price).
std::vector<unsigned char> encode_mipmapped_exr(const Image& image, const std::string& name) {
  PRISM_CHECK(image.channels() == 3 && image.width > 0 && image.height > 0);
  float largest = 0.0f;
  for (const float v : image.pixels) largest = std::max(largest, std::abs(v));
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  auto out = OIIO::ImageOutput::create("texture.exr");
  PRISM_CHECK(out != nullptr);
  out->set_ioproxy(&memory);
  OIIO::ImageSpec spec(image.width, image.height, 3,
                       largest <= kHalfMax ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"R", "G", "B"};
  spec.tile_width = spec.tile_height = kTileSide;
  spec.attribute("compression", "none");
  spec.attribute("textureformat", "Plain Texture");
  spec.attribute("wrapmodes", "periodic,periodic");
  const auto fail = [&](const std::string& what) {
    return Error(ErrorKind::kInternal, fmt::format("texture '{}': cannot build its MIP-map: {}: {}",
                                                   name, what, out->geterror()));
  };
  // ImageBuf wraps the caller's pixels (no copy) for level 0.
  const OIIO::ImageSpec float_spec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT);
  OIIO::ImageBuf level(float_spec, const_cast<float*>(image.pixels.data()));
  if (!out->open("texture.exr", spec, OIIO::ImageOutput::Create)) throw fail("open");
  if (!out->write_image(OIIO::TypeDesc::FLOAT, level.localpixels())) throw fail("level 0");
  int w = image.width, h = image.height;
  for (int index = 1; w > 1 || h > 1; ++index) {
    w = std::max(1, w / 2);
    h = std::max(1, h / 2);
    OIIO::ImageBuf smaller(OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::FLOAT));
    if (!OIIO::ImageBufAlgo::resize(smaller, level, "box", 0.0f)) {
      throw Error(ErrorKind::kInternal, fmt::format("texture '{}': cannot build MIP level {}: {}",
                                                    name, index, smaller.geterror()));
    }
    level = std::move(smaller);
    OIIO::ImageSpec level_spec = spec;
    level_spec.width = level_spec.full_width = w;
    level_spec.height = level_spec.full_height = h;
    if (!out->open("texture.exr", level_spec, OIIO::ImageOutput::AppendMIPLevel) ||
        !out->write_image(OIIO::TypeDesc::FLOAT, level.localpixels())) {
      throw fail(fmt::format("level {}", index));
    }
  }
  if (!out->close()) throw fail("close");
  return bytes;
}

class OiioTextureLookup final : public TextureLookup {
 public:
  OiioTextureLookup() : system_(OIIO::TextureSystem::create(/*shared=*/false)) {
    PRISM_CHECK(system_ != nullptr);
    // Every "file" is in memory: none needs closing to spare file handles (and none is
    // reopened through its reader).
    system_->attribute("max_open_files", 1 << 20);
  }
  // teardown_imagecache: OpenImageIO 2.4 does not free a private TextureSystem's ImageCache
  // otherwise (LeakSanitizer: 25 kB a textured render, allocated in ImageCache::create).
  ~OiioTextureLookup() override {
    OIIO::TextureSystem::destroy(system_, /*teardown_imagecache=*/true);
  }
  OiioTextureLookup(const OiioTextureLookup&) = delete;
  OiioTextureLookup& operator=(const OiioTextureLookup&) = delete;

  size_t size() const override { return entries_.size(); }
  Rgb lookup(uint32_t texture, Vec2 uv, Vec2 duv_dx, Vec2 duv_dy) const override;
  Rgb average(uint32_t texture) const override { return entries_[texture]->average; }
  uint64_t content_hash() const override { return hash_; }
  /// Adds `image` as the next texture (MIP-mapped and opened now); `name` is for messages.
  void add(const Image& image, const std::string& name);

 private:
  struct Entry {
    std::vector<unsigned char> exr;
    std::unique_ptr<OIIO::Filesystem::IOMemReader> reader;  ///< reads `exr`
    OIIO::TextureSystem::TextureHandle* handle = nullptr;
    Rgb average{0.0f};
  };
  OIIO::TextureSystem* system_ = nullptr;
  std::vector<std::unique_ptr<Entry>> entries_;
  uint64_t hash_ = kFnvOffset;
};

void OiioTextureLookup::add(const Image& image, const std::string& name) {
  const size_t i = entries_.size();
  {
    hash_ = fnv1a64(std::as_bytes(std::span<const float>(image.pixels)), hash_);
    auto entry = std::make_unique<Entry>();
    double sum[3] = {0.0, 0.0, 0.0};
    const size_t count = size_t(image.width) * image.height;
    for (size_t p = 0; p < count; ++p) {
      for (int c = 0; c < 3; ++c) sum[c] += image.pixels[3 * p + size_t(c)];
    }
    entry->average = Rgb(float(sum[0] / double(count)), float(sum[1] / double(count)),
                         float(sum[2] / double(count)));
    entry->exr = encode_mipmapped_exr(image, name);
    entry->reader =
        std::make_unique<OIIO::Filesystem::IOMemReader>(entry->exr.data(), entry->exr.size());
    // The TextureSystem opens the "file" through the reader; the name only has to be unique.
    const OIIO::ustring file(fmt::format("prism-texture-{}.exr", i));
    void* proxy = entry->reader.get();
    OIIO::ImageSpec config;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    OIIO::ImageSpec opened;
    if (!system_->imagecache()->add_file(file, nullptr, &config) ||
        (entry->handle = system_->get_texture_handle(file)) == nullptr ||
        !system_->get_imagespec(entry->handle, nullptr, 0, opened) || opened.width != image.width) {
      throw Error(ErrorKind::kInput,
                  fmt::format("texture '{}': the texture system cannot open it: {}", name,
                              system_->geterror()));
    }
    entries_.push_back(std::move(entry));
  }
}

Rgb OiioTextureLookup::lookup(uint32_t texture, Vec2 uv, Vec2 duv_dx, Vec2 duv_dy) const {
  const Entry& entry = *entries_[texture];
  OIIO::TextureOpt options;
  options.swrap = options.twrap = OIIO::TextureOpt::WrapPeriodic;
  options.interpmode = OIIO::TextureOpt::InterpBilinear;
  // OpenImageIO's t runs down the image from its top row; prism's v runs up.
  float rgb[3] = {0.0f, 0.0f, 0.0f};
  const bool ok = system_->texture(entry.handle, system_->get_perthread_info(), options, uv.x,
                                   1.0f - uv.y, duv_dx.x, -duv_dx.y, duv_dy.x, -duv_dy.y, 3, rgb);
  // Every texture opened at construction, so a failed lookup is a coordinate that is not a
  // number: black, as a ray that is not a number misses.
  if (!ok) return Rgb(0.0f);
  return Rgb(rgb[0], rgb[1], rgb[2]);
}

}  // namespace

std::shared_ptr<const TextureLookup> make_texture_lookup(const std::vector<Image>& images,
                                                         const std::vector<std::string>& names) {
  PRISM_CHECK(images.size() == names.size());
  try {
    auto lookup = std::make_shared<OiioTextureLookup>();
    for (size_t i = 0; i < images.size(); ++i) lookup->add(images[i], names[i]);
    return lookup;
  } catch (const std::bad_alloc&) {
    throw Error(ErrorKind::kResource, "out of memory while preparing the textures");
  }
}

SceneTexturesReport load_scene_textures(Scene& scene, const ColorPipeline& pipeline) {
  SceneTexturesReport report;
  if (scene.textures.empty()) return report;
  try {
    // One image at a time: only its MIP-map stays in memory.
    auto lookup = std::make_shared<OiioTextureLookup>();
    for (const TextureSource& source : scene.textures) {
      const TextureImage texture = read_texture_image(source, pipeline, report.warnings);
      report.descriptions.push_back(
          fmt::format("{}: {} ({})", source.name, texture.color_space, texture.space_rule));
      lookup->add(texture.image, source.name);
    }
    scene.texture_lookup = std::move(lookup);
  } catch (const std::bad_alloc&) {
    throw Error(ErrorKind::kResource, "out of memory while preparing the textures");
  }
  return report;
}

}  // namespace prism
