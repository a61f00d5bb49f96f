// The memory bandwidth one rank gets when all ranks stream at once: the ceiling of the parallel
// ratio for memory-bound work (vector updates, triangular sweeps, sparse products).
//
// Every rank streams over its own vectors (default 4e6 doubles, 32 MB each, far above the caches):
// y += a x (PETSc VecAXPY: 24 bytes per entry) and y = x (VecCopy: 16 bytes), repeated, with a
// barrier before and after. Prints one JSON line: ranks and the per-rank bandwidths in GB/s (the
// slowest rank's). Run with mpirun -n 1 and -n 2 (parallel_ratio.py does): when two ranks each get
// a fraction f of the one-rank bandwidth, a memory-bound part of a step scales as 1 / (2 f)
// instead of 1/2.
//   bench_memory_bandwidth [-n 4000000] [-repeat 20]
#include <petscvec.h>

#include <cstdio>

#include "support/SlowestRank.hpp"

int main(int argc, char** argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  PetscInt n = 4000000, repeat = 20;
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-n", &n, nullptr));
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-repeat", &repeat, nullptr));
  PetscMPIInt ranks;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &ranks));
  Vec x, y;
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, &x));
  PetscCall(VecDuplicate(x, &y));
  PetscCall(VecSet(x, 1.0));
  PetscCall(VecSet(y, 2.0));
  PetscCall(VecAXPY(y, 1e-9, x));  // touch both once before timing
  using strand::testing::slowestRankSeconds;
  const double axpy = slowestRankSeconds(PETSC_COMM_WORLD, [&] {
    for (PetscInt i = 0; i < repeat; ++i) PetscCallAbort(PETSC_COMM_SELF, VecAXPY(y, 1e-9, x));
  });
  const double copy = slowestRankSeconds(PETSC_COMM_WORLD, [&] {
    for (PetscInt i = 0; i < repeat; ++i) PetscCallAbort(PETSC_COMM_SELF, VecCopy(x, y));
  });
  const double gb = 1e-9 * static_cast<double>(n) * static_cast<double>(repeat) * sizeof(PetscScalar);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                        "{\"bench\": \"memory_bandwidth\", \"ranks\": %d, \"doubles_per_rank\": %d, \"repeat\": %d, "
                        "\"axpy_gb_per_s_per_rank\": %.3f, \"copy_gb_per_s_per_rank\": %.3f}\n",
                        static_cast<int>(ranks), static_cast<int>(n), static_cast<int>(repeat), 3.0 * gb / axpy,
                        2.0 * gb / copy));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&y));
  PetscCall(PetscFinalize());
  return 0;
}
