// Linearized modes of the ALE kinds (issue 35; seed 000): about a steady material flow the inertia
// linearizes to M x'' + G x' + K x = 0 with the transport's gyroscopic G and its stiffness change
// (solvers/ModalSolver.hpp), solved by SLEPc (PEP) on the free coordinates.
//
// requirement: an axially moving string between pinned ends vibrates at
//   omega_n = n pi c / l (1 - v^2 / c^2)       (Wickert & Mote, J. Appl. Mech. 57 (1990);
// seed 000 Eq. 56 for n = 1), c^2 = T / rho_x the wave speed; to 1e-6 in the string limit.
// requirement: an axially moving beam (seed 000 Eq. 54): its first frequencies against the
// independent sine-series Galerkin solution of the equation (support/MovingBeam.hpp), over
// transport speeds up to near the divergence speed v_d^2 = (T + EI (pi / l)^2) / rho_x, at the
// Hermite cubic's rate h^4; the eigenvalues stay purely imaginary (a gyroscopic system).
// requirement: the torsion of a fixed-free shaft (seed 000 sec. 4.2, Table 3), exact
// f_i = (2i - 1) / (4 l) sqrt(G / rho). The linear spin interpolation with the consistent polar
// mass has, on N equal elements of length h, the discrete modes theta_j = sin(k x_j) with the
// exact wave numbers k_i = (2i - 1) pi / (2 l) (the free end is the symmetric extension
// theta_{N+1} = theta_{N-1}, which sin(k x) satisfies when cos(k l) = 0), so each discrete
// frequency is known in closed form:
//   omega_i^h = (c / h) sqrt(6 (1 - cos k_i h) / (2 + cos k_i h)),     i = 1 .. N,
// which exceeds the exact c k_i by (k h)^2 / 24 to leading order.
// requirement: the divergence (critical) transport speed of a span, where its stiffness
// T - rho v^2 meets the bending buckling load: v_d^2 = (T + EI (pi/l)^2) / rho for pinned ends,
// (T + 4 EI (pi/l)^2) / rho for clamped ends (Wickert & Mote 1990; the Euler loads), at the
// Hermite cubic's rate; and a transport_speed sweep reports it. Asserted for modes 1..5 and
// N = 1..10 to 1e-9, with the table printed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "strand/elements/ElementRegistry.hpp"
#include "strand/solvers/ModalSolver.hpp"
#include "strand/solvers/ModeLabels.hpp"
#include "strand/solvers/Sweep.hpp"
#include "support/MovingBeam.hpp"
#include "support/Scenes.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

// A straight span along x on `elements` ALE cable elements, pinned at both ends, prestretched by
// `lambda`, its material flowing at v [m/s] (the nodes stay).
model::SceneDescription movingSpan(int elements, double l, double E, double A, double I, double rho, double lambda,
                                   double v) {
  model::SceneDescription sc;
  sc.file = "(test)";
  sc.dimension = 2;
  sc.analysis = model::Analysis::Modes;
  model::BodyDesc b;
  b.name = "span";
  b.kind = elements::findKind("AleCable2d");
  b.elements = elements;
  b.geometry.kind = model::GeometryKind::Line;
  b.geometry.start = {0, 0, 0};
  b.geometry.end = {l, 0, 0};
  b.section.numbers = {{"E", E}, {"A", A}, {"I", I}, {"rho", rho}};
  b.initialStretch = lambda;
  b.hasMaterialMotion = true;
  b.materialMotion.kind = model::TimeFunction::Kind::Linear;
  b.materialMotion.rate = -v / lambda;
  sc.bodies.push_back(b);
  pinEnds(sc, "span");
  return sc;
}

struct Modes {
  std::vector<double> omega, residual;
  double maxRealPart = 0.0;
  std::string method;
  double divergenceFactor = 0.0;
  std::vector<std::string> labels;  // solvers/ModeLabels.hpp
};

Modes modesOf(const model::SceneDescription& sc, int count) {
  solvers::Problem p(PETSC_COMM_WORLD, sc);
  Vec X;
  PetscCallAbort(PETSC_COMM_WORLD, p.dofs().createVector(&X));
  PetscCallAbort(PETSC_COMM_WORLD, p.assembler().initialState(X));
  solvers::ModalOptions opt;
  opt.count = count;
  solvers::ModalResult r;
  double factor = 0.0;
  std::vector<solvers::ModeLabel> labels;
  {
    solvers::ModalSolver s(p.assembler(), opt);
    PetscCallAbort(PETSC_COMM_WORLD, s.solve(X, &r));
    PetscCallAbort(PETSC_COMM_WORLD, s.divergenceFactor(&factor));
    PetscCallAbort(PETSC_COMM_WORLD, solvers::labelModes(p.assembler(), s.massMatrix(), r, &labels));
  }
  Modes m{r.omega, r.relativeResidual, r.maxRealPart, r.method, factor, {}};
  for (const solvers::ModeLabel& l : labels) m.labels.push_back(l.name);
  solvers::destroyModes(&r);
  VecDestroy(&X);
  return m;
}

}  // namespace

