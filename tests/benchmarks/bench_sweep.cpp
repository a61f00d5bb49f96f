// Benchmark of issue 4: a sweep of 200 gamma values x 10 modes on a 2,000-DOF model (2D chordwise
// cantilever, 500 AncfCable2d elements, mu = 70, gamma 0..20), with and without Coriolis.
// One JSON line per variant:
//   sweep     solvers::runSweep: one Problem, one ModalSolver reusing its matrices, EPS/PEP
//             objects and factorization pattern; steady state by secant continuation in Omega^2;
//   naive     a fresh Problem, steady state from the initial shape (load_steps) and a fresh
//             ModalSolver at every point;
//   warm      runSweep with modes.warm_start (EPS only: EPSSetInitialSpace from the last point).
// Keys: variant, coriolis, method, points, modes, dofs, seconds, ms_per_point, and for the sweep
// variant the total of both Coriolis settings (target: <= 4 s on one core).
//   bench_sweep [-points 200] [-elements 500] [-count 10]
#include <petscsys.h>
#include <slepcsys.h>

#include <cstdio>

#include "strand/solvers/ModalSolver.hpp"
#include "strand/solvers/Problem.hpp"
#include "strand/solvers/StaticSolver.hpp"
#include "strand/solvers/Sweep.hpp"
#include <gtest/gtest.h>  // the scene helpers report through gtest

#include "support/Rotating.hpp"

using namespace strand;

namespace {

model::SceneDescription scene(int elements, int points, int count, bool coriolis) {
  auto sc = strand::testing::rotatingCantilever(2, elements, 0.0, 0.0, 70.0);
  sc.sweep.present = true;
  sc.sweep.parameter = model::SweepParameter::Gamma;
  sc.sweep.from = 0.0;
  sc.sweep.to = 20.0;
  sc.sweep.points = points;
  sc.sweep.refine = 0;
  sc.modes.count = count;
  sc.modes.coriolis = coriolis;
  sc.statics.loadSteps = 4;
  return sc;
}

double naive(const model::SceneDescription& sc, std::string* method) {
  const double t0 = MPI_Wtime();
  for (int i = 0; i < sc.sweep.points; ++i) {
    model::SceneDescription s = sc;
    const double gamma = sc.sweep.from + (sc.sweep.to - sc.sweep.from) * i / (sc.sweep.points - 1);
    solvers::Problem p(PETSC_COMM_WORLD, s);
    p.setAngularSpeed(gamma / p.model().scales().time());
    Vec X;
    PetscCallAbort(PETSC_COMM_WORLD, p.dofs().createVector(&X));
    PetscCallAbort(PETSC_COMM_WORLD, p.assembler().initialState(X));
    std::string why;
    solvers::StaticSolver steady(p.assembler(), sc.statics.loadSteps);
    PetscCallAbort(PETSC_COMM_WORLD, steady.solve(X, nullptr, &why));
    solvers::ModalSolver modal(p.assembler(), solvers::modalOptions(sc.modes));
    solvers::ModalResult r;
    PetscCallAbort(PETSC_COMM_WORLD, modal.solve(X, &r));
    *method = r.method;
    solvers::destroyModes(&r);
    VecDestroy(&X);
  }
  return MPI_Wtime() - t0;
}

void line(const char* variant, bool coriolis, const std::string& method, int points, int count, int dofs,
          double seconds, const char* extra = "") {
  PetscPrintf(PETSC_COMM_WORLD,
              "{\"benchmark\": \"sweep\", \"variant\": \"%s\", \"coriolis\": %s, \"method\": \"%s\", \"points\": %d, "
              "\"modes\": %d, \"dofs\": %d, \"seconds\": %.6e, \"ms_per_point\": %.6e%s}\n",
              variant, coriolis ? "true" : "false", method.c_str(), points, count, dofs, seconds,
              1e3 * seconds / points, extra);
}

}  // namespace

int main(int argc, char** argv) {
  PetscCall(SlepcInitialize(&argc, &argv, nullptr, nullptr));
  PetscInt points = 200, elements = 500, count = 10;
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-points", &points, nullptr));
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-elements", &elements, nullptr));
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-count", &count, nullptr));
  const int dofs = 4 * (elements + 1);
  double total = 0.0;
  PetscLogStage stages[2][3];  // -log_view per variant: sweep, warm, naive x Coriolis off / on
  for (int c = 0; c < 2; ++c)
    for (int v = 0; v < 3; ++v) {
      const char* names[3] = {"sweep", "warm", "naive"};
      char name[64];
      std::snprintf(name, sizeof(name), "%s%s", names[v], c ? " coriolis" : "");
      PetscCall(PetscLogStageRegister(name, &stages[c][v]));
    }
  for (bool coriolis : {false, true}) {
    const auto sc = scene(elements, points, count, coriolis);
    solvers::SweepResult r;
    PetscCall(PetscLogStagePush(stages[coriolis][0]));
    PetscCall(solvers::runSweep(PETSC_COMM_WORLD, sc, &r));
    PetscCall(PetscLogStagePop());
    total += r.seconds;
    line("sweep", coriolis, r.method, points, count, dofs, r.seconds);
    if (!coriolis) {
      auto warm = sc;
      warm.modes.warmStart = true;
      solvers::SweepResult w;
      PetscCall(PetscLogStagePush(stages[coriolis][1]));
      PetscCall(solvers::runSweep(PETSC_COMM_WORLD, warm, &w));
      PetscCall(PetscLogStagePop());
      // a warm start that skips a mode shows up as a frequency difference
      double dev = 0.0;
      for (size_t i = 0; i < w.omegaBar.size() && i < r.omegaBar.size(); ++i)
        for (size_t k = 0; k < w.omegaBar[i].size() && k < r.omegaBar[i].size(); ++k)
          dev = std::max(dev, std::fabs(w.omegaBar[i][k] / r.omegaBar[i][k] - 1.0));
      char extra[96];
      std::snprintf(extra, sizeof(extra), ", \"max_rel_deviation_from_sweep\": %.3e", dev);
      line("warm", coriolis, w.method, points, count, dofs, w.seconds, extra);
    }
    std::string method;
    PetscCall(PetscLogStagePush(stages[coriolis][2]));
    const double t = naive(sc, &method);
    PetscCall(PetscLogStagePop());
    line("naive", coriolis, method, points, count, dofs, t);
  }
  PetscPrintf(PETSC_COMM_WORLD,
              "{\"benchmark\": \"sweep\", \"variant\": \"sweep_total\", \"points\": %d, \"modes\": %d, \"dofs\": %d, "
              "\"seconds\": %.6e, \"target_seconds\": 4}\n",
              (int)points, (int)count, dofs, total);
  PetscCall(SlepcFinalize());
  return 0;
}
