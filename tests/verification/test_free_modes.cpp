// requirement (issue 32 items 7, 11): the modal solver reports the rigid-body modes of a body with
// no supports, at 0 Hz, and then its elastic modes; and a projected solve whose basis would span
// every free coordinate is solved exactly instead.
//
// Free-free Euler-Bernoulli beam: omega_n = (beta_n L)^2 sqrt(EI / (rho A L^4)) with beta_n L =
// 4.73004074, 7.85320462, 10.99560784 (Blevins, Formulas for Natural Frequency and Mode Shape,
// 1979, Table 8-1, "free-free"; the same roots as the clamped-clamped beam, cos(bL) cosh(bL) = 1).
// The gradient-deficient ANCF cable has no torsion coordinate, so its rigid-body modes are 3 in 2D
// (two translations, one rotation) and 5 in 3D (three translations, two rotations). Before: shift-
// and-invert about 0 factored the singular stiffness and the solve stopped with a zero pivot
// (exit 91).
//
// Projection (item 11): with modes.projection_modes at or above the number of free coordinates the
// projected problem is no reduction and its highest basis modes are the least accurate; the solver
// then solves the quadratic problem with TOAR (pep) and says so. Before: relative residuals 1e-7
// against pep's 1e-13 on this rotating blade (gamma 10, 16 elements, 64 free coordinates).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "strand/solvers/ModalSolver.hpp"
#include "support/Rotating.hpp"
#include "support/Scenes.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

solvers::ModalResult freeModes(int dim, int elements, int count, const Section& s) {
  auto sc = cantilever(dim, elements, 1.0, s);
  sc.supports.clear();
  solvers::Problem p(PETSC_COMM_WORLD, sc);
  Vec X;
  PetscCallAbort(PETSC_COMM_WORLD, p.dofs().createVector(&X));
  PetscCallAbort(PETSC_COMM_WORLD, p.assembler().initialState(X));
  solvers::ModalResult r;
  const PetscErrorCode status = solvers::solveModes(p.assembler(), X, count, &r);
  EXPECT_EQ(status, 0) << "the modal solve of a free body failed";
  for (Vec& v : r.shapes) VecDestroy(&v);
  r.shapes.clear();
  VecDestroy(&X);
  return r;
}

}  // namespace

TEST(FreeModes, FreeFreeBeamHasThreeRigidModesThenTheAnalyticBendingFrequencies) {
  const Section s;
  const double scale = std::sqrt(s.E * s.I / (s.rho * s.A));
  const double betaL[3] = {4.73004074, 7.85320462, 10.99560784};
  const solvers::ModalResult r = freeModes(2, 64, 6, s);
  ASSERT_EQ(r.omega.size(), 6u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_TRUE(r.rigid[k]) << "mode " << k + 1;
    EXPECT_EQ(r.omega[k], 0.0);
    EXPECT_LT(r.relativeResidual[k], 1e-6);
  }
  for (int k = 0; k < 3; ++k) {
    const double exact = betaL[k] * betaL[k] * scale, w = r.omega[3 + k];
    std::printf("free-free mode %d: omega %.10g exact %.10g rel.error %.2e residual %.1e\n", k + 1, w, exact,
                std::fabs(w - exact) / exact, r.relativeResidual[3 + k]);
    EXPECT_FALSE(r.rigid[3 + k]);
    // 64 cubic elements (h^4): measured 2.1e-8, 1.6e-7, 6.0e-7 (32 elements: 3.3e-7, 2.5e-6, 9.6e-6)
    EXPECT_LT(std::fabs(w - exact) / exact, 2e-6) << "mode " << k + 1;
    EXPECT_LT(r.relativeResidual[3 + k], 1e-8);
  }
}

TEST(FreeModes, FreeCableIn3dHasFiveRigidModesThenPairsOfBendingModes) {
  const Section s;
  const double scale = std::sqrt(s.E * s.I / (s.rho * s.A));
  const solvers::ModalResult r = freeModes(3, 16, 9, s);
  ASSERT_EQ(r.omega.size(), 9u);
  for (int k = 0; k < 5; ++k) EXPECT_TRUE(r.rigid[k]) << "mode " << k + 1;
  const double first = 4.73004074 * 4.73004074 * scale;
  for (int k = 5; k < 7; ++k) {  // the first bending pair, in two planes
    EXPECT_FALSE(r.rigid[k]);
    EXPECT_LT(std::fabs(r.omega[k] - first) / first, 1e-5) << "mode " << k + 1 << ": " << r.omega[k];
  }
}

TEST(FreeModes, ProjectionSpanningEveryFreeCoordinateIsSolvedExactly) {
  const auto sc = rotatingCantilever(2, 16, 10.0, 0.0, 70.0);  // 64 free coordinates
  solvers::ModalOptions pep;
  pep.count = 5;
  pep.coriolis = true;
  pep.method = model::ModalMethod::Pep;
  solvers::ModalOptions projected = pep;
  projected.method = model::ModalMethod::Projected;
  projected.projectionModes = 70;
  const RotatingModes exact = rotatingModes(sc, pep), p = rotatingModes(sc, projected);
  ASSERT_EQ(p.omegaBar.size(), 5u);
  EXPECT_EQ(p.method, "pep");
  for (size_t k = 0; k < 5; ++k) {
    std::printf("mode %zu: omega_bar %.10g (pep %.10g), residual %.1e\n", k + 1, p.omegaBar[k], exact.omegaBar[k],
                p.residual[k]);
    EXPECT_LT(p.residual[k], 1e-10);
    EXPECT_NEAR(p.omegaBar[k], exact.omegaBar[k], 1e-9 * exact.omegaBar[k]);
  }
}