TEST(AleModes, AxiallyMovingStringHasWickertMoteFrequencies) {
  // steel wire r = 1 mm, l = 1 m, Green strain 8.79e-5 (T = 55.2 N, c = 47.47 m/s)
  const double l = 1.0, E = 2e11, A = M_PI * 1e-6, rho = 7800.0, eps = 8.7895e-5, lam = std::sqrt(1.0 + 2.0 * eps);
  const double T = E * A * eps * lam, rhoX = rho * A / lam, c = std::sqrt(T / rhoX);
  for (double v : {0.0, 10.0, 30.0}) {
    // I = 1e-24 m^4: the bending stiffness EI (n pi / l)^2 adds 2e-13 relative to T (with I = 1e-18
    // it added 2.9e-7 to mode 4's frequency: the string formula holds only in the limit)
    const Modes m = modesOf(movingSpan(64, l, E, A, 1e-24, rho, lam, v), 4);  // h^4: 1.3e-6 for mode 4 at N = 32
    ASSERT_EQ(m.omega.size(), 4u);
    EXPECT_EQ(m.method, v > 0.0 ? "pep" : "eps");
    EXPECT_LT(m.maxRealPart, 1e-8) << "purely imaginary eigenvalues";
    for (int n = 1; n <= 4; ++n) {
      const double exact = n * M_PI * c / l * (1.0 - v * v / (c * c));
      const double err = std::fabs(m.omega[n - 1] / exact - 1.0);
      std::printf("v = %4.1f m/s  mode %d: %.8f Hz (exact %.8f Hz), error %.2e, residual %.1e\n", v, n,
                  m.omega[n - 1] / (2 * M_PI), exact / (2 * M_PI), err, m.residual[n - 1]);
      EXPECT_LT(err, 1e-6) << "v " << v << " mode " << n;
      EXPECT_LT(m.residual[n - 1], 1e-8);
      EXPECT_EQ(m.labels[n - 1], "bending");  // in the plane, across the span (issue 36 item 4)
    }
  }
}

TEST(AleModes, AxiallyMovingBeamMatchesTheGalerkinSolutionAtRateFour) {
  const double l = 1.0, rho = 7800.0, E = 2e11, r = 2e-3, A = M_PI * r * r, I = M_PI * std::pow(r, 4) / 4.0;
  const double eps = 8e-5, lam = std::sqrt(1.0 + 2.0 * eps);
  const double rhoX = rho * A / lam, EI = E * I / lam, T = E * A * eps * lam;
  const double vd = std::sqrt((T + EI * M_PI * M_PI / (l * l)) / rhoX);  // divergence speed (pinned ends)
  std::printf("divergence speed %.4f m/s\n", vd);
  for (double v : {0.0, 20.0, 35.0, 0.95 * vd}) {
    const MovingBeam ref{rhoX, EI, T, v, l};
    const auto exact = ref.modes(40, 3);
    std::vector<std::vector<double>> err;
    for (int n : {4, 8, 16}) {
      const Modes m = modesOf(movingSpan(n, l, E, A, I, rho, lam, v), 3);
      ASSERT_EQ(m.omega.size(), 3u);
      EXPECT_LT(m.maxRealPart, 1e-8);
      std::vector<double> e;
      for (int k = 0; k < 3; ++k) {
        e.push_back(std::fabs(m.omega[k] / exact[k].omega - 1.0));
        std::printf("v = %6.3f m/s, N = %2d, mode %d: %.6f Hz (Galerkin %.6f Hz), error %.2e\n", v, n, k + 1,
                    m.omega[k] / (2 * M_PI), exact[k].omega / (2 * M_PI), e.back());
      }
      err.push_back(e);
    }
    const double bound[3] = {2e-5, 2e-4, 5e-4};  // at N = 16; measured up to 1.6e-5, 1.2e-4, 3.3e-4 (0.95 v_d)
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT(err[2][k], bound[k]) << "v " << v << " mode " << k + 1;
      if (err[2][k] > 1e-9) {
        EXPECT_NEAR(std::log2(err[1][k] / err[2][k]), 4.0, 0.5) << "v " << v << " mode " << k + 1;
      }
    }
  }
}

