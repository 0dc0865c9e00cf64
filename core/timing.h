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

}  // namespace prism
