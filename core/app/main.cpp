// prism's entry point: runs the command line and turns every failure into one line on stderr
// and a documented exit code. Under mpirun every rank runs this; see core/app/mpi_world.h.

#include <algorithm>
#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "core/app/cli.h"
#include "core/app/mpi_world.h"
#include "core/error.h"

namespace {

void print_error(std::string message) {
  std::replace(message.begin(), message.end(), '\n', ' ');
  std::fprintf(stderr, "prism: error: %s\n", message.c_str());
}

/// Under MPI a rank's own failure names the rank.
std::string with_rank(const std::string& message) {
  if (prism::mpi::size() <= 1) return message;
  return "rank " + std::to_string(prism::mpi::rank()) + ": " + message;
}

int run(int argc, char** argv) {
  try {
    return prism::run_cli(argc, argv);
  } catch (const prism::RankError& e) {
    // Every rank knows it: rank 0 says it once.
    if (prism::mpi::rank() == 0) print_error(e.what());
    return e.code();
  } catch (const prism::Error& e) {
    print_error(with_rank(e.what()));
    return e.exit_code();
  } catch (const std::bad_alloc&) {
    print_error(with_rank("out of memory"));
    return prism::kExitOutput;
  } catch (const std::exception& e) {
    print_error(with_rank(std::string("internal error: ") + e.what()));
    return prism::kExitInternal;
  } catch (...) {
    print_error(with_rank("internal error: unknown exception"));
    return prism::kExitInternal;
  }
}

}  // namespace

int main(int argc, char** argv) {
  prism::MpiWorld world;
  return world.exit(run(argc, argv));
}
