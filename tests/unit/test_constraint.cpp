// Joint constraint kernels (include/strand/elements/Constraint.hpp).
// requirement: the gradient G = dg/dq and the contracted Hessian H(w) = d(G^T w)/dq are the exact
// derivatives: Taylor tests whose remainders fall as h^2 (g(q + h d) - g - h G d, and
// G(q + h d)^T w - G^T w - h H d), for every form (equal, distance, orthogonal) with constant, block
// and rigid-body fields, in 2D and 3D; H is symmetric.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "strand/elements/Constraint.hpp"

using namespace strand::elements;

namespace {

JointField constant(double x, double y, double z) {
  JointField f;
  f.kind = JointField::Kind::Constant;
  f.c = {x, y, z};
  return f;
}
JointField block(int k) {
  JointField f;
  f.kind = JointField::Kind::Block;
  f.block = k;
  return f;
}
JointField rigid(JointField::Kind kind, int k, double x, double y) {
  JointField f;
  f.kind = kind;
  f.block = k;
  f.c = {x, y, 0.0};
  return f;
}

// Largest Taylor remainders of g and of G^T w for steps h and h/2, per equation row; returns the
// observed rates (log2 of the ratio), the smaller of the two tests.
template <int D>
double taylorRate(const ConstraintEq& eq, int nBlocks, unsigned seed) {
  using C = Constraint<D>;
  const int n = nBlocks * D, m = C::equations(eq);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> q(n), d(n), w(m);
  for (double& x : q) x = u(rng);
  for (double& x : d) x = u(rng);
  for (double& x : w) x = u(rng);
  auto remainders = [&](double h, double* rg, double* rG) {
    std::vector<double> g0(m), G0(m * n), g1(m), G1(m * n), H(n * n, 0.0), qh(n);
    C::evaluate(eq, q.data(), n, g0.data(), G0.data());
    C::addHessian(eq, q.data(), n, w.data(), 1.0, H.data());
    for (int i = 0; i < n; ++i) qh[i] = q[i] + h * d[i];
    C::evaluate(eq, qh.data(), n, g1.data(), G1.data());
    *rg = *rG = 0.0;
    for (int k = 0; k < m; ++k) {
      double Gd = 0.0;
      for (int j = 0; j < n; ++j) Gd += G0[k * n + j] * d[j];
      *rg = std::max(*rg, std::fabs(g1[k] - g0[k] - h * Gd));
    }
    for (int j = 0; j < n; ++j) {
      double t1 = 0.0, t0 = 0.0, Hd = 0.0;
      for (int k = 0; k < m; ++k) {
        t1 += G1[k * n + j] * w[k];
        t0 += G0[k * n + j] * w[k];
      }
      for (int i = 0; i < n; ++i) Hd += H[j * n + i] * d[i];
      *rG = std::max(*rG, std::fabs(t1 - t0 - h * Hd));
    }
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) EXPECT_NEAR(H[i * n + j], H[j * n + i], 1e-14) << "H not symmetric";
  };
  double g1, G1, g2, G2;
  remainders(1e-3, &g1, &G1);
  remainders(5e-4, &g2, &G2);
  double rate = 99.0;
  if (g1 > 1e-13) rate = std::min(rate, std::log2(g1 / g2));
  if (G1 > 1e-13) rate = std::min(rate, std::log2(G1 / G2));
  return rate;  // 99: the form is linear in the chosen fields (remainder at round-off)
}

}  // namespace

TEST(Constraint, PinOfTwoRigidBodiesHasExactDerivatives2d) {
  ConstraintEq eq;  // rigid point of body A (blocks 0, 1) = rigid point of body B (blocks 2, 3)
  eq.a = rigid(JointField::Kind::RigidPoint, 0, 0.3, -0.2);
  eq.b = rigid(JointField::Kind::RigidPoint, 2, -0.5, 0.1);
  const double r = taylorRate<2>(eq, 4, 1);
  EXPECT_GT(r, 1.9);
  EXPECT_LT(r, 2.1);
}

TEST(Constraint, PinOfACableNodeToTheGroundIsLinear3d) {
  ConstraintEq eq;
  eq.a = block(0);
  eq.b = constant(1.0, 2.0, 3.0);
  EXPECT_EQ(taylorRate<3>(eq, 1, 2), 99.0);
}

TEST(Constraint, DistanceBetweenARigidPointAndACableNodeHasExactDerivatives) {
  ConstraintEq eq;
  eq.form = ConstraintForm::Distance;
  eq.length = 0.7;
  eq.a = rigid(JointField::Kind::RigidPoint, 0, 0.4, 0.3);
  eq.b = block(2);
  EXPECT_NEAR(taylorRate<2>(eq, 3, 3), 2.0, 0.1);
  ConstraintEq e3;  // 3D: between two cable nodes
  e3.form = ConstraintForm::Distance;
  e3.length = 1.0;
  e3.a = block(0);
  e3.b = block(1);
  EXPECT_NEAR(taylorRate<3>(e3, 2, 4), 2.0, 0.1);
}

TEST(Constraint, SlopeNormalToARigidDirectionHasExactDerivatives) {
  ConstraintEq eq;  // clamp's orientation part: cable slope (block 0) . R(phi) n (phi in block 1)
  eq.form = ConstraintForm::Orthogonal;
  eq.a = block(0);
  eq.b = rigid(JointField::Kind::RigidDirection, 1, 0.0, 1.0);
  EXPECT_NEAR(taylorRate<2>(eq, 2, 5), 2.0, 0.1);
}

TEST(Constraint, ValuesAtAKnownState) {
  // rigid body at (1, 2), phi = pi/2: its body point (0.5, 0) is at (1, 2.5); a pin to (1, 2.5) holds
  ConstraintEq eq;
  eq.a = rigid(JointField::Kind::RigidPoint, 0, 0.5, 0.0);
  eq.b = constant(1.0, 2.5, 0.0);
  const double q[4] = {1.0, 2.0, M_PI / 2, 0.0};
  double g[2], G[8];
  Constraint<2>::evaluate(eq, q, 4, g, G);
  EXPECT_NEAR(g[0], 0.0, 1e-15);
  EXPECT_NEAR(g[1], 0.0, 1e-15);
  // d/dphi of R(phi) (0.5, 0) at pi/2 is (-0.5, 0)
  EXPECT_NEAR(G[0 * 4 + 2], -0.5, 1e-15);
  EXPECT_NEAR(G[1 * 4 + 2], 0.0, 1e-15);
  ConstraintEq dist;
  dist.form = ConstraintForm::Distance;
  dist.length = 2.0;
  dist.a = constant(0.0, 0.0, 0.0);
  dist.b = constant(3.0, 4.0, 0.0);
  Constraint<2>::evaluate(dist, q, 4, g, G);
  EXPECT_NEAR(g[0], 3.0, 1e-15);  // |(3, 4)| - 2
}
