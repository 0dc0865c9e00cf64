#pragma once

#include <embree3/rtcore.h>

#include <atomic>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>

#include "core/error.h"

namespace prism {

/// An Embree device whose error callback and memory monitor report into prism: the first error
/// Embree raises is kept as a prism::Error (kResource for out-of-memory, kInternal otherwise)
/// until throw_pending_error() throws it. The callbacks may run on any of Embree's threads.
class EmbreeDevice {
 public:
  /// Creates the device; throws Error if Embree cannot (e.g. unsupported CPU).
  EmbreeDevice();
  ~EmbreeDevice();
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;

  RTCDevice handle() const { return device_; }
  /// Throws the first error reported since the last call, prefixed with `during`; clears it.
  void throw_pending_error(const std::string& during);
  /// Bytes Embree currently holds, as its memory monitor reported them.
  size_t bytes_in_use() const;

 private:
  static void on_error(void* user, RTCError code, const char* message);
  static bool on_memory(void* user, ssize_t bytes, bool post);

  RTCDevice device_ = nullptr;
  std::mutex mutex_;
  std::optional<Error> first_error_;
  std::atomic<int64_t> bytes_{0};
};

/// Maps an Embree error code to the prism error it becomes.
Error embree_error(RTCError code, const std::string& message);

}  // namespace prism
