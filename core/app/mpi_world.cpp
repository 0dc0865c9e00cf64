#include "core/app/mpi_world.h"

#include <mpi.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <new>

namespace prism {
namespace {

bool initialized = false;
int world_rank = 0;
int world_size = 1;
int open_jobs = 0;

/// Whether an MPI launcher started this process: mpirun/mpiexec (Open MPI) or a PMIx launcher
/// such as `srun --mpi=pmix`.
bool launched_by_mpi() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMIX_RANK") != nullptr;
}

ErrorKind kind_of_exit_code(int code) {
  switch (code) {
    case kExitBadInput:
      return ErrorKind::kInput;
    case kExitOutput:
      return ErrorKind::kOutput;
    default:
      return ErrorKind::kInternal;
  }
}

}  // namespace

MpiWorld::MpiWorld() {
  if (!launched_by_mpi()) return;
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  initialized = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &world_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &world_size);
}

MpiWorld::~MpiWorld() {
  if (initialized) MPI_Finalize();
  initialized = false;
  world_rank = 0;
  world_size = 1;
}

int MpiWorld::exit(int code) {
  if (open_jobs > 0) mpi::abort_all(code == kExitSuccess ? kExitInternal : code);
  return code;
}

namespace mpi {

int rank() { return world_rank; }
int size() { return world_size; }
bool active() { return initialized; }

std::vector<std::string> all_gather(const std::string& text) {
  if (!initialized) return {text};
  const int length = static_cast<int>(text.size());
  std::vector<int> lengths(static_cast<size_t>(world_size));
  MPI_Allgather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, MPI_COMM_WORLD);
  std::vector<int> offsets(static_cast<size_t>(world_size), 0);
  for (size_t r = 1; r < offsets.size(); ++r) offsets[r] = offsets[r - 1] + lengths[r - 1];
  std::string all(size_t(offsets.back() + lengths.back()), '\0');
  MPI_Allgatherv(text.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(),
                 MPI_CHAR, MPI_COMM_WORLD);
  std::vector<std::string> texts;
  for (size_t r = 0; r < offsets.size(); ++r) texts.push_back(all.substr(offsets[r], lengths[r]));
  return texts;
}

std::string broadcast(const std::string& text) {
  if (!initialized) return text;
  int length = static_cast<int>(text.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::string out = world_rank == 0 ? text : std::string(size_t(length), '\0');
  MPI_Bcast(out.data(), length, MPI_CHAR, 0, MPI_COMM_WORLD);
  return out;
}

void abort_all(int code) {
  if (!initialized) std::exit(code);
  // The launcher forwards output asynchronously: MPI_Abort at once can lose the error line
  // printed just before it.
  std::fflush(stdout);
  std::fflush(stderr);
  usleep(300 * 1000);
  MPI_Abort(MPI_COMM_WORLD, code);
  std::_Exit(code);  // MPI_Abort does not return
}

}  // namespace mpi

MpiJob::MpiJob() : counted_(world_size > 1) {
  if (counted_) ++open_jobs;
}
MpiJob::~MpiJob() = default;
void MpiJob::close() {
  if (counted_ && open_jobs > 0) --open_jobs;
  counted_ = false;
}

RankError::RankError(int rank, int exit_code, const std::string& message)
    : Error(kind_of_exit_code(exit_code), "rank " + std::to_string(rank) + ": " + message),
      rank_(rank),
      code_(exit_code) {}

ErrorReport current_error_report() {
  try {
    throw;
  } catch (const Error& e) {
    return {e.exit_code(), e.what()};
  } catch (const std::bad_alloc&) {
    return {kExitOutput, "out of memory"};
  } catch (const std::exception& e) {
    return {kExitInternal, std::string("internal error: ") + e.what()};
  } catch (...) {
    return {kExitInternal, "internal error: unknown exception"};
  }
}

}  // namespace prism
