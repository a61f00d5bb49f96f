// requirement: the first three bending frequencies of a uniform Euler-Bernoulli cantilever,
// omega_n = (beta_n L)^2 sqrt(EI / (rho A L^4)) with beta_n L = 1.87510407, 4.69409113, 7.85475744
// (e.g. Blevins, Formulas for Natural Frequency and Mode Shape, Table 8-1), through a SLEPc
// shift-and-invert solve; the observed convergence rate in N (cubic Hermite: h^4) is asserted.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "strand/solvers/ModalSolver.hpp"
#include "support/Scenes.hpp"

using namespace strand;
using namespace strand::testing;

namespace {
std::vector<double> bendingFrequencies(int dim, int n, const Section& s, int count, model::Vec3 along = {1, 0, 0}) {
  auto sc = cantilever(dim, n, 1.0, s);
  sc.bodies[0] = straightBody("beam", dim, n, {0, 0, 0}, along, s);
  solvers::Problem p(PETSC_COMM_WORLD, sc);
  Vec X;
  PetscCallAbort(PETSC_COMM_WORLD, p.dofs().createVector(&X));
  PetscCallAbort(PETSC_COMM_WORLD, p.assembler().initialState(X));
  solvers::ModalResult r;
  PetscCallAbort(PETSC_COMM_WORLD, solvers::solveModes(p.assembler(), X, count, &r));
  for (double res : r.relativeResidual) EXPECT_LT(res, 1e-8);
  std::vector<double> w = r.omega;
  solvers::destroyModes(&r);
  VecDestroy(&X);
  return w;
}
}  // namespace

TEST(CantileverModes, FirstThreeBendingFrequenciesConvergeAtRateFour) {
  const Section s;  // EA/EI = 1e4: the first axial mode (8.1e3 rad/s) lies above the third bending mode
  const double scale = std::sqrt(s.E * s.I / (s.rho * s.A));
  const double betaL[3] = {1.87510407, 4.69409113, 7.85475744};
  std::vector<std::array<double, 3>> err;
  for (int n : {4, 8, 16, 32}) {
    const auto w = bendingFrequencies(2, n, s, 3);
    ASSERT_EQ(w.size(), 3u);
    std::array<double, 3> e{};
    for (int k = 0; k < 3; ++k) {
      const double exact = betaL[k] * betaL[k] * scale;
      e[k] = std::fabs(w[k] - exact) / exact;
      std::printf("n=%2d mode %d omega %.10g exact %.10g rel.error %.3e\n", n, k + 1, w[k], exact, e[k]);
    }
    err.push_back(e);
  }
  for (int k = 0; k < 3; ++k) {
    const double rate = std::log2(err[1][k] / err[3][k]) / 2.0;  // n = 8 -> 32
    std::printf("mode %d observed rate %.2f\n", k + 1, rate);
    EXPECT_NEAR(rate, 4.0, 0.3) << "mode " << k + 1;
  }
  // beta_n L are given to 9 digits: 1e-7 resolves them
  EXPECT_LT(err[3][0], 1e-7);
  EXPECT_LT(err[3][1], 1e-6);
  EXPECT_LT(err[3][2], 1e-5);
}

TEST(CantileverModes, ThreeDimensionalCableHasPairsOfBendingModes) {
  const Section s;
  const auto w2 = bendingFrequencies(2, 16, s, 2);
  const auto w3 = bendingFrequencies(3, 16, s, 4);
  ASSERT_EQ(w3.size(), 4u);
  // bending in the two planes through the axis: equal pairs, equal to the 2D values
  EXPECT_NEAR(w3[0] / w2[0], 1.0, 1e-9);
  EXPECT_NEAR(w3[1] / w2[0], 1.0, 1e-9);
  EXPECT_NEAR(w3[2] / w2[1], 1.0, 1e-9);
  EXPECT_NEAR(w3[3] / w2[1], 1.0, 1e-9);
}

// requirement: a clamp holds the slope's direction along any direction (issue 36 item 2): a
// cantilever along a skew direction (held by r'.n = 0 with multipliers, a saddle-point shift-and-
// invert) has the frequencies of the same cantilever along x (held by elimination).
TEST(CantileverModes, SkewClampGivesTheAxisAlignedFrequencies) {
  const Section s{2.1e11, 1e-4, 1e-8, 7850.0};
  for (int dim : {2, 3}) {
    const model::Vec3 skew = dim == 2 ? model::Vec3{0.6, 0.8, 0} : model::Vec3{1.0 / 3, 2.0 / 3, 2.0 / 3};
    const auto ref = bendingFrequencies(dim, 16, s, 6), turned = bendingFrequencies(dim, 16, s, 6, skew);
    ASSERT_EQ(ref.size(), turned.size());
    for (size_t k = 0; k < ref.size(); ++k) {
      std::printf("dim %d mode %zu: along x %.9f rad/s, skew %.9f rad/s\n", dim, k + 1, ref[k], turned[k]);
      EXPECT_NEAR(turned[k] / ref[k], 1.0, 1e-9) << "dim " << dim << " mode " << k + 1;
    }
  }
}
