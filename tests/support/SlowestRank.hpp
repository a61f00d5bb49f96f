#pragma once
// Wall time of work that every rank does at once, as the benchmarks report it: the slowest rank's
// seconds, from a common start (a barrier) to the rank's own end.
#include <mpi.h>

namespace strand::testing {

template <class Work>
double slowestRankSeconds(MPI_Comm comm, Work work) {
  MPI_Barrier(comm);
  const double start = MPI_Wtime();
  work();
  const double mine = MPI_Wtime() - start;
  double slowest;
  MPI_Allreduce(&mine, &slowest, 1, MPI_DOUBLE, MPI_MAX, comm);
  return slowest;
}

}  // namespace strand::testing
