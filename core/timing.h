#pragma once

#include <chrono>
#include <utility>

namespace prism {

/// Calls f() and returns its wall time in milliseconds.
template <typename F>
double time_ms(F&& f) {
  const auto start = std::chrono::steady_clock::now();
  std::forward<F>(f)();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

/// Seconds of wall time from `start` (a steady_clock reading) to now.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace prism
