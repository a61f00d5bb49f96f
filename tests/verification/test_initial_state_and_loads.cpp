// Verification of initial velocities of cables and time-dependent loads (issue 3), at -n 1 and -n 2,
// on a free 1 m rope (8 AncfCable2d elements, EA = 1e4 N, EI = 1 N m^2, no supports, no gravity):
//  1. Started with the rigid velocity field v = v_lin + w x (r - c) about its centre c (scene key
//     bodies[].initial_velocity), the centre of mass moves exactly with v_lin (no force:
//     momentum theorem; the scheme's update of the total momentum is exact), and the angular
//     momentum L = int rho A r x v dx = sum_a q_a x (M v)_a is conserved by the exact motion;
//     generalized-alpha rho_inf = 1 keeps it to O(h^2) (rate 2 asserted).
//  2. A nodal force F0 sin(2 pi f t) e_y at the free end (loads.nodal[].function): the centre of
//     mass obeys m y_cm'' = F0 sin(omega t) whatever the body deforms, so from rest
//     y_cm(t) = (F0 / m)(t / omega - sin(omega t) / omega^2). Generalized-alpha (rho_inf 0.9) and
//     BDF2 converge to it at rate 2; the energy balance T + U - W_t (W_t = int v.f(t) dt) stays
//     constant to O(h^2).
//  3. Gravity scaled by a time function (loads.function: sine): likewise m y_cm'' = -m g sin(omega t),
//     y_cm(t) = -g (t / omega - sin(omega t) / omega^2); generalized-alpha converges at rate 2.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "strand/solvers/Dynamics.hpp"
#include "support/Pendulum.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

constexpr double kF0 = 1.0, kFrequency = 2.0;

model::SceneDescription freeRope() {
  model::SceneDescription sc = flexiblePendulum();
  sc.supports.clear();
  sc.loads.gravity = {0, 0, 0};
  sc.analysis = model::Analysis::Dynamic;
  return sc;
}

struct Observed {
  double dxcm = 0, dycm = 0;     // displacement of the centre of mass
  double px = 0, py = 0, L = 0;  // momentum, angular momentum about the origin
  double mass = 0, maxBalance = 0, loadWork = 0;
};

// p = M V and M X in model order; sums over position coordinates give the momentum and m * x_cm.
Observed observe(solvers::Problem& p, Vec X, Vec V) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  Mat M;
  Vec MX, MV;
  PetscCallAbort(comm, p.dofs().createMatrix(&M, nullptr));
  PetscCallAbort(comm, p.assembler().massMatrix(M, false));
  PetscCallAbort(comm, VecDuplicate(X, &MX));
  PetscCallAbort(comm, VecDuplicate(X, &MV));
  PetscCallAbort(comm, MatMult(M, X, MX));
  PetscCallAbort(comm, MatMult(M, V, MV));
  std::vector<double> mx, mv, q;
  PetscCallAbort(comm, p.assembler().toModelOrder(MX, mx));
  PetscCallAbort(comm, p.assembler().toModelOrder(MV, mv));
  PetscCallAbort(comm, p.assembler().gatherToRoot(X, q));
  Observed o;
  const model::Body& b = p.model().bodies()[0];
  o.mass = b.properties.rhoA * b.length;
  double v[6] = {0, 0, 0, 0, 0, 0};
  if (!q.empty()) {
    for (int n = 0; n <= b.elements; ++n) {
      const int pb = b.posBlock[n], sb = b.block(n, 1);
      v[0] += mx[2 * pb];
      v[1] += mx[2 * pb + 1];
      v[2] += mv[2 * pb];
      v[3] += mv[2 * pb + 1];
      for (int blk : {pb, sb}) v[4] += q[2 * blk] * mv[2 * blk + 1] - q[2 * blk + 1] * mv[2 * blk];
    }
  }
  MPI_Bcast(v, 6, MPI_DOUBLE, 0, comm);
  o.dxcm = v[0] / o.mass;
  o.dycm = v[1] / o.mass;
  o.px = v[2];
  o.py = v[3];
  o.L = v[4];
  MatDestroy(&M);
  VecDestroy(&MX);
  VecDestroy(&MV);
  return o;
}

struct Trajectory {
  Observed start, end;
};

Trajectory run(const model::SceneDescription& sc, const model::DynamicsDesc& d) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  solvers::Problem p(comm, sc);
  Vec X, V;
  PetscCallAbort(comm, p.createInitialState(&X, &V));
  Trajectory r;
  r.start = observe(p, X, V);
  solvers::Dynamics dyn(p.assembler(), d);
  double e0 = 0.0, maxBalance = 0.0, loadWork = 0.0;
  solvers::Dynamics::StepCallback cb = [&](const solvers::DynamicsStep& s, Vec, Vec) -> PetscErrorCode {
    if (s.step == 0) e0 = s.energy();
    maxBalance = std::max(maxBalance, std::fabs(s.energy() - e0));
    loadWork = std::max(loadWork, std::fabs(s.loadWork));
    return 0;
  };
  std::string failure;
  PetscCallAbort(comm, dyn.run(X, V, cb, &failure));
  EXPECT_EQ(failure, "");
  r.end = observe(p, X, V);
  r.end.maxBalance = maxBalance;
  r.end.loadWork = loadWork;
  VecDestroy(&X);
  VecDestroy(&V);
  return r;
}

}  // namespace

