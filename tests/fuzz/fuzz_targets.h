#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace prism::fuzz {

/// One fuzz target: a parser prism owns, fed arbitrary bytes (tests/fuzz/README.md).
///
/// Contract of every `run`: it returns normally for any input, valid or not. prism::Error (bad
/// input, reported to the user in one line) is caught inside and is a pass; any other exception,
/// a crash, a sanitizer report, more than 2 s or more than 2 GB is a bug in prism. Inputs a
/// loader reads from a file are written to a per-process temporary folder first (one path per
/// target, reused). Not thread-safe.
struct Target {
  const char* name;         ///< the corpus folder's name: tests/fuzz/corpus/<name>/
  const char* description;  ///< what the bytes are, one line
  void (*run)(const uint8_t* data, size_t size);
};

/// Every target, in the order `scripts/fuzz --list` prints them.
const std::vector<Target>& targets();

/// The target called `name`, or null.
const Target* find_target(const std::string& name);

}  // namespace prism::fuzz
