#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace prism {

/// 64-bit FNV-1a of `bytes`, continuing from `hash` (start with kFnvOffset). For telling whether
/// data changed (checkpoints, parts, scene files), not for security: five lines of a public
/// algorithm instead of a dependency.
inline constexpr uint64_t kFnvOffset = 0xcbf29ce484222325ull;
inline uint64_t fnv1a64(std::span<const std::byte> bytes, uint64_t hash = kFnvOffset) {
  for (const std::byte b : bytes) hash = (hash ^ uint64_t(b)) * 0x100000001b3ull;
  return hash;
}
inline uint64_t fnv1a64(std::string_view text, uint64_t hash = kFnvOffset) {
  return fnv1a64(std::as_bytes(std::span<const char>(text.data(), text.size())), hash);
}

/// FNV-1a over 64-bit little-endian words instead of bytes (the tail bytes one by one): eight
/// times fewer steps for the large buffers of render state files, where it tells a damaged file
/// from an intact one.
inline uint64_t fnv1a64_words(std::span<const std::byte> bytes, uint64_t hash = kFnvOffset) {
  const size_t words = bytes.size() / 8;
  for (size_t i = 0; i < words; ++i) {
    uint64_t w;
    __builtin_memcpy(&w, bytes.data() + 8 * i, 8);
    hash = (hash ^ w) * 0x100000001b3ull;
  }
  return fnv1a64(bytes.subspan(8 * words), hash);
}

/// `value` as 16 lower-case hexadecimal digits.
std::string hex64(uint64_t value);

}  // namespace prism
