// Seed 001 Tables 1-3 in our terms (issue 5, "speed against accuracy"): the spin-up (Omega0 =
// 4 rad/s, E = 70 GPa, or -omega 20 -E 30e9) for each discretization and size (AMM 3-7 modes, FEM
// and RPIM 5-40 nodes) and each integrator (Newmark, generalized-alpha rho_inf 0.9, BDF2, RK4, ABM4),
// the error of the residual amplitude after the spin-up (seed 001's measure) and of the whole tip
// history against a converged reference (FEM 40 elements, Newmark dt = 0.5 ms), and the wall time.
// One JSON line per run; drivers/plot/strand_plot.py charts error against wall time.
// Options: -omega W, -E E, -t_end T (default 20 s), -scheme NAME (only that integrator).
#include <petscsys.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "support/HubBeamRuns.hpp"

using namespace strand;
using namespace strand::testing;
using model::HubBeamMethod;
using model::Integrator;

int main(int argc, char** argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  PetscReal omega = 4.0, E = 70e9, tEnd = 20.0;
  PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-omega", &omega, nullptr));
  PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-E", &E, nullptr));
  PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-t_end", &tEnd, nullptr));
  char only[32] = "";  // -scheme NAME: run only that scheme (Newmark, alpha0.9, BDF2, RK4, ABM4)
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-scheme", only, sizeof(only), nullptr));
  const TipSeries ref = runHubBeam(seed001HubBeam(E, omega, HubBeamMethod::Fem, 40),
                                   fixedStep(Integrator::Newmark, 5e-4, tEnd), 2);
  const double refAmp = ref.amplitudeAfter(15.0), peak = ref.maxAbsUy();
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "{\"study\": \"hub_beam\", \"reference\": \"fem 40, Newmark 0.5 ms\", "
                        "\"omega0\": %.6e, \"E\": %.6e, \"amplitude_m\": %.6e, \"peak_m\": %.6e}\n", omega, E, refAmp, peak));
  struct Disc { HubBeamMethod m; std::vector<int> sizes; const char* name; };
  const Disc discs[] = {{HubBeamMethod::AssumedModes, {3, 4, 5, 6, 7}, "AMM"},
                        {HubBeamMethod::Fem, {5, 10, 20, 40}, "FEM"},
                        {HubBeamMethod::Rpim, {6, 11, 21, 41}, "RPIM"}};
  struct Scheme { Integrator i; const char* name; };
  const Scheme schemes[] = {{Integrator::Newmark, "Newmark"}, {Integrator::GeneralizedAlpha, "alpha0.9"},
                            {Integrator::Bdf, "BDF2"}, {Integrator::Rk4, "RK4"}, {Integrator::Abm4, "ABM4"}};
  for (const Disc& disc : discs)
    for (int size : disc.sizes)
      for (const Scheme& sc : schemes) {
        if (only[0] && std::string(only) != sc.name) continue;
        model::HubBeamDesc d = seed001HubBeam(E, omega, disc.m, size);
        // implicit: 1 ms (seed 001's Newmark); explicit: a safe fraction of the stability limit,
        // from the highest frequency of the (non-rotating) model
        double dt = 1e-3;
        if (sc.i == Integrator::Rk4 || sc.i == Integrator::Abm4) {
          const double wmax = ffr::HubBeam(d).highestFrequency();
          // RK4: h omega_max = 2 (stable to 2.83). ABM4 is weakly unstable on undamped modes: a mode
          // grows by exp(0.16 (h omega)^6) per step (AdamsBashforthMoulton.hpp), by
          // exp(0.16 (h omega)^5 omega T) over the run; h omega = min(0.3, (10 / (0.16 omega T))^(1/5))
          // keeps that below e^10, so round-off (1e-16) stays below 1e-11 of the motion
          const double hwAbm = std::min(0.3, std::pow(10.0 / (0.16 * wmax * tEnd), 0.2));
          dt = std::min(1e-3, (sc.i == Integrator::Rk4 ? 2.0 : hwAbm) / wmax);
          dt = tEnd / std::ceil(tEnd / dt);
          if (tEnd / dt > 2e6) continue;  // fine models: explicit steps too many for a study (see docs)
        }
        model::DynamicsDesc dyn = fixedStep(sc.i, dt, tEnd);
        dyn.rhoInf = 0.9;
        const TipSeries s = runHubBeam(d, dyn, std::max(1, static_cast<int>(std::lround(5e-4 / dt))));
        const double ampErr = s.failure.empty() ? std::abs(s.amplitudeAfter(15.0) / refAmp - 1) : -1.0;
        const double histErr = s.failure.empty() ? s.maxDifferenceUy(ref) / peak : -1.0;
        PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                              "{\"study\": \"hub_beam\", \"method\": \"%s\", \"size\": %d, \"scheme\": \"%s\", "
                              "\"dt\": %.6e, \"steps\": %d, \"wall_s\": %.6e, \"amplitude_error\": %.6e, "
                              "\"history_error\": %.6e, \"label\": \"%s %d\", \"failed\": %s}\n",
                              disc.name, size, sc.name, dt, s.steps, s.wallTime, ampErr, histErr, disc.name, size,
                              s.failure.empty() ? "false" : "true"));
        std::fflush(stdout);
      }
  PetscCall(PetscFinalize());
  return 0;
}
