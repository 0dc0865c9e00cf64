// Loading the image module (color/image_io.h) in the `prism` program, and the program's
// forwarders of the functions it holds. Only the program links this file; the tests and the
// Python module link the functions themselves (prism_image_files).

#include <dlfcn.h>

#include <condition_variable>
#include <filesystem>
#include <mutex>
#include <string>
#include <system_error>

#include "color/image_io.h"
#include "color/image_io_functions.h"
#include "core/error.h"
#include "core/huge_page_heap.h"
#include "core/parallel.h"

namespace prism {
namespace {

constexpr const char* kModuleFileName = "libprism_image_io.so";
/// About what the module's libraries allocate while they load (Debian 12: ~28 MiB).
constexpr size_t kImageIoStaticHeapBytes = size_t{30} << 20;

/// The module beside the running program (/proc/self/exe, a copy's own folder for a copy),
/// whatever the working directory.
std::filesystem::path module_path() {
  std::error_code ec;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec || program.empty()) return kModuleFileName;  // the loader's search path then
  return program.parent_path() / kModuleFileName;
}

/// The module, loaded once per process by the first call that needs it.
class ImageIoModule {
 public:
  /// Throws what functions() would when the module's file is not there, without loading it: a
  /// command can say so before its work rather than after it.
  void check_present() const {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path_, ec)) throw load_error("no such file");
  }

  /// The module's functions, loading it the first time; throws Error(kInternal) naming the
  /// module when it does not load.
  const ImageIoFunctions& functions() {
    std::call_once(loaded_, [this] { load(); });
    if (functions_ == nullptr) throw load_error(failure_);
    return *functions_;
  }

 private:
  Error load_error(const std::string& why) const {
    return Error(ErrorKind::kInternal,
                 "cannot load prism's image module " + path_.string() + ": " + why +
                     " (it is built beside the prism program; rebuild with scripts/build)");
  }

  void load() {
    // The libraries' static initialisers allocate ~28 MiB from this thread's heap, mostly in
    // blocks of 2-4 KiB (OpenImageIO's string table): in huge pages, 15 page faults instead of
    // ~7,000 (core/huge_page_heap.h).
    advise_huge_pages_at_heap_top(kImageIoStaticHeapBytes);
    // The module itself is linked with -z now: one whose symbols the program does not provide
    // fails here, as a whole, rather than at some later call. RTLD_LAZY leaves the function
    // calls of the ~260 libraries it pulls in to be bound when first made (13 thousand fewer
    // symbol lookups, about 25 ms of the load). RTLD_LOCAL: its libraries stay out of the
    // program's scope.
    void* handle = dlopen(path_.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (handle == nullptr) {
      const char* message = dlerror();
      failure_ = message != nullptr ? message : "dlopen failed";
      return;
    }
    using Entry = const ImageIoFunctions* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(handle, kImageIoFunctionsSymbol));
    if (entry == nullptr) {
      failure_ = std::string("no symbol ") + kImageIoFunctionsSymbol;
      return;
    }
    const ImageIoFunctions* table = entry();
    if (table == nullptr || table->version != kImageIoFunctionsVersion ||
        table->size != sizeof(ImageIoFunctions)) {
      failure_ = "the module is from another build of prism";
      return;
    }
    functions_ = table;
  }

  const std::filesystem::path path_ = module_path();
  std::once_flag loaded_;
  std::string failure_;
  const ImageIoFunctions* functions_ = nullptr;
};

ImageIoModule& image_io_module() {
  static ImageIoModule module;
  return module;
}

const ImageIoFunctions& image_io() { return image_io_module().functions(); }

}  // namespace

void check_image_io() { image_io_module().check_present(); }

/// Where a preload's task stands; shared with the task, which may start after the preload ends.
struct ImageIoPreload::State {
  enum class Step { kQueued, kLoading, kDone, kCancelled };
  std::mutex mutex;
  std::condition_variable done;
  Step step = Step::kQueued;
};

ImageIoPreload::ImageIoPreload(int threads) {
  if (threads < 2) return;  // one thread: the task would wait for it, or add a second one
  state_ = std::make_shared<State>();
  run_beside([state = state_] {
    using Step = State::Step;
    {
      std::lock_guard lock(state->mutex);
      if (state->step != Step::kQueued) return;
      state->step = Step::kLoading;
    }
    try {
      image_io_module().functions();
    } catch (...) {
      // The first call that needs the module reports why it does not load.
    }
    std::lock_guard lock(state->mutex);
    state->step = Step::kDone;
    state->done.notify_all();
  });
}

ImageIoPreload::~ImageIoPreload() {
  if (!state_) return;
  using Step = State::Step;
  std::unique_lock lock(state_->mutex);
  if (state_->step == Step::kQueued) state_->step = Step::kCancelled;
  state_->done.wait(lock, [&] { return state_->step != Step::kLoading; });
}

namespace color_detail {

void write_exr_file(const std::filesystem::path& path, const Image& image,
                    const ImageMetadata& metadata, const ColorPipeline& pipeline,
                    const ExrOptions& options) {
  image_io().write_exr_file(path, image, metadata, pipeline, options);
}

void write_display_file(const std::filesystem::path& path, const std::string& format,
                        const Image& image, const ImageMetadata& metadata,
                        const ColorPipeline& pipeline) {
  image_io().write_display_file(path, format, image, metadata, pipeline);
}

}  // namespace color_detail

void write_display_image(const std::filesystem::path& path, const Image& image,
                         const ImageMetadata& metadata, const ColorPipeline& pipeline) {
  image_io().write_display_image(path, image, metadata, pipeline);
}

ImageFileContents read_image_file(const std::filesystem::path& path) {
  return image_io().read_image_file(path);
}

void write_state_file(const std::filesystem::path& path, const Image& image, const Film& film,
                      const ImageMetadata& metadata, const ColorPipeline& pipeline,
                      const ExrOptions& options) {
  image_io().write_state_file(path, image, film, metadata, pipeline, options);
}

StateFileContents read_state_file(const std::filesystem::path& path) {
  return image_io().read_state_file(path);
}

ImageMetadata read_state_file_attributes(const std::filesystem::path& path) {
  return image_io().read_state_file_attributes(path);
}

SceneTexturesReport load_scene_textures(Scene& scene, const ColorPipeline& pipeline) {
  // Nothing to read (the module's function returns the same empty report): a scene without
  // textures does not wait here for the module its render loads beside its samples.
  if (scene.textures.empty()) return {};
  return image_io().load_scene_textures(scene, pipeline);
}

}  // namespace prism
