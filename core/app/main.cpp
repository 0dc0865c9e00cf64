// prism's entry point: runs the command line and turns every failure into one line on stderr
// and a documented exit code.

#include <algorithm>
#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "core/app/cli.h"
#include "core/error.h"

namespace {

void print_error(std::string message) {
  std::replace(message.begin(), message.end(), '\n', ' ');
  std::fprintf(stderr, "prism: error: %s\n", message.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return prism::run_cli(argc, argv);
  } catch (const prism::Error& e) {
    print_error(e.what());
    return e.exit_code();
  } catch (const std::bad_alloc&) {
    print_error("out of memory");
    return prism::kExitOutput;
  } catch (const std::exception& e) {
    print_error(std::string("internal error: ") + e.what());
    return prism::kExitInternal;
  } catch (...) {
    print_error("internal error: unknown exception");
    return prism::kExitInternal;
  }
}
