#include "accel/embree/embree_device.h"

namespace prism {
namespace {

const char* code_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE:
      return "no error";
    case RTC_ERROR_UNKNOWN:
      return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
  }
  return "unknown error";
}

// ThreadSanitizer builds (docs/RELIABILITY.md) give Embree one thread. Embree builds on the
// workers of Debian's oneTBB, which is not instrumented: TSan cannot see the synchronisation that
// hands their results to the calling thread, and reports every block a worker allocated and the
// caller later frees (and every sphere bound a worker computed) as a race. On one thread Embree
// runs its builds on the calling thread, and TSan still sees every access prism makes to Embree's
// results from prism's own threads. Other builds leave the thread count to oneTBB.
#if defined(__SANITIZE_THREAD__)
constexpr const char* kDeviceConfig = "threads=1";
#else
constexpr const char* kDeviceConfig = nullptr;
#endif

}  // namespace

Error embree_error(RTCError code, const std::string& message) {
  const ErrorKind kind =
      code == RTC_ERROR_OUT_OF_MEMORY ? ErrorKind::kResource : ErrorKind::kInternal;
  std::string text = std::string("Embree: ") + code_name(code);
  if (!message.empty()) text += ": " + message;
  return Error(kind, text, ErrorLocation{{}, 0, "accelerator 'embree'"});
}

EmbreeDevice::EmbreeDevice() {
  device_ = rtcNewDevice(kDeviceConfig);
  if (device_ == nullptr) {
    throw embree_error(rtcGetDeviceError(nullptr), "cannot create a device");
  }
  rtcSetDeviceErrorFunction(device_, &EmbreeDevice::on_error, this);
  rtcSetDeviceMemoryMonitorFunction(device_, &EmbreeDevice::on_memory, this);
}

EmbreeDevice::~EmbreeDevice() {
  if (device_ != nullptr) rtcReleaseDevice(device_);
}

void EmbreeDevice::throw_pending_error(const std::string& during) {
  std::optional<Error> error;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    error.swap(first_error_);
  }
  if (error) throw Error(error->kind(), during + ": " + error->message(), error->location());
}

size_t EmbreeDevice::bytes_in_use() const {
  const int64_t b = bytes_.load(std::memory_order_relaxed);
  return b > 0 ? static_cast<size_t>(b) : 0;
}

void EmbreeDevice::on_error(void* user, RTCError code, const char* message) {
  if (code == RTC_ERROR_NONE) return;
  auto* self = static_cast<EmbreeDevice*>(user);
  const std::lock_guard<std::mutex> lock(self->mutex_);
  if (!self->first_error_) self->first_error_ = embree_error(code, message ? message : "");
}

bool EmbreeDevice::on_memory(void* user, ssize_t bytes, bool /*post*/) {
  static_cast<EmbreeDevice*>(user)->bytes_.fetch_add(bytes, std::memory_order_relaxed);
  return true;  // never veto: limits are the operating system's business
}

}  // namespace prism
