// What every image writer shares: the atomic write (temporary file, fsync, rename), the
// writability probe, the finite check and the header attributes.

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstring>

#include "color/image_writers.h"
#include "core/atomic_file.h"

namespace prism {
namespace fs = std::filesystem;

namespace color_detail {

Error output_error(const fs::path& path, const std::string& message) {
  return Error(ErrorKind::kOutput, message, ErrorLocation{path.string(), 0, {}});
}

void write_atomically(const fs::path& target, const std::string& format,
                      const OIIO::ImageSpec& spec, const OIIO::TypeDesc& type, const void* pixels) {
  write_atomically(target, format, {Subimage{spec, type, pixels}});
}

void write_atomically(const fs::path& target, const std::string& format,
                      const std::vector<Subimage>& subimages) {
  PRISM_CHECK(!subimages.empty());
  AtomicFile temp(target);
  try {
    auto out = OIIO::ImageOutput::create(format);
    if (!out) throw output_error(target, "no " + format + " writer: " + OIIO::geterror());
    std::vector<OIIO::ImageSpec> specs;
    for (const Subimage& s : subimages) specs.push_back(s.spec);
    const bool opened = subimages.size() == 1
                            ? out->open(temp.temp_path().string(), specs[0])
                            : out->open(temp.temp_path().string(), int(specs.size()), specs.data());
    // The folder was checked before the work; if it went away or became read-only since, say
    // so as that check does rather than with OpenImageIO's message about the temporary file.
    if (!opened) check_output_writable(target);
    bool ok = opened;
    for (size_t i = 0; ok && i < subimages.size(); ++i) {
      if (i > 0)
        ok = out->open(temp.temp_path().string(), specs[i], OIIO::ImageOutput::AppendSubimage);
      ok = ok && out->write_image(subimages[i].type, subimages[i].pixels);
    }
    ok = ok && out->close();
    if (!ok) {
      const std::string reason = out->geterror();
      throw output_error(target, "cannot write the " + format +
                                     " file: " + (reason.empty() ? "unknown error" : reason));
    }
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw output_error(target, "cannot write the " + format + " file: " + e.what());
  }
  temp.commit();
}

void check_finite(std::span<const float> values, const fs::path& path) {
  const size_t bad =
      std::count_if(values.begin(), values.end(), [](float v) { return !std::isfinite(v); });
  if (bad > 0) {
    throw Error(ErrorKind::kInternal,
                std::to_string(bad) + " NaN/Inf values would be written; refusing to write",
                ErrorLocation{path.string(), 0, {}});
  }
}

void add_header_attributes(OIIO::ImageSpec& spec, const ImageMetadata& metadata,
                           const ColorPipeline& pipeline) {
  for (const auto& [name, value] : metadata) {
    if (!name.empty()) spec.attribute(name, value);
  }
  spec.attribute("prism:ocioConfig", pipeline.config_name());
  spec.attribute("prism:ocioConfigHash", pipeline.config_hash());
  spec.attribute("prism:ocioConfigSource", pipeline.config_source());
  spec.attribute("prism:workingSpace", pipeline.working_space());
  if (!pipeline.display().empty()) {
    spec.attribute("prism:display", pipeline.display());
    spec.attribute("prism:view", pipeline.view());
  }
  if (!pipeline.look().empty()) spec.attribute("prism:look", pipeline.look());
}

}  // namespace color_detail

}  // namespace prism