TEST(InitialStateAndLoads, AFreeRopeKeepsItsMomentumAndAngularMomentum) {
  model::SceneDescription sc = freeRope();
  model::BodyDesc& b = sc.bodies[0];
  b.section.set("damping_axial", 3e-4);  // Kelvin-Voigt: objective, so it keeps L too
  b.section.set("damping_bending", 3e-4);  // Kelvin-Voigt: objective, so it keeps L too
  b.hasInitialVelocity = true;
  b.linearVelocity = {1.0, 0.5, 0.0};
  b.angularVelocity = {0.0, 0.0, 2.0};
  b.velocityCenter = {0.5, 0.0, 0.0};
  const double tEnd = 1.0;
  double drift[3];
  for (int k = 0; k < 3; ++k) {
    const Trajectory r = run(sc, scheme(model::Integrator::GeneralizedAlpha, 1.0, 2e-3 / (1 << k), tEnd));
    // expected from the field: p = m v_lin (the centre is the centre of mass), L about the origin
    // = r_cm x m v_lin + J_cm w with J_cm = m l^2 / 12 for the straight rope
    const double m = r.start.mass, L0 = 0.5 * m * 0.5 + m * 1.0 / 12.0 * 2.0;
    EXPECT_NEAR(r.start.px, m * 1.0, 1e-12 * m);
    EXPECT_NEAR(r.start.py, m * 0.5, 1e-12 * m);
    EXPECT_NEAR(r.start.L, L0, 1e-12 * L0);
    EXPECT_NEAR(r.end.dxcm, 1.0 * tEnd, 1e-10);
    EXPECT_NEAR(r.end.dycm, 0.5 * tEnd, 1e-10);
    EXPECT_NEAR(r.end.px, r.start.px, 1e-10 * m);  // round-off of up to 4000 steps
    drift[k] = std::fabs(r.end.L - r.start.L) / r.start.L;
    std::printf("h = %.1e: centre of mass moved (%.12f, %.12f) m (exact (1, 0.5)); angular momentum %.10e -> %.10e "
                "(relative drift %.3e)\n",
                2e-3 / (1 << k), r.end.dxcm, r.end.dycm, r.start.L, r.end.L, drift[k]);
  }
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(std::log2(drift[k] / drift[k + 1]), 2.0, 0.2);
}

TEST(InitialStateAndLoads, ATimedForceMovesTheCentreOfMassByNewtonsLaw) {
  model::SceneDescription sc = freeRope();
  model::NodalLoadDesc load;
  load.at.body = sc.bodies[0].name;
  load.at.node = -1;
  load.force = {0.0, kF0, 0.0};
  load.timed = true;
  load.function.kind = model::TimeFunction::Kind::Sine;
  load.function.amplitude = 1.0;
  load.function.frequency = kFrequency;
  sc.loads.nodal.push_back(load);
  const double tEnd = 0.5, w = 2.0 * M_PI * kFrequency;
  model::DynamicsDesc bdf2 = scheme(model::Integrator::Bdf, 1.0, 0, tEnd);
  bdf2.bdfOrder = 2;
  const struct {
    const char* name;
    model::DynamicsDesc d;
  } cases[] = {{"alpha 0.9", scheme(model::Integrator::GeneralizedAlpha, 0.9, 0, tEnd)}, {"bdf2", bdf2}};
  for (const auto& c : cases) {
    double err[3], balance[3];
    for (int k = 0; k < 3; ++k) {
      model::DynamicsDesc d = c.d;
      d.dt = 2e-3 / (1 << k);
      const Trajectory r = run(sc, d);
      const double exact = kF0 / r.start.mass * (tEnd / w - std::sin(w * tEnd) / (w * w));
      err[k] = std::fabs(r.end.dycm - exact);
      balance[k] = r.end.maxBalance / r.end.loadWork;
      std::printf("%-9s h = %.1e: y_cm %.10e (exact %.10e, error %.3e); |energy balance| / |W_t| %.3e\n", c.name, d.dt,
                  r.end.dycm, exact, err[k], balance[k]);
    }
    for (int k = 0; k < 2; ++k) EXPECT_NEAR(std::log2(err[k] / err[k + 1]), 2.0, 0.15) << c.name;
    EXPECT_LT(balance[2], balance[0]) << c.name;
  }
}

TEST(InitialStateAndLoads, TimeScaledGravityMovesTheCentreOfMassByNewtonsLaw) {
  model::SceneDescription sc = freeRope();
  sc.loads.gravity = {0.0, -9.81, 0.0};
  sc.loads.timed = true;
  sc.loads.function.kind = model::TimeFunction::Kind::Sine;
  sc.loads.function.amplitude = 1.0;
  sc.loads.function.frequency = kFrequency;
  const double tEnd = 0.5, w = 2.0 * M_PI * kFrequency;
  const double exact = -9.81 * (tEnd / w - std::sin(w * tEnd) / (w * w));
  double err[3];
  for (int k = 0; k < 3; ++k) {
    const Trajectory r = run(sc, scheme(model::Integrator::GeneralizedAlpha, 0.9, 2e-3 / (1 << k), tEnd));
    err[k] = std::fabs(r.end.dycm - exact);
    std::printf("gravity x sin: h = %.1e: y_cm %.10e (exact %.10e, error %.3e); |energy balance| / |W| %.3e\n",
                2e-3 / (1 << k), r.end.dycm, exact, err[k], r.end.maxBalance / r.end.loadWork);
  }
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(std::log2(err[k] / err[k + 1]), 2.0, 0.15);
}
