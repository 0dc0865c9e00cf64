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

namespace prism {
namespace fs = std::filesystem;

namespace color_detail {
namespace {

fs::path folder_of(const fs::path& path) {
  return path.has_parent_path() ? path.parent_path() : fs::path(".");
}

// A hidden file beside the target, unique per process and call, so concurrent writers never
// share one.
fs::path temp_path_for(const fs::path& target) {
  static std::atomic<unsigned> counter{0};
  std::string name = ".";
  name += target.filename().string();
  name += ".prism-tmp-" + std::to_string(getpid()) + "-" + std::to_string(counter++);
  return folder_of(target) / name;
}

// The written file replaces the target only once complete and on disk: a crash or error leaves
// the previous file, never a partial one.
class TempFile {
 public:
  explicit TempFile(const fs::path& target) : target_(target), temp_(temp_path_for(target)) {}
  ~TempFile() {
    if (!committed_) {
      std::error_code ec;
      fs::remove(temp_, ec);
    }
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  const fs::path& path() const { return temp_; }

  void commit() {
    const int fd = ::open(temp_.c_str(), O_RDONLY);
    if (fd < 0 || ::fsync(fd) != 0) {
      const std::string reason = std::strerror(errno);
      if (fd >= 0) ::close(fd);
      throw output_error(target_, "cannot flush the written file to disk: " + reason);
    }
    ::close(fd);
    std::error_code ec;
    fs::rename(temp_, target_, ec);
    if (ec) throw output_error(target_, "cannot replace the file: " + ec.message());
    committed_ = true;
    // Make the rename itself durable; a failure here loses nothing already written.
    if (const int dir = ::open(folder_of(target_).c_str(), O_RDONLY | O_DIRECTORY); dir >= 0) {
      ::fsync(dir);
      ::close(dir);
    }
  }

 private:
  fs::path target_;
  fs::path temp_;
  bool committed_ = false;
};

}  // namespace

Error output_error(const fs::path& path, const std::string& message) {
  return Error(ErrorKind::kOutput, message, ErrorLocation{path.string(), 0, {}});
}

void write_atomically(const fs::path& target, const std::string& format,
                      const OIIO::ImageSpec& spec, const OIIO::TypeDesc& type, const void* pixels) {
  TempFile temp(target);
  try {
    auto out = OIIO::ImageOutput::create(format);
    if (!out) throw output_error(target, "no " + format + " writer: " + OIIO::geterror());
    const bool opened = out->open(temp.path().string(), spec);
    // The folder was checked before the work; if it went away or became read-only since, say
    // so as that check does rather than with OpenImageIO's message about the temporary file.
    if (!opened) check_output_writable(target);
    const bool ok = opened && out->write_image(type, pixels) && out->close();
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

void check_finite(const std::vector<float>& values, const fs::path& path) {
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

void check_output_writable(const fs::path& path) {
  using color_detail::output_error;
  const fs::path folder = color_detail::folder_of(path);
  std::error_code ec;
  if (path.filename().empty()) throw output_error(path, "the output path names no file");
  if (!fs::exists(folder, ec)) {
    throw output_error(path, "the output folder '" + folder.string() + "' does not exist");
  }
  if (!fs::is_directory(folder, ec)) {
    throw output_error(path, "'" + folder.string() + "' is not a folder");
  }
  if (fs::is_directory(path, ec)) throw output_error(path, "the output path is a folder");
  // Creating a file is the only reliable test (permissions, read-only mounts, ACLs, quotas).
  const fs::path probe = color_detail::temp_path_for(path);
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) {
    throw output_error(path, "cannot create files in the output folder '" + folder.string() +
                                 "': " + std::strerror(errno));
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

}  // namespace prism
