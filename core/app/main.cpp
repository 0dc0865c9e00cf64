// prism's entry point: runs the command line and turns every failure into one line on stderr
// and a documented exit code. Under mpirun every rank runs this; see core/app/mpi_world.h.

#include <malloc.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>
#include <string>

#include "core/app/cli.h"
#include "core/app/mpi_world.h"
#include "core/error.h"
#include "core/huge_page_heap.h"

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

/// glibc's malloc returns big blocks to the kernel when they are freed (they come from their own
/// mmap, or the heap is trimmed), and the next render pass's blocks of the same size then fault
/// every page in again: ~6,000 page faults a 480 x 360 render with light-traced caustics, at
/// ~14 us each on the virtual machines prism is measured on. Kept instead, they are reused. (The
/// film and images have huge pages of their own: core/huge_page_allocator.h.)
void keep_freed_memory() {
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest: blocks up to 32 MiB from the heap
  mallopt(M_TRIM_THRESHOLD, 1 << 30);   // and no trimming of the heap's top below 1 GiB free
}

/// Ends the process with `code` once the command is done: every file it wrote is closed and
/// renamed into place by then, so only stdio is left to flush. The libraries' static destructors
/// (about 260 of them come with OpenImageIO) would take another 15-20 ms per command, mostly
/// faulting in code never run before; they are skipped. Sanitizer builds exit normally, since
/// LeakSanitizer reports from an exit handler.
[[noreturn]] void exit_now(int code) {
  std::fflush(stdout);
  std::fflush(stderr);
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  std::exit(code);
#else
  std::_Exit(code);
#endif
}

}  // namespace

int main(int argc, char** argv) {
  keep_freed_memory();
  // What the scene's parsing and the BVH's build allocate next, in huge pages: ~1,300 fewer
  // page faults for a CS184 mesh scene, on the single thread before the render.
  prism::advise_huge_pages_at_heap_top(size_t{16} << 20);
  int code = 0;
  {
    prism::MpiWorld world;
    code = world.exit(run(argc, argv));
    // MPI is finalised (the world's destructor) before the process ends.
  }
  exit_now(code);
}
