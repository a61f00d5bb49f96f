// gtest main for Strand tests: PETSc/SLEPc initialized once, only rank 0 prints gtest output.
#include <gtest/gtest.h>
#include <slepcsys.h>

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  PetscCall(SlepcInitialize(&argc, &argv, nullptr, nullptr));
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  int result = RUN_ALL_TESTS();
  // Any rank failing fails the run.
  int global = 0;
  MPI_Allreduce(&result, &global, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  PetscCall(SlepcFinalize());
  return global;
}
