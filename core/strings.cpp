#include "core/strings.h"

#include <cstdio>

#include "core/hash.h"

namespace prism {

std::string to_lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
  }
  return out;
}

std::string lower_case_extension(const std::filesystem::path& path) {
  return to_lower(path.extension().string());
}

std::string join(std::span<const std::string> items, std::string_view separator,
                 std::string_view if_empty) {
  if (items.empty()) return std::string(if_empty);
  std::string out = items.front();
  for (size_t i = 1; i < items.size(); ++i) {
    out += separator;
    out += items[i];
  }
  return out;
}

std::string hex64(uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(value));
  return text;
}

}  // namespace prism
