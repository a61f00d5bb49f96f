// Per-step cost of the floating-frame hub-beam (issue 5: "small systems must not pay large-model
// overheads: measure the per-step cost against a plain dense loop"). Seed 001's spin-up (Omega0 =
// 4 rad/s, E = 70 GPa, no output) for each discretization and each fixed-step scheme, run
//  - on PETSc TS (our strand_alpha, TSBDF, TSRK4, strand_abm4; SNES, KSP preonly + LU on a dense
//    Mat; -ffr_dense false), and
//  - on the small-system path: the same steps as plain loops on Eigen matrices (the default);
// both in one process, same answers (the largest tip difference is printed). One JSON line per
// basis and scheme. Implicit schemes: dt = 1 ms over 20 s; explicit: 0.3 / omega_max over 2 s.
#include <petscsys.h>

#include <cstdio>

#include "support/HubBeamRuns.hpp"

using namespace strand;
using namespace strand::testing;
using model::Integrator;

int main(int argc, char** argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  struct Case { model::HubBeamMethod m; int size; const char* name; };
  const Case cases[] = {{model::HubBeamMethod::AssumedModes, 3, "modes 3+3"}, {model::HubBeamMethod::Fem, 10, "fem 10"},
                        {model::HubBeamMethod::Rpim, 11, "rpim 11"}, {model::HubBeamMethod::Fem, 40, "fem 40"}};
  struct Scheme { Integrator i; const char* name; };
  const Scheme schemes[] = {{Integrator::Newmark, "Newmark"}, {Integrator::Bdf, "BDF2"}, {Integrator::Rk4, "RK4"},
                            {Integrator::Abm4, "ABM4"}};
  for (const Case& c : cases)
    for (const Scheme& sc : schemes) {
      const model::HubBeamDesc d = seed001HubBeam(70e9, 4.0, c.m, c.size);
      const ffr::HubBeam hb(d);
      model::DynamicsDesc dyn = fixedStep(sc.i, 1e-3, 20.0);
      if (model::isExplicit(sc.i)) {
        if (hb.size() > 60) continue;  // 1e6 explicit steps: not a per-step measurement worth its time
        dyn.tEnd = 2.0;
        dyn.dt = dyn.tEnd / std::ceil(dyn.tEnd * hb.highestFrequency() / 0.3);
      }
      PetscCall(PetscOptionsSetValue(nullptr, "-ffr_dense", "false"));
      const TipSeries ts = runHubBeam(d, dyn, 1);
      PetscCall(PetscOptionsClearValue(nullptr, "-ffr_dense"));
      const TipSeries dense = runHubBeam(d, dyn, 1);
      const double usTs = 1e6 * ts.wallTime / ts.steps, usDense = 1e6 * dense.wallTime / dense.steps;
      PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                            "{\"bench\": \"hub_beam_step\", \"basis\": \"%s\", \"scheme\": \"%s\", \"unknowns\": %d, "
                            "\"steps\": %d, \"petsc_ts_us_per_step\": %.6e, \"dense_us_per_step\": %.6e, "
                            "\"ratio\": %.6e, \"tip_difference_m\": %.6e}\n",
                            c.name, sc.name, hb.size(), dense.steps, usTs, usDense, usTs / usDense,
                            dense.maxDifferenceUy(ts)));
      std::fflush(stdout);
    }
  PetscCall(PetscFinalize());
  return 0;
}
