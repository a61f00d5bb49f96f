// Work-precision study of the axially moving string (issue 35; docs/validation.md, "Variable-length
// ALE cables"): the first frequency f1 = (c^2 - v^2)/(2 l c) = 22.6857 Hz of seed 000 sec. 4.1
// (l = 1 m, steel wire r = 1 mm, v = 10 m/s) against the wall time that finds it, two ways:
//   modes     the gyroscopic eigenproblem about the steady flow (ModalSolver, SLEPc PEP), once;
//   newmark   a time integration started in the exact first mode, f1 from the midpoint's zero
//             crossings over 5 periods (tests/support/MovingString.hpp), at 100, 400 and 2000 steps
//             per period;
// for AleCable2d and AleCable3d with N = 2, 4, 8, 16 elements. One JSON line per run:
//   study_moving_string > docs/data/moving_string.jsonl
// (A fixed-length Lagrangian cable cannot model the span: its material leaves it; the belt
// machinery of issue 34 could, as the free span of a belt loop, and is not in this study.)
#include <petsctime.h>
#include <slepcsys.h>

#include <cmath>

#include "strand/solvers/ModalSolver.hpp"
#include "support/MovingString.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

double modalFirstFrequency(const MovingString& s, int elements, const char* kind) {
  model::SceneDescription sc = stringScene(s, elements, 1e-3, 1e-2, kind);
  sc.analysis = model::Analysis::Modes;
  solvers::Problem p(PETSC_COMM_WORLD, sc);
  Vec X;
  PetscCallAbort(PETSC_COMM_WORLD, p.dofs().createVector(&X));
  PetscCallAbort(PETSC_COMM_WORLD, p.assembler().initialState(X));
  solvers::ModalOptions opt;
  opt.count = 1;
  solvers::ModalResult r;
  double f = std::nan("");
  {
    solvers::ModalSolver m(p.assembler(), opt);
    PetscCallAbort(PETSC_COMM_WORLD, m.solve(X, &r));
    if (!r.omega.empty()) f = r.omega[0] / (2.0 * M_PI);
  }
  solvers::destroyModes(&r);
  VecDestroy(&X);
  return f;
}

void report(const char* kind, const char* method, int elements, int stepsPerPeriod, double f, double f1, double wall) {
  PetscCallAbort(PETSC_COMM_WORLD,
                 PetscPrintf(PETSC_COMM_WORLD,
                             "{\"study\": \"moving_string\", \"kind\": \"%s\", \"method\": \"%s\", \"label\": \"%s %s%s\", "
                             "\"elements\": %d, \"steps_per_period\": %d, \"f1\": %.9f, \"error\": %.6e, \"wall_s\": %.6f}\n",
                             kind, method, kind, method,
                             stepsPerPeriod > 0 ? (" " + std::to_string(stepsPerPeriod) + "/T").c_str() : "", elements,
                             stepsPerPeriod, f, std::fabs(f / f1 - 1.0), wall));
}

}  // namespace

int main(int argc, char** argv) {
  PetscCall(SlepcInitialize(&argc, &argv, nullptr, nullptr));
  const MovingString s;
  modalFirstFrequency(s, 2, "AleCable2d");  // warm-up: the first solve sets up SLEPc and the caches
  for (const char* kind : {"AleCable2d", "AleCable3d"})
    for (int n : {2, 4, 8, 16}) {
      PetscLogDouble t0, t1;
      PetscCall(PetscTime(&t0));
      const double fm = modalFirstFrequency(s, n, kind);
      PetscCall(PetscTime(&t1));
      report(kind, "modes", n, 0, fm, s.f1, t1 - t0);
      for (int spp : {100, 400, 2000}) {
        PetscCall(PetscTime(&t0));
        const double f = firstFrequency(s, n, spp, kind);
        PetscCall(PetscTime(&t1));
        report(kind, "newmark", n, spp, f, s.f1, t1 - t0);
      }
    }
  PetscCall(SlepcFinalize());
  return 0;
}
