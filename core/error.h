#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace prism {

/// What went wrong, which decides the process exit code (see README "Exit codes").
enum class ErrorKind {
  kUsage,     ///< bad command line or option value: exit 2
  kInput,     ///< bad scene or mesh file, dangling reference, bad number: exit 2
  kOutput,    ///< output cannot be written: exit 3
  kResource,  ///< out of memory or another resource: exit 3
  kInternal,  ///< a broken invariant inside prism: exit 1
};

/// Where in an input an error was found. Every field is optional (empty / 0 when unknown).
struct ErrorLocation {
  std::string file;
  int line = 0;
  std::string element;  ///< e.g. "<polylist material=\"white\">" or "materials[2].albedo"
};

/// The one exception type for configuration, input and I/O failures. Its what() is the
/// one-line message printed by main: "file:line: element: message".
class Error : public std::runtime_error {
 public:
  Error(ErrorKind kind, const std::string& message, ErrorLocation location = {});

  ErrorKind kind() const { return kind_; }
  const ErrorLocation& location() const { return location_; }
  const std::string& message() const { return message_; }
  /// The documented process exit code for this error kind (2, 3 or 1).
  int exit_code() const;

 private:
  ErrorKind kind_;
  ErrorLocation location_;
  std::string message_;
};

/// Exit codes of the prism program.
inline constexpr int kExitSuccess = 0;
inline constexpr int kExitInternal = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitOutput = 3;

[[noreturn]] void fail_check(const char* condition, const char* file, int line);

}  // namespace prism

/// Internal invariant, checked in every build type. Failure throws ErrorKind::kInternal.
#define PRISM_CHECK(condition) \
  ((condition) ? (void)0 : ::prism::fail_check(#condition, __FILE__, __LINE__))
