// Convergence study for the validation charts (docs/validation.md): the same cases as
// tests/verification/test_cantilever_statics.cpp and test_cantilever_modes.cpp, over a wider range
// of N, one JSON line per point. References: the exact elastica (Bisshopp & Drucker 1945;
// tests/support/Elastica.hpp) and beta_n L = 1.87510407, 4.69409113, 7.85475744 (Blevins Table 8-1).
//   study_convergence [-max_elements 128]
#include <slepcsys.h>

#include <cmath>

#include "strand/solvers/ModalSolver.hpp"
#include "support/Elastica.hpp"
#include "support/Scenes.hpp"

using namespace strand;
using namespace strand::testing;

int main(int argc, char** argv) {
  PetscCall(SlepcInitialize(&argc, &argv, nullptr, nullptr));
  PetscInt maxN = 128;
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-max_elements", &maxN, nullptr));
  // Elastica under a dead tip force P = k EI / L^2, against the inextensible solution, for three
  // axial-to-bending ratios EA/EI [1/m^2] (L = 1). The axial strain P/EA = k EI/EA bounds the
  // accuracy from below (plateau ~ k EI/EA); a large EA/EI slows the pre-asymptotic convergence
  // (membrane locking of the cubic cable; docs/validation.md).
  for (double ratio : {1e6, 1e8, 1e10}) {
    const Section stiff{2.1e11, 1e-2, 1e-2 / ratio, 7850.0};
    for (double k : {1.0, 10.0}) {
      const ElasticaTip ref = cantileverTipForce(k);
      for (int n = 2; n <= maxN; n *= 2) {
        auto sc = cantilever(2, n, 1.0, stiff);
        addTipLoad(sc, {0, -k * stiff.E * stiff.I, 0});
        solvers::Problem p(PETSC_COMM_WORLD, sc);
        std::string failure;
        const auto q = solveStatic(p, 20, &failure);
        const model::Vec3 tip = nodePosition(p, q, 0, -1);
        PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                              "{\"study\": \"elastica\", \"EA_over_EI\": %.1e, \"load_parameter\": %.3e, "
                              "\"elements\": %d, \"tip_error\": %.6e, \"converged\": %s}\n",
                              ratio, k, n, std::hypot(tip[0] - ref.x, tip[1] - ref.y),
                              failure.empty() ? "true" : "false"));
      }
    }
  }
  // cantilever bending frequencies (EA/EI = 1e4)
  const Section s;
  const double scale = std::sqrt(s.E * s.I / (s.rho * s.A));
  // roots of cos(x) cosh(x) = -1 to 16 digits (mpmath findroot): the 9 printed digits of the
  // tables limit the reference to ~5e-9 relative, visible on this chart beyond N = 32
  const double betaL[3] = {1.875104068711961, 4.694091132974175, 7.854757438237613};
  for (int n = 2; n <= maxN; n *= 2) {
    auto sc = cantilever(2, n, 1.0, s);
    solvers::Problem p(PETSC_COMM_WORLD, sc);
    Vec X;
    PetscCall(p.dofs().createVector(&X));
    PetscCall(p.assembler().initialState(X));
    solvers::ModalResult r;
    PetscCall(solvers::solveModes(p.assembler(), X, 3, &r));
    for (int m = 0; m < 3 && m < static_cast<int>(r.omega.size()); ++m) {
      const double exact = betaL[m] * betaL[m] * scale;
      PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                            "{\"study\": \"cantilever_modes\", \"mode\": %d, \"elements\": %d, "
                            "\"relative_error\": %.6e}\n",
                            m + 1, n, std::fabs(r.omega[m] - exact) / exact));
    }
    solvers::destroyModes(&r);
    PetscCall(VecDestroy(&X));
  }
  PetscCall(SlepcFinalize());
  return 0;
}
