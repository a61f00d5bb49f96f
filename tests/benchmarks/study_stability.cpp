// Stability map (issue 3): the largest stable step of each scheme against the highest frequency
// omega_max of the model, measured. Models: the undamped flexible pendulum of the integrator tests
// (1 m rope, EA = 1e4 N, EI = 1 N m^2, pinned, released under gravity) with 2, 4, 8 and 16
// elements, so omega_max (SLEPc, K x = omega^2 M x at rest) spans an order of magnitude.
// For each scheme, bisection on h (12 halvings of the bracket) for the largest step whose run of
// -t_end seconds (default 0.05 s) ends without a stop (blow-up guard or Newton failure). Explicit:
// RK4 (theory h omega_max = 2 sqrt(2)); ABM4 (unstable on undamped modes at every h over long runs:
// its "largest stable step" shrinks with the run length, shown for the same 0.05 s). A-stable
// implicit schemes (generalized-alpha rho 0.9, Newmark, HHT, BDF1, BDF2): checked at
// h = 100 / omega_max and 1e-2 s, where they must run. BDF3-5 are not A-stable: an undamped mode
// grows while h omega lies in a band on the imaginary axis (largest root of
// rho(zeta) - i h omega sigma(zeta) above 1: 0-1.94 for BDF3, 0-4.71 for BDF4, 0.71-9.39 for BDF5;
// Hairer & Wanner, Solving ODEs II, Sec. V.2), and the band holds every mode with h omega in it,
// not only the highest: runs of -t_end_bdf seconds (default 0.5 s: the growth per step is at most
// 4.6 %, 19 %, 38 %, and a high mode starts near round-off) at h omega_max = 0.25 ... 128 (factors
// of 2), recorded as run or stopped. One JSON line per (scheme, model).
#include <petscsys.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "strand/solvers/Dynamics.hpp"
#include "strand/solvers/Schemes.hpp"
#include "support/Pendulum.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

bool runs(const model::SceneDescription& sc, model::DynamicsDesc d) {
  const PendulumRun r = runPendulum(sc, d, true);
  return r.failure.empty();
}

}  // namespace

int main(int argc, char** argv) {
  PetscCall(SlepcInitialize(&argc, &argv, nullptr, nullptr));
  PetscReal tEnd = 0.05, tEndBdf = 0.5;
  PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-t_end", &tEnd, nullptr));
  PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-t_end_bdf", &tEndBdf, nullptr));
  for (int elements : {2, 4, 8, 16}) {
    const model::SceneDescription sc = flexiblePendulum(0.0, 1e8, elements);
    const double omega = highestFrequency(sc);
    for (model::Integrator integrator : {model::Integrator::Rk4, model::Integrator::Abm4}) {
      const char* name = integrator == model::Integrator::Rk4 ? "rk4" : "abm4";
      double lo = 0.05 / omega, hi = 10.0 / omega;  // stable, unstable
      if (!runs(sc, scheme(integrator, 1.0, lo, tEnd))) lo = 0.0;
      for (int k = 0; k < 12 && lo > 0.0; ++k) {
        const double mid = 0.5 * (lo + hi);
        (runs(sc, scheme(integrator, 1.0, mid, tEnd)) ? lo : hi) = mid;
      }
      PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                            "{\"study\": \"stability\", \"scheme\": \"%s\", \"elements\": %d, \"omega_max\": %.6e, "
                            "\"t_end\": %.3e, \"limit\": \"largest_stable\", \"h_limit\": %.6e, \"h_omega\": %.4f, "
                            "\"theory_h_omega\": %s}\n",
                            name, elements, omega, tEnd, lo, lo * omega,
                            integrator == model::Integrator::Rk4 ? "2.8284" : "null"));
    }
    for (int order : {3, 4, 5}) {
      model::DynamicsDesc d = scheme(model::Integrator::Bdf, 1.0, 0.0, tEndBdf);
      d.bdfOrder = order;
      std::string hw, ok;
      for (double x : {0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0, 128.0}) {
        d.dt = x / omega;
        hw += (hw.empty() ? "" : ", ") + std::to_string(x).substr(0, 6);
        ok += (ok.empty() ? "" : ", ") + std::string(runs(sc, d) ? "true" : "false");
      }
      PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                            "{\"study\": \"stability_band\", \"scheme\": \"bdf%d\", \"elements\": %d, \"omega_max\": %.6e, "
                            "\"t_end\": %.3e, \"h_omega\": [%s], \"runs\": [%s], \"theory_band\": [%.4f, %.4f]}\n",
                            order, elements, omega, tEndBdf, hw.c_str(), ok.c_str(), solvers::bdfGrowthBand(order).lower,
                            solvers::bdfGrowthBand(order).upper));
    }
    for (const char* name : {"generalized_alpha", "newmark", "hht", "bdf1", "bdf2"}) {
      const std::string n = name;
      model::DynamicsDesc d = scheme(n == "newmark" ? model::Integrator::Newmark
                                     : n == "hht"   ? model::Integrator::Hht
                                     : n.rfind("bdf", 0) == 0 ? model::Integrator::Bdf
                                                              : model::Integrator::GeneralizedAlpha,
                                     0.9, 0, tEnd);
      d.bdfOrder = n == "bdf1" ? 1 : 2;
      const double h1 = 100.0 / omega, h2 = 1e-2;
      d.dt = h1;
      const bool ok1 = runs(sc, d);
      d.dt = h2;
      d.tEnd = std::max(tEnd, 2.0 * h2);
      const bool ok2 = runs(sc, d);
      PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                            "{\"study\": \"stability_implicit\", \"scheme\": \"%s\", \"elements\": %d, \"omega_max\": %.6e, "
                            "\"runs_at_h_omega_100\": %s, \"runs_at_h_1e-2\": %s, \"h_omega_at_1e-2\": %.1f}\n",
                            name, elements, omega, ok1 ? "true" : "false", ok2 ? "true" : "false", h2 * omega));
    }
  }
  PetscCall(SlepcFinalize());
  return 0;
}