TEST(AleModes, FixedFreeShaftTorsionHasTheClosedFormOfLinearElements) {
  const double l = 1.0, E = 2.1e11, nu = 0.3, rho = 7850.0, R = 0.02;
  const double c = std::sqrt(E / (2.0 * (1.0 + nu)) / rho);
  std::printf(" N  mode  f_h [Hz]        closed form     exact           error vs exact\n");
  for (int N = 1; N <= 10; ++N) {
    model::SceneDescription sc;
    sc.file = "(test)";
    sc.dimension = 3;
    sc.analysis = model::Analysis::Modes;
    model::BodyDesc b;
    b.name = "shaft";
    b.kind = elements::findKind("AleBeamShaft3d");
    b.elements = N;
    b.geometry.kind = model::GeometryKind::Line;
    b.geometry.start = {0, 0, 0};
    b.geometry.end = {l, 0, 0};
    b.section.numbers = {{"E", E}, {"nu", nu}, {"rho", rho}, {"radius", R}, {"inner_radius", 0.0}};
    sc.bodies.push_back(b);
    // every node's position and slope held: only the spin angles move (the root's is held too)
    for (long node = 0; node <= N; ++node) {
      model::SupportDesc s;
      s.at.body = "shaft";
      s.at.node = node;
      s.type = model::SupportType::Fixed;
      s.dofs = {0, 1, 2, 3, 4, 5};
      if (node == 0) s.dofs.push_back(7);  // theta (block 2: p, theta)
      sc.supports.push_back(s);
    }
    const int count = std::min(N, 5);
    const Modes m = modesOf(sc, count);
    ASSERT_EQ(static_cast<int>(m.omega.size()), count) << "N " << N;
    const double h = l / N;
    for (int i = 1; i <= count; ++i) {
      const double k = (2 * i - 1) * M_PI / (2 * l);
      const double closed = c / h * std::sqrt(6.0 * (1.0 - std::cos(k * h)) / (2.0 + std::cos(k * h)));
      const double exact = c * k;
      std::printf("%2d  %d  %14.6f  %14.6f  %14.6f  %.3e\n", N, i, m.omega[i - 1] / (2 * M_PI), closed / (2 * M_PI),
                  exact / (2 * M_PI), m.omega[i - 1] / exact - 1.0);
      EXPECT_NEAR(m.omega[i - 1] / closed, 1.0, 1e-9) << "N " << N << " mode " << i;
      EXPECT_EQ(m.labels[i - 1], "torsion") << "N " << N << " mode " << i;  // issue 36 item 4
    }
  }
}

TEST(AleModes, DivergenceSpeedOfPinnedAndClampedSpans) {
  const double l = 1.0, rho = 7800.0, E = 2e11, r = 2e-3, A = M_PI * r * r, I = M_PI * std::pow(r, 4) / 4.0;
  const double eps = 8e-5, lam = std::sqrt(1.0 + 2.0 * eps);
  const double rhoX = rho * A / lam, EI = E * I / lam, T = E * A * eps * lam;
  for (model::SupportType ends : {model::SupportType::Pinned, model::SupportType::Clamped}) {
    const double euler = (ends == model::SupportType::Pinned ? 1.0 : 4.0) * EI * M_PI * M_PI / (l * l);
    const double vd = std::sqrt((T + euler) / rhoX);
    std::vector<double> err;
    for (int n : {4, 8, 16}) {
      auto sc = movingSpan(n, l, E, A, I, rho, lam, 10.0);
      for (auto& s : sc.supports) s.type = ends;
      const Modes m = modesOf(sc, 1);
      err.push_back(std::fabs(10.0 * m.divergenceFactor / vd - 1.0));
      std::printf("%s ends, N = %2d: v_d = %.8f m/s (exact %.8f m/s), error %.2e\n",
                  ends == model::SupportType::Pinned ? "pinned" : "clamped", n, 10.0 * m.divergenceFactor, vd, err.back());
    }
    EXPECT_LT(err[2], 1e-5);
    EXPECT_NEAR(std::log2(err[1] / err[2]), 4.0, 0.5);
  }
}

TEST(AleModes, TransportSpeedSweepReportsTheCriticalSpeed) {
  const double l = 1.0, rho = 7800.0, E = 2e11, r = 2e-3, A = M_PI * r * r, I = M_PI * std::pow(r, 4) / 4.0;
  const double eps = 8e-5, lam = std::sqrt(1.0 + 2.0 * eps);
  auto sc = movingSpan(16, l, E, A, I, rho, lam, 0.0);
  sc.bodies[0].hasMaterialMotion = false;
  sc.modes.count = 3;
  sc.sweep.present = true;
  sc.sweep.parameter = model::SweepParameter::TransportSpeed;
  sc.sweep.from = 0.0;
  sc.sweep.to = 40.0;
  sc.sweep.points = 5;
  solvers::SweepResult res;
  PetscCallAbort(PETSC_COMM_WORLD, solvers::runSweep(PETSC_COMM_WORLD, sc, &res));
  ASSERT_EQ(res.parameter.size(), 5u);
  const double reference = 10.0 * modesOf(movingSpan(16, l, E, A, I, rho, lam, 10.0), 1).divergenceFactor;
  EXPECT_NEAR(res.criticalSpeed / reference, 1.0, 1e-9);
  for (size_t i = 0; i < res.parameter.size(); ++i) {
    const Modes m = modesOf(movingSpan(16, l, E, A, I, rho, lam, res.parameter[i]), 3);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(res.omega[i][k] / m.omega[k], 1.0, 1e-9) << "point " << i;
    if (i > 0) {
      EXPECT_LT(res.omega[i][0], res.omega[i - 1][0]);  // the first frequency falls with the speed
    }
  }
}
