// The MPI world of `mpirun -n N aggpack sweep|repose --seeds` (see mpi_world.h).

#include "mpi_world.h"

#include <cstdlib>
#include <exception>
#include <string>

#include "aggpack/core/error.h"

#ifdef AGGPACK_HAS_MPI
// The C API only (OpenMPI's and MPICH's mpi.h otherwise pull in the removed C++ bindings).
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace aggpack::cli {

namespace {

// The number of ranks mpirun launched, from its environment (OpenMPI, then PMI/PMIx launchers).
std::size_t launched_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_SIZE", "PMI_SIZE"}) {
    if (const char* value = std::getenv(name)) {
      const long size = std::strtol(value, nullptr, 10);
      if (size > 0) return static_cast<std::size_t>(size);
    }
  }
  return 1;
}

}  // namespace

void run_on_mpi_world(const std::function<void(const MpiWorld&)>& work,
                      const std::function<void()>& finish) {
  const std::size_t launched = launched_size();
  if (launched <= 1) {
    work(MpiWorld{});
    finish();
    return;
  }
#ifndef AGGPACK_HAS_MPI
  throw InvalidInput("mpirun -n", std::to_string(launched),
                     "1: this aggpack is built without MPI (cmake -DAGGPACK_WITH_MPI=ON with "
                     "libopenmpi-dev); use --case K --of N per process and `aggpack merge`");
#else
  int is_initialized = 0;
  MPI_Initialized(&is_initialized);
  if (is_initialized == 0) MPI_Init(nullptr, nullptr);
  int rank = 0;
  int size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  std::exception_ptr failure;
  try {
    work(MpiWorld{static_cast<std::size_t>(rank), static_cast<std::size_t>(size)});
  } catch (...) {
    failure = std::current_exception();
  }
  // Every rank reaches this point, failed or not: the barrier that tells rank 0 all are done.
  const int ok = failure ? 0 : 1;
  int failed_ranks = 0;
  const int local_failed = 1 - ok;
  MPI_Allreduce(&local_failed, &failed_ranks, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  if (rank == 0 && failed_ranks == 0) {
    try {
      finish();
    } catch (...) {
      failure = std::current_exception();
    }
  }
  MPI_Finalize();
  if (failure) std::rethrow_exception(failure);
  if (rank == 0 && failed_ranks > 0) {
    throw LimitExceeded("mpirun ranks that failed", std::to_string(failed_ranks),
                        "0 (their errors are above; the runs that finished are in runs/: run "
                        "the rest with --case K --of N, then `aggpack merge`)");
  }
#endif
}

}  // namespace aggpack::cli
