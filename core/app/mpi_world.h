#pragma once

#include <string>
#include <vector>

#include "core/error.h"

namespace prism {

/// The processes of this run. prism is one binary with and without mpirun: MpiWorld (one, in
/// main()) initialises MPI (MPI_THREAD_FUNNELED: only the main thread makes MPI calls) only
/// when the process was started by an MPI launcher (OMPI_COMM_WORLD_SIZE or PMIX_RANK in the
/// environment), and finalises it when destroyed. Otherwise there is one rank, 0, and no MPI
/// call is ever made, so plain `prism` neither prints nor waits for anything of MPI's.
class MpiWorld {
 public:
  MpiWorld();
  ~MpiWorld();
  MpiWorld(const MpiWorld&) = delete;
  MpiWorld& operator=(const MpiWorld&) = delete;

  /// The process exit code for `code`: returns it, unless an MpiJob is open (a rank leaving a
  /// distributed render alone, on an error): then every process of the job ends at once with
  /// `code` (MPI_Abort), since the others would wait for this one forever.
  int exit(int code);
};

namespace mpi {

/// This process's rank in [0, size()): 0 without MPI.
int rank();
/// The number of processes of the run: 1 without MPI.
int size();
/// Whether MPI is initialised (the process was started by an MPI launcher).
bool active();

/// Every rank's `text`, in rank order. Collective: every rank must call it.
std::vector<std::string> all_gather(const std::string& text);
/// Rank 0's `text` on every rank. Collective: every rank must call it.
std::string broadcast(const std::string& text);

/// Ends every process of the run with `code` at once (MPI_Abort), after giving the launcher a
/// moment to forward what this process printed. Without MPI: std::exit(code).
[[noreturn]] void abort_all(int code);

}  // namespace mpi

/// While open, the ranks depend on each other (a distributed render): a rank whose command
/// ends without close() (an exception) ends the whole job (MpiWorld::exit()). Only meaningful
/// under MPI; harmless otherwise.
class MpiJob {
 public:
  MpiJob();
  ~MpiJob();
  MpiJob(const MpiJob&) = delete;
  MpiJob& operator=(const MpiJob&) = delete;
  /// The ranks finished together: they may now exit with their own codes.
  void close();

 private:
  bool counted_;
};

/// An error every rank of the run knows (ranks agree on it collectively): rank 0 prints it as
/// "rank N: message" naming the rank it happened on, every rank exits with its code, and no
/// rank aborts the others.
class RankError : public Error {
 public:
  RankError(int rank, int exit_code, const std::string& message);
  int rank() const { return rank_; }
  int code() const { return code_; }

 private:
  int rank_;
  int code_;
};

/// The exit code and one-line message of the exception being handled (call inside a catch
/// block): Error's, out of memory (3), or an internal error (1).
struct ErrorReport {
  int exit_code = kExitInternal;
  std::string message;
};
ErrorReport current_error_report();

}  // namespace prism
