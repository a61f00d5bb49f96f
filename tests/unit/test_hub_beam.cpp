// The floating-frame hub-beam's discretizations and equations (src/ffr, issue 5):
//  1. FEM and RPIM shapes have the Kronecker property at the nodes (seed 001 Eq. 37): deflection
//     and rotation coordinates are the nodal values.
//  2. The non-rotating clamped-free beam: bending frequencies beta_n^2 sqrt(EI / (rho A L^4)) with
//     beta_n L = 1.8751041, 4.6940911, 7.8547574, and the axial (2n - 1) pi / 2 sqrt(E / rho) / L;
//     Hermite FEM converges at rate 4 (eigenvalue error O(h^(2(p+1-m))), p = 3, m = 2); RPIM's
//     Kronecker defect is round-off times the moment matrices' condition number.
//  3. The first-order model's stiffening matrix Gc (seed 001's a C + D): the flapwise operator
//     K_b + Omega^2 Gc gives the rotating cantilever's frequencies of Wright et al. 1982 / the
//     project's 10-digit Frobenius series (tests/verification/test_rotating_modes.cpp), hub radius
//     included, for all three bases.
//  4. Taylor test of the exact Jacobian of the free-hub residual (nonlinear): error ratio 4 per halving.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "strand/ffr/AssumedModes.hpp"
#include "strand/ffr/HermiteFem.hpp"
#include "strand/ffr/HubBeam.hpp"
#include "strand/ffr/RadialPointInterpolation.hpp"

using namespace strand;
using namespace strand::ffr;

namespace {

// L = 1, EI / (rho A L^4) = 1: frequencies come out dimensionless
model::HubBeamDesc unitBeam(model::HubBeamMethod method) {
  model::HubBeamDesc d;
  d.present = true;
  d.length = 1.0;
  d.E = 1e4;
  d.A = 1e-2;
  d.I = 1e-6;  // EI = 1e-2
  d.rho = 1.0;  // rho A = 1e-2 -> EI / (rho A) = 1
  d.method = method;
  d.angle.kind = model::TimeFunction::Kind::Constant;
  return d;
}

// bending-only (flapwise) generalized eigenvalues of (K_b + Omega^2 Gc, M_b), ascending sqrt
std::vector<double> flapwise(const HubBeamMatrices& m, const DeformationBasis& basis, double omega) {
  // bending coordinates: those with a non-zero bending shape somewhere
  const int n = basis.size();
  std::vector<int> idx;
  ShapeRows r;
  Eigen::VectorXd used = Eigen::VectorXd::Zero(n);
  for (const QuadraturePoint& qp : basis.quadrature()) {
    basis.shapes(qp.x, r);
    used += r.bending.transpose().cwiseAbs();
  }
  for (int i = 0; i < n; ++i)
    if (used[i] > 0) idx.push_back(i);
  const int nb = static_cast<int>(idx.size());
  Eigen::MatrixXd K(nb, nb), M(nb, nb);
  for (int i = 0; i < nb; ++i)
    for (int j = 0; j < nb; ++j) {
      K(i, j) = m.K(idx[i], idx[j]) + omega * omega * m.Gc(idx[i], idx[j]);
      M(i, j) = m.M(idx[i], idx[j]);
    }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
  std::vector<double> w;
  for (int i = 0; i < nb; ++i) w.push_back(std::sqrt(es.eigenvalues()[i]));
  return w;
}

const double kBeta[3] = {1.8751040687, 4.6940911330, 7.8547574382};

}  // namespace

TEST(HubBeamBasis, KroneckerPropertyAtNodes) {
  HermiteFem fem(2.0, 4);
  RadialPointInterpolation rpim(2.0, RpimParameters{6, 3.0, 1.03, 2.5, 4});
  for (const DeformationBasis* b : {static_cast<const DeformationBasis*>(&fem), static_cast<const DeformationBasis*>(&rpim)}) {
    const int nodes = b->size() / 3;
    ShapeRows r;
    double worst = 0.0;
    for (int k = 1; k <= nodes; ++k) {
      b->shapes(k * 2.0 / nodes, r);
      for (int c = 0; c < b->size(); ++c) {
        const int node = c / 3 + 1, kind = c % 3;
        const double one = node == k ? 1.0 : 0.0;
        worst = std::max(worst, std::abs(r.axial[c] - (kind == 0 ? one : 0.0)));
        worst = std::max(worst, std::abs(r.bending[c] - (kind == 1 ? one : 0.0)));
        worst = std::max(worst, std::abs(r.bendingSlope[c] - (kind == 2 ? one : 0.0)));
      }
    }
    // RPIM solves its moment matrices: round-off grows with their condition number
    const auto* rp = dynamic_cast<const RadialPointInterpolation*>(b);
    const double bound = rp ? 10 * 2.2e-16 / rp->worstReciprocalCondition() : 1e-15;
    std::printf("%s: Kronecker defect %.2e (bound %.2e)\n", b->name().c_str(), worst, bound);
    EXPECT_LT(worst, bound) << b->name();
  }
}

