#include "core/error.h"

namespace prism {
namespace {

std::string format_what(const std::string& message, const ErrorLocation& location) {
  std::string out;
  if (!location.file.empty()) {
    out += location.file;
    if (location.line > 0) out += ":" + std::to_string(location.line);
    out += ": ";
  }
  if (!location.element.empty()) out += location.element + ": ";
  out += message;
  return out;
}

}  // namespace

Error::Error(ErrorKind kind, const std::string& message, ErrorLocation location)
    : std::runtime_error(format_what(message, location)),
      kind_(kind),
      location_(std::move(location)),
      message_(message) {}

int Error::exit_code() const {
  switch (kind_) {
    case ErrorKind::kUsage:
    case ErrorKind::kInput:
      return kExitBadInput;
    case ErrorKind::kOutput:
    case ErrorKind::kResource:
      return kExitOutput;
    case ErrorKind::kInternal:
      return kExitInternal;
  }
  return kExitInternal;
}

void fail_check(const char* condition, const char* file, int line) {
  throw Error(ErrorKind::kInternal, std::string("internal check failed: ") + condition,
              ErrorLocation{file, line, {}});
}

}  // namespace prism
