// Assembly benchmark (issue: foundation): residual and tangent assembly of the 3D ANCF cable,
// time per element (wall time of the whole assembly over N; under mpirun, of all ranks together)
// on one core for N = 1e3 .. 1e6 (the memory of a static solve is measured by
// study_catenary on a 1 km tether). Prints JSON lines; no assertion.
// Rerun: make bench_assembly && ./tests/benchmarks/bench_assembly [-max_elements 1000000]
#include <petscsys.h>

#include <cmath>

#include "support/Scenes.hpp"

using namespace strand;
using namespace strand::testing;

namespace {
model::SceneDescription hanging(int n) {
  auto sc = cantilever(3, n, 1.0);  // clamped at 0, gravity: a 3D cable cantilever (L = 1 m, d = 10 mm steel)
  sc.bodies[0].section.set("A", M_PI * 0.25 * 1e-4);
  sc.bodies[0].section.set("I", M_PI * 1e-8 / 64.0);
  sc.loads.gravity = {0, 0, -9.81};
  return sc;
}
}  // namespace

int main(int argc, char** argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  PetscInt maxN = 1000000;
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-max_elements", &maxN, nullptr));
  PetscMPIInt ranks;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &ranks));
  for (int n = 1000; n <= maxN; n *= 10) {
    solvers::Problem p(PETSC_COMM_WORLD, hanging(n));
    Vec X, R;
    Mat J;
    PetscCall(p.dofs().createVector(&X));
    PetscCall(VecDuplicate(X, &R));
    PetscCall(p.dofs().createMatrix(&J, nullptr));
    PetscCall(p.assembler().initialState(X));
    PetscCall(VecShift(X, 1e-3));  // a slightly deformed, stressed state
    double times[2] = {0, 0};
    int reps[2] = {0, 0};
    for (int which = 0; which < 2; ++which) {
      PetscLogDouble t0, t1;
      PetscCall(PetscTime(&t0));
      int more = 1;
      do {
        if (which == 0) PetscCall(p.assembler().staticResidual(X, 1.0, R));
        else PetscCall(p.assembler().staticJacobian(X, 1.0, J));
        ++reps[which];
        PetscCall(PetscTime(&t1));
        // one decision for all ranks (each rank's own clock would stop them at different
        // repetitions, and the next collective assembly would wait forever)
        more = t1 - t0 < 0.5 || reps[which] < 3;
        PetscCallMPI(MPI_Bcast(&more, 1, MPI_INT, 0, PETSC_COMM_WORLD));
      } while (more);
      times[which] = (t1 - t0) / reps[which];
    }
    PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                          "{\"bench\": \"assembly\", \"element\": \"AncfCable3d\", \"gauss_points\": 5, \"ranks\": %d, \"elements\": %d, "
                          "\"residual_us_per_element\": %.4f, \"tangent_us_per_element\": %.4f, "
                          "\"residual_plus_tangent_us_per_element\": %.4f}\n",
                          ranks, n, 1e6 * times[0] / n, 1e6 * times[1] / n, 1e6 * (times[0] + times[1]) / n));
    VecDestroy(&X);
    VecDestroy(&R);
    MatDestroy(&J);
  }
  PetscCall(PetscFinalize());
  return 0;
}
