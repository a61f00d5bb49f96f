// Stability map (issue 3): the largest stable step of each scheme against the highest frequency
// omega_max of the model, measured. Models: the undamped flexible pendulum of the integrator tests
// (1 m rope, EA = 1e4 N, EI = 1 N m^2, pinned, released under gravity) with 2, 4, 8 and 16
// elements, so omega_max (SLEPc, K x = omega^2 M x at rest) spans an order of magnitude.
// For each scheme, bisection on h (12 halvings of the bracket) for the largest step whose run of
// -t_end seconds (default 0.05 s) ends without a stop (blow-up guard or Newton failure). Explicit:
// RK4 (theory h omega_max = 2 sqrt(2)); ABM4 (unstable on undamped modes at every h over long runs:
// its "largest stable step" shrinks with the run length, shown for the same 0.05 s). Implicit
// (generalized-alpha rho 0.9, Newmark, BDF2): checked at h = 100 / omega_max and 1e-2 s, where they
// must run. One JSON line per (scheme, model).
#include <petscsys.h>

#include <cmath>
#include <cstdio>

#include "strand/solvers/Dynamics.hpp"
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
  PetscReal tEnd = 0.05;
  PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-t_end", &tEnd, nullptr));
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
                            "\"t_end\": %.3e, \"h_max\": %.6e, \"h_omega\": %.4f, \"theory_h_omega\": %s}\n",
                            name, elements, omega, tEnd, lo, lo * omega,
                            integrator == model::Integrator::Rk4 ? "2.8284" : "null"));
    }
    for (const char* name : {"generalized_alpha", "newmark", "bdf2"}) {
      model::DynamicsDesc d = scheme(std::string(name) == "newmark" ? model::Integrator::Newmark
                                     : std::string(name) == "bdf2"  ? model::Integrator::Bdf
                                                                    : model::Integrator::GeneralizedAlpha,
                                     0.9, 0, tEnd);
      d.bdfOrder = 2;
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