TEST(HubBeamBasis, NonRotatingCantileverFrequencies) {
  auto check = [](const model::HubBeamDesc& d, double tol) {
    const auto basis = makeBasis(d);
    const HubBeamMatrices m = integrateMatrices(*basis, d);
    const std::vector<double> w = flapwise(m, *basis, 0.0);
    double worst = 0.0;
    for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(w[k] / (kBeta[k] * kBeta[k]) - 1.0));
    std::printf("%-28s bending 1-3: %.8f %.8f %.8f  worst rel. error %.2e\n", basis->name().c_str(), w[0], w[1], w[2],
                worst);
    EXPECT_LT(worst, tol) << basis->name();
    return worst;
  };
  model::HubBeamDesc d = unitBeam(model::HubBeamMethod::AssumedModes);
  d.axialModes = d.bendingModes = 5;
  check(d, 1e-10);  // the modes are the exact eigenfunctions
  d.method = model::HubBeamMethod::Fem;
  double prev = 0.0;
  for (int n : {8, 16, 32}) {
    d.elements = n;
    const double e = check(d, 1e-3);
    if (prev > 0) {
      std::printf("  rate %.2f\n", std::log2(prev / e));
      EXPECT_NEAR(std::log2(prev / e), 4.0, 0.3);
    }
    prev = e;
  }
  d.method = model::HubBeamMethod::Rpim;
  d.nodes = 11;
  check(d, 2e-5);  // measured 7.4e-6 (cell supports; 2.4e-4 with point supports)
}

TEST(HubBeamMatrices, StiffeningMatchesFrobeniusSeries) {
  struct Row { double delta, gamma, w[3]; };  // tests/verification/test_rotating_modes.cpp
  const Row rows[] = {{0.0, 1, {3.681646814, 22.18101115, 61.84176259}},
                      {0.0, 12, {13.17015049, 37.60311233, 79.61447849}},
                      {0.5, 2, {4.499271759, 22.99373252, 62.67185564}},
                      {1.0, 10, {16.60636284, 44.36822392, 89.15632883}}};
  struct Case { model::HubBeamMethod method; int size; double tol; };
  const Case cases[] = {{model::HubBeamMethod::Fem, 32, 2e-5}, {model::HubBeamMethod::Rpim, 21, 1e-5},
                        {model::HubBeamMethod::AssumedModes, 7, 2e-2}};
  for (const Case& c : cases) {
    for (const Row& row : rows) {
      model::HubBeamDesc d = unitBeam(c.method);
      d.elements = c.size;
      d.nodes = c.size;
      d.axialModes = d.bendingModes = c.size;
      d.hubRadius = row.delta;
      const auto basis = makeBasis(d);
      const HubBeamMatrices m = integrateMatrices(*basis, d);
      const std::vector<double> w = flapwise(m, *basis, row.gamma);
      double worst = 0.0;
      for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(w[k] / row.w[k] - 1.0));
      std::printf("%-28s delta %.1f gamma %4.1f: %.8f %.8f %.8f  worst rel. error %.2e\n", basis->name().c_str(),
                  row.delta, row.gamma, w[0], w[1], w[2], worst);
      EXPECT_LT(worst, c.tol) << basis->name();
    }
  }
}

TEST(HubBeam, JacobianTaylorTestFreeHub) {
  for (auto method : {model::HubBeamMethod::Fem, model::HubBeamMethod::AssumedModes, model::HubBeamMethod::Rpim}) {
    model::HubBeamDesc d = unitBeam(method);
    d.elements = 3;
    d.nodes = 4;
    d.driven = false;
    d.hubInertia = 0.3;
    d.hubRadius = 0.2;
    d.torque.kind = model::TimeFunction::Kind::Constant;
    d.torque.value = 0.7;
    const HubBeam hb(d);
    const int n = hb.size();
    std::srand(7);
    const Eigen::VectorXd q = 0.1 * Eigen::VectorXd::Random(n), v = Eigen::VectorXd::Random(n),
                          a = Eigen::VectorXd::Random(n), dir = Eigen::VectorXd::Random(n);
    const double sV = 3.0, sA = 11.0;
    Eigen::VectorXd F0, F1;
    Eigen::MatrixXd J;
    hb.residual(0.5, q, v, a, F0);
    hb.jacobian(0.5, q, v, a, sV, sA, J);
    double prev = 0.0;
    for (double eps : {1e-2, 5e-3, 2.5e-3}) {
      hb.residual(0.5, q + eps * dir, v + eps * sV * dir, a + eps * sA * dir, F1);
      const double err = (F1 - F0 - eps * J * dir).norm();
      if (prev > 0) {
        std::printf("%s: Taylor ratio %.4f\n", hb.basis().name().c_str(), prev / err);
        EXPECT_NEAR(prev / err, 4.0, 0.05);
      }
      prev = err;
    }
  }
}
