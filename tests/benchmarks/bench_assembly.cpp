// Assembly benchmark: residual and tangent assembly per element, for every element kind, time per
// element (wall time of the whole assembly over N; under mpirun, of all ranks together) on one core.
//  - AncfCable3d (the default, and the only kind that older builds know): a 3D cable cantilever
//    (L = 1 m, d = 10 mm steel) under gravity, N = 1e3 .. 1e6 (-max_elements);
//  - with -kinds all: also AncfCable2d, AncfBeam2dShear and AncfBeam2dLinear (selective
//    integration, 0.1 x 0.02 m steel section) on a 2D cantilever of the same N.
// The state is slightly deformed (u = 1e-3 everywhere). Prints JSON lines; no assertion.
// Rerun: cmake --build build --target bench_assembly && ./build/tests/benchmarks/bench_assembly [-max_elements 1000000] [-kinds all]
// The cable before and after a change, interleaved: tests/benchmarks/compare_assembly.py.
#include <petscsys.h>

#include <cmath>
#include <cstring>
#include <string>

#include "support/Scenes.hpp"
#include "support/ShearBeams.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

model::SceneDescription hanging(int n) {
  auto sc = cantilever(3, n, 1.0);  // clamped at 0, gravity: a 3D cable cantilever (L = 1 m, d = 10 mm steel)
  Section s;
  s.A = M_PI * 0.25 * 1e-4;
  s.I = M_PI * 1e-8 / 64.0;
  sc.bodies[0] = straightBody("beam", 3, n, {0, 0, 0}, {1, 0, 0}, s);
  sc.loads.gravity = {0, 0, -9.81};
  return sc;
}

model::SceneDescription planar(const std::string& kind, int n) {
  model::SceneDescription sc;
  if (kind == "AncfCable2d") {
    Section s;
    s.A = 2e-3;
    s.I = 6.67e-8;
    sc = cantilever(2, n, 1.0, s);
  } else {
    RectangleSection s;
    s.height = 0.02;
    sc = shearCantilever(kind, n, 1.0, s);
  }
  sc.loads.gravity = {0, -9.81, 0};
  return sc;
}

PetscErrorCode measure(const model::SceneDescription& sc, const char* kind, int n, int ranks) {
  PetscFunctionBeginUser;
  solvers::Problem p(PETSC_COMM_WORLD, sc);
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
                        "{\"bench\": \"assembly\", \"element\": \"%s\", \"ranks\": %d, \"elements\": %d, "
                        "\"coordinates\": %d, \"residual_us_per_element\": %.4f, \"tangent_us_per_element\": %.4f, "
                        "\"residual_plus_tangent_us_per_element\": %.4f}\n",
                        kind, ranks, n, p.model().numDofs(), 1e6 * times[0] / n, 1e6 * times[1] / n,
                        1e6 * (times[0] + times[1]) / n));
  PetscCall(VecDestroy(&X));
  PetscCall(VecDestroy(&R));
  PetscCall(MatDestroy(&J));
  PetscFunctionReturn(0);
}

}  // namespace

int main(int argc, char** argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  PetscInt maxN = 1000000, minN = 1000;
  char kinds[64] = "AncfCable3d";
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-max_elements", &maxN, nullptr));
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-min_elements", &minN, nullptr));
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-kinds", kinds, sizeof(kinds), nullptr));
  PetscMPIInt ranks;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &ranks));
  for (int n = minN; n <= maxN; n *= 10) {
    PetscCall(measure(hanging(n), "AncfCable3d", n, ranks));
    if (std::strcmp(kinds, "all") == 0)
      for (const char* kind : {"AncfCable2d", "AncfBeam2dShear", "AncfBeam2dLinear"}) PetscCall(measure(planar(kind, n), kind, n, ranks));
  }
  PetscCall(PetscFinalize());
  return 0;
}
