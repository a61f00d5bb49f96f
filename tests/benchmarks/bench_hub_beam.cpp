// Per-step cost of the floating-frame hub-beam (issue 5: "small systems must not pay large-model
// overheads: measure the per-step cost against a plain dense loop"). Seed 001's spin-up (Omega0 =
// 4 rad/s, E = 70 GPa, 20 s, dt = 1 ms, Newmark, no output) for each discretization, run
//  - on PETSc TS (our strand_alpha TS, SNES, KSP preonly + LU on a dense Mat; -ffr_dense false), and
//  - on the small-system path: the same step as a plain loop on Eigen matrices (the default);
// both in one process, same answers (the tip difference is printed). One JSON line per basis.
#include <petscsys.h>

#include <cstdio>

#include "support/HubBeamRuns.hpp"

using namespace strand;
using namespace strand::testing;

int main(int argc, char** argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  struct Case { model::HubBeamMethod m; int size; const char* name; };
  const Case cases[] = {{model::HubBeamMethod::AssumedModes, 3, "modes 3+3"}, {model::HubBeamMethod::Fem, 10, "fem 10"},
                        {model::HubBeamMethod::Rpim, 11, "rpim 11"}, {model::HubBeamMethod::Fem, 40, "fem 40"}};
  const model::DynamicsDesc dyn = fixedStep(model::Integrator::Newmark, 1e-3, 20.0);
  for (const Case& c : cases) {
    const model::HubBeamDesc d = seed001HubBeam(70e9, 4.0, c.m, c.size);
    const int n = ffr::HubBeam(d).size();
    PetscCall(PetscOptionsSetValue(nullptr, "-ffr_dense", "false"));
    const TipSeries ts = runHubBeam(d, dyn, 1000);
    PetscCall(PetscOptionsClearValue(nullptr, "-ffr_dense"));
    const TipSeries dense = runHubBeam(d, dyn, 1000);
    const double usTs = 1e6 * ts.wallTime / ts.steps, usDense = 1e6 * dense.wallTime / dense.steps;
    PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                          "{\"bench\": \"hub_beam_step\", \"basis\": \"%s\", \"unknowns\": %d, \"steps\": %d, "
                          "\"petsc_ts_us_per_step\": %.6e, \"dense_us_per_step\": %.6e, \"ratio\": %.6e, "
                          "\"tip_difference_m\": %.6e}\n",
                          c.name, n, dense.steps, usTs, usDense, usTs / usDense,
                          std::abs(ts.uy.back() - dense.uy.back())));
  }
  PetscCall(PetscFinalize());
  return 0;
}
