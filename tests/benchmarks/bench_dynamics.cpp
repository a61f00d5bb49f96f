// Time per step of the dynamics (issue 3, "Speed"): the spin-up of seed 001 (10 ANCF cable
// elements, 2D, h = 1e-3 s, 20 s = 20,000 steps, generalized-alpha rho_inf = 0.9), on one core,
// Newton converged at every step (SNES rtol 1e-10). Accuracy stated with the speed: the stretch
// after the spin-up against the rotating-frame static solution (test_spin_up.cpp explains the
// remaining residual-vibration difference). One JSON line per run; options: -repeat N, -t_end T.
#include <petscsys.h>
#include <petsctime.h>

#include <cmath>
#include <cstdio>

#include "strand/solvers/Dynamics.hpp"
#include "support/Scenes.hpp"

using namespace strand;
using namespace strand::testing;

int main(int argc, char** argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  PetscInt repeat = 3;
  PetscReal tEnd = 20.0;
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-repeat", &repeat, nullptr));
  PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-t_end", &tEnd, nullptr));
  const double L = 10.0, omega0 = 4.0, E = 70e9;
  for (PetscInt rep = 0; rep < repeat; ++rep) {
    solvers::Problem p(PETSC_COMM_WORLD, seed001Beam(E, 10, omega0));
    model::DynamicsDesc d;
    d.rhoInf = 0.9;
    d.dt = 1e-3;
    d.tEnd = tEnd;
    Vec X, V;
    PetscCall(p.createInitialState(&X, &V));
    solvers::Dynamics dyn(p.assembler(), d);
    PetscCall(dyn.setFromOptions());
    long newton = 0, steps = 0;
    solvers::Dynamics::StepCallback cb = [&](const solvers::DynamicsStep& st, Vec, Vec) -> PetscErrorCode {
      newton += st.newtonIterations;
      steps = st.step;
      return 0;
    };
    std::string failure;
    PetscLogDouble t0, t1;
    PetscCall(PetscTime(&t0));
    PetscCall(dyn.run(X, V, cb, &failure));
    PetscCall(PetscTime(&t1));
    // stretch in the hub frame against the static rotating-frame solution
    std::vector<double> q;
    PetscCall(p.assembler().gatherToRoot(X, q));
    double stretch = 0.0;
    if (!q.empty()) {
      const model::Vec3 tip = nodePosition(p, q, 0, -1);
      stretch = std::hypot(tip[0], tip[1]) - L;
    }
    model::SceneDescription ss = seed001Beam(E, 10);
    ss.rotation.present = true;
    ss.rotation.omega = omega0;
    solvers::Problem ps(PETSC_COMM_WORLD, ss);
    const std::vector<double> qs = solveStatic(ps, 1);
    const double stretchStatic = nodePosition(ps, qs, 0, -1)[0] - L;
    PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                          "{\"bench\": \"spin_up\", \"elements\": 10, \"dt\": 1.0e-03, \"steps\": %ld, \"seconds\": %.6e, "
                          "\"us_per_step\": %.3f, \"newton_per_step\": %.4f, \"failed\": %s, \"stretch\": %.6e, "
                          "\"stretch_static\": %.6e}\n",
                          steps, t1 - t0, 1e6 * (t1 - t0) / std::max(steps, 1L), double(newton) / std::max(steps, 1L),
                          failure.empty() ? "false" : "true", stretch, stretchStatic));
    VecDestroy(&X);
    VecDestroy(&V);
  }
  PetscCall(PetscFinalize());
  return 0;
}
