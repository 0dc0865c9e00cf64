#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace prism {

/// `text` with the ASCII letters A-Z in lower case; every other byte (UTF-8 included) as it is.
std::string to_lower(std::string_view text);

/// The extension of `path` with its dot, in lower case (".exr" for "Out.EXR"); "" for none.
std::string lower_case_extension(const std::filesystem::path& path);

/// The items in order with `separator` between them ("a, b, c"); `if_empty` when there are
/// none (messages say "(none)" rather than nothing).
std::string join(std::span<const std::string> items, std::string_view separator = ", ",
                 std::string_view if_empty = "");

}  // namespace prism
