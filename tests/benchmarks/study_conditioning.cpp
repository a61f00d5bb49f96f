// Conditioning study (issue: foundation; design section 3): static tip deflection of a linear
// cantilever against the number of elements N, with and without slope scaling.
// Exact: w = F L^3 / (3 E I); cubic Hermite elements contain it, so every error is round-off
// amplified by the conditioning of the stiffness matrix. Prints one JSON line per case.
//   study_conditioning [-max_elements 10000]
#include <petscsys.h>

#include <cmath>
#include <cstdio>

#include "support/Scenes.hpp"

using namespace strand;
using namespace strand::testing;

int main(int argc, char** argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  PetscInt maxN = 10000;
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-max_elements", &maxN, nullptr));
  for (double ratio : {1e4, 1e7}) {  // EA/EI [1/m^2] with L = 1
    for (bool scaled : {false, true}) {
      for (int n : {10, 100, 1000, 3000, 10000}) {
        if (n > maxN) continue;
        Section s;
        s.A = ratio * s.I;
        auto sc = cantilever(2, n, 1.0, s);
        sc.discretization.slopeScaling = scaled;
        const double F = 1e-6 * s.E * s.I;  // w / L = 3.3e-7: geometric nonlinearity ~1e-13 relative
        addTipLoad(sc, {0, -F, 0});
        solvers::Problem p(PETSC_COMM_WORLD, sc);
        std::string failure;
        const auto q = solveStatic(p, 1, &failure);
        const double w = -nodePosition(p, q, 0, -1)[1];
        const double exact = F / (3.0 * s.E * s.I);
        PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                              "{\"study\": \"conditioning\", \"EA_over_EI\": %.6e, \"slope_scaling\": %s, \"elements\": %d, "
                              "\"tip_deflection\": %.12e, \"relative_error\": %.3e, \"converged\": %s}\n",
                              ratio, scaled ? "true" : "false", n, w, std::fabs(w / exact - 1.0),
                              failure.empty() ? "true" : "false"));
      }
    }
  }
  PetscCall(PetscFinalize());
  return 0;
}
