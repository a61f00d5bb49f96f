// Time per step of a large 3D cable model (issue 3, "Speed"): a steel cable cantilever under
// gravity (L = 1 m, d = 10 mm, E = 210 GPa, rho = 7850 kg/m^3; AncfCable3d), released from the
// straight shape, generalized-alpha rho_inf = 0.9, h = 1e-3 s, N elements (-elements, default
// 1000 and 10000), -steps steps (default 100), -length L (default 1 m), -ramp T (gravity applied
// over T seconds instead of at once). Newton converged at every step (SNES rtol 1e-10) or
// the run reports a failure. Accuracy stated with the speed: the tip deflection at the end against
// the static deflection rho A g L^4 / (8 EI) (the free vibration swings about it, up to twice it).
// One JSON line per size; run on one core (or under mpirun for the parallel ratio).
// ms_per_step covers the whole run (set-up of the integrator, consistent start, every step);
// steady_ms_per_step only the steps after the first, i.e. without the one-off set-up and first
// factorizations, which a long batch run amortizes (docs/performance.md, "10^5 elements").
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
  PetscInt sizes[8] = {1000, 10000}, nsizes = 8, steps = 100;
  PetscBool set;
  PetscCall(PetscOptionsGetIntArray(nullptr, nullptr, "-elements", sizes, &nsizes, &set));
  if (!set) nsizes = 2;
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-steps", &steps, nullptr));
  PetscMPIInt ranks;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &ranks));
  const double d = 0.01;
  PetscReal L = 1.0;  // -length: a longer cable keeps the element length of N / L
  PetscReal ramp = 0.0;  // -ramp T: gravity ramped in over T seconds (loads.function: ramp)
  PetscReal dt = 1e-3;   // -dt h: the time step (the run covers -steps steps of 1 ms either way)
  PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-length", &L, nullptr));
  PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-ramp", &ramp, nullptr));
  PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-dt", &dt, nullptr));
  for (PetscInt k = 0; k < nsizes; ++k) {
    model::SceneDescription sc = steelCantileverUnderGravity(static_cast<int>(sizes[k]), L, d);
    const model::BodyDesc& s = sc.bodies[0];
    if (ramp > 0.0) {
      sc.loads.timed = true;
      sc.loads.function.kind = model::TimeFunction::Kind::Ramp;
      sc.loads.function.value = 1.0;
      sc.loads.function.start = 0.0;
      sc.loads.function.end = ramp;
    }
    model::DynamicsDesc dd;
    dd.rhoInf = 0.9;
    dd.dt = dt;
    dd.tEnd = steps * 1e-3;
    PetscLogDouble t0, t1, t2;
    PetscCall(PetscTime(&t0));
    solvers::Problem p(PETSC_COMM_WORLD, sc);
    Vec X, V;
    PetscCall(p.createInitialState(&X, &V));
    solvers::Dynamics dyn(p.assembler(), dd);
    PetscCall(dyn.setFromOptions());
    long newton = 0, done = 0, rejected = 0;
    PetscLogDouble afterFirst = 0.0;
    solvers::Dynamics::StepCallback cb = [&](const solvers::DynamicsStep& st, Vec, Vec) -> PetscErrorCode {
      newton += st.newtonIterations;
      done = st.step;
      rejected = st.rejectedSteps;
      if (st.step == 1) PetscCall(PetscTime(&afterFirst));
      return 0;
    };
    std::string failure;
    PetscCall(PetscTime(&t1));
    PetscCall(dyn.run(X, V, cb, &failure));
    PetscCall(PetscTime(&t2));
    std::vector<double> q;
    PetscCall(p.assembler().gatherToRoot(X, q));
    double tip = 0.0;
    if (!q.empty()) tip = nodePosition(p, q, 0, -1)[2];
    const elements::SectionValues& sec = s.section;
    const double staticTip = -sec.number("rho") * sec.number("A") * 9.81 * std::pow(L, 4) / (8.0 * sec.number("E") * sec.number("I"));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                          "{\"bench\": \"cantilever_3d_dynamics\", \"elements\": %d, \"length\": %.6e, \"ranks\": %d, \"dt\": %.3e, "
                          "\"steps\": %ld, \"setup_seconds\": %.6e, \"seconds\": %.6e, \"ms_per_step\": %.4f, "
                          "\"steady_ms_per_step\": %.4f, "
                          "\"newton_per_step\": %.4f, \"newton_start\": \"%s\", \"failed\": %s, \"rejected_steps\": %ld, \"tip_z\": %.9e, \"static_tip_z\": %.6e}\n",
                          static_cast<int>(sizes[k]), static_cast<double>(L), ranks, static_cast<double>(dt), done, t1 - t0, t2 - t1, 1e3 * (t2 - t1) / std::max(done, 1L),
                          done > 1 ? 1e3 * (t2 - afterFirst) / (done - 1) : 0.0,
                          double(newton) / std::max(done, 1L), dyn.newtonStart().c_str(), failure.empty() ? "false" : "true", rejected, tip, staticTip));
    if (!failure.empty()) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "# %s\n", failure.c_str()));
    VecDestroy(&X);
    VecDestroy(&V);
  }
  PetscCall(PetscFinalize());
  return 0;
}
