#pragma once
// `mpirun -n N aggpack sweep|repose --seeds ...` (issue 15 item 6): each rank runs the share of
// `--case rank+1 --of N`, and rank 0 merges once every rank is done. MPI is started only when the
// process was launched by mpirun with more than one rank, so a plain `aggpack` never touches it.

#include <cstddef>
#include <functional>

namespace aggpack::cli {

/// The MPI world of this process: size 1 (rank 0) when not launched by mpirun.
struct MpiWorld {
  std::size_t rank = 0;
  std::size_t size = 1;
  [[nodiscard]] bool is_split() const { return size > 1; }
};

/// Runs `work` on every rank of the world mpirun started (MPI_Init before, MPI_Finalize after),
/// then, when every rank's `work` succeeded, `finish` on rank 0 only. A rank whose work threw
/// rethrows its error after the others are done; rank 0 then reports the failed ranks instead of
/// finishing. Outside mpirun (or with one rank): `work` then `finish` in this process.
/// \throw InvalidInput when launched by mpirun with several ranks but built without MPI.
void run_on_mpi_world(const std::function<void(const MpiWorld&)>& work,
                      const std::function<void()>& finish);

}  // namespace aggpack::cli
