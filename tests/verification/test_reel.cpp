// Verification of reels paying out an ALE tether (model::ReelDesc; seed 000; issue 35).
//
// A steel tether (r = 5 mm, 10 m) hangs from a fixed exit point with a 5 kg block pinned to its
// end (3D: on a spherical joint); gravity is ramped in over 1 s. Its material comes off a reel of
// radius R whose angle phi pays it out at the exit node (node 0): p_0 = p_0(0) - R phi, the nodes
// below equally spaced in material (Eq. 51), the end's material held.
//
// requirement (torque control): a braked reel. With the tether stiff (strain ~1e-5), the reel, the
// wound material, the hanging tether and the block form one degree of freedom phi, the paid-out
// length l = l0 + R phi. Their kinetic energy is M phi'^2 / 2 with
//   M = J_core + R^2 (rho A (c0 + l0) + m)       (c0: the wound length at t = 0)
// constant, because material wound on the reel at radius R and material hanging both move at
// R phi' and their sum c + l is conserved. The potential is -g(t) (rho A l^2 / 2 + m l), so
//   M phi'' + c_r phi' = R g(t) (rho A (l0 + R phi) + m) + tau(t)   (g and the motor's tau ramped),
// integrated here with RK4 (h = 1e-4 s, error ~1e-13). Ours against it over 5 s, and the mass
// rho A (p_N - p_0) + rho A content(phi) against its initial value (round-off). The energy
// balance closes too: kinetic (reel, tether, block) + strain + the brake's dissipation - the work of
// the loads (gravity on the material in the tether as it moves, Q(q) . v; the block's weight; the
// motor's torque) stays zero, which checks that the reel's open-system inertia J phi'' and the
// ALE tether's mass transport hand the material's kinetic energy over without loss or gain.
//
// requirement (speed control): a driven reel whose angle is the payout of test_ale.cpp's payout
// test over R (0.2 m/s, started over 2 s) is that payout: the force at the exit is the weight below
// it, rho A g l(t) + m g, once the speed is constant; and the torque the reel takes is the material
// force at the exit times R: the reel pays out unstretched material that the exit stretches, so per
// length paid out it does the work T lambda - W = T (1 + eps / 2) (W = EA eps^2 / 2, lambda = 1 +
// eps to first order in the exit strain eps = T / EA = 7.4e-6; its own inertia takes nothing at
// constant speed).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "strand/elements/ElementRegistry.hpp"
#include "strand/solvers/Dynamics.hpp"
#include "support/HangingTether.hpp"
#include "support/Scenes.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

constexpr double kReelRadius = 0.5, kCore = 2.0, kContent = 100.0, kBrake = 40.0, kTorque = 5.0;

model::ReelDesc reel() {
  model::ReelDesc r;
  r.name = "winch";
  r.body = "tether";
  r.radius = kReelRadius;
  r.inertia = kCore;
  r.content = kContent;
  return r;
}

// phi(t) of the braked reel's one-degree-of-freedom equation (header), RK4 from rest.
std::vector<double> brakedReelAngle(const std::vector<double>& times) {
  const double R = kReelRadius, M = kCore + R * R * (rhoA() * (kContent + kL0) + kBlock);
  auto acc = [&](double t, double phi, double w) {
    const double g = kG * std::min(t, 1.0);
    return (R * g * (rhoA() * (kL0 + R * phi) + kBlock) + kTorque * std::min(t, 1.0) - kBrake * w) / M;
  };
  std::vector<double> out;
  double t = 0.0, phi = 0.0, w = 0.0;
  const double h = 1e-4;
  for (double target : times) {
    while (t < target - 1e-12) {
      const double dt = std::min(h, target - t);
      const double k1p = w, k1w = acc(t, phi, w);
      const double k2p = w + 0.5 * dt * k1w, k2w = acc(t + 0.5 * dt, phi + 0.5 * dt * k1p, w + 0.5 * dt * k1w);
      const double k3p = w + 0.5 * dt * k2w, k3w = acc(t + 0.5 * dt, phi + 0.5 * dt * k2p, w + 0.5 * dt * k2w);
      const double k4p = w + dt * k3w, k4w = acc(t + dt, phi + dt * k3p, w + dt * k3w);
      phi += dt / 6.0 * (k1p + 2 * k2p + 2 * k3p + k4p);
      w += dt / 6.0 * (k1w + 2 * k2w + 2 * k3w + k4w);
      t += dt;
    }
    out.push_back(phi);
  }
  return out;
}

void brakedReel(int dim, bool ring = false, bool exitLast = false) {
  model::SceneDescription sc = hangingTether(dim, exitLast);
  if (ring) {  // a frictionless ring 5 m below the exit, the tether straight through it: it carries nothing
    model::SupportDesc s;
    s.at.body = "tether";
    s.at.node = 10;
    s.type = model::SupportType::Sliding;
    sc.supports.push_back(s);
  }
  model::ReelDesc r = reel();
  if (exitLast) r.node = -1;
  r.damping = kBrake;
  r.torque.kind = model::TimeFunction::Kind::Ramp;  // with gravity
  r.torque.start = 0.0;
  r.torque.end = 1.0;
  r.torque.value = kTorque;
  sc.reels.push_back(r);
  sc.dynamics.tEnd = 5.0;
  solvers::Problem p(PETSC_COMM_WORLD, sc);
  Vec X, V;
  PetscCallAbort(PETSC_COMM_WORLD, p.createInitialState(&X, &V));
  solvers::Dynamics dyn(p.assembler(), sc.dynamics);
  const model::Model& m = p.model();
  const model::Body& tether = m.bodies()[0];
  const int k = tether.info().materialBlock(), phiDof = m.reelBlock(0) * dim;
  std::vector<double> times, phis;
  double worstMass = 0.0, worstEnergy = 0.0, loadWork = 0.0;
  solvers::Dynamics::StepCallback cb = [&](const solvers::DynamicsStep& st, Vec Xs, Vec) -> PetscErrorCode {
    worstEnergy = std::max(worstEnergy, std::fabs(st.energy()));
    loadWork = st.loadWork;
    std::vector<double> q;
    PetscCall(p.assembler().gatherToRoot(Xs, q));
    if (q.empty()) return 0;
    const double phi = q[phiDof], length = std::fabs(q[tether.block(tether.elements, k) * dim] - q[tether.block(0, k) * dim]);
    times.push_back(st.time);
    phis.push_back(phi);
    // rho A (wound + hanging) against rho A (c0 + l0)
    worstMass = std::max(worstMass, rhoA() * std::fabs(length + (kContent - kReelRadius * phi) - (kContent + kL0)));
    return 0;
  };
  std::string failure;
  PetscCallAbort(PETSC_COMM_WORLD, dyn.run(X, V, cb, &failure));
  EXPECT_EQ(failure, "");
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  double worst = 0.0, final = 0.0;
  if (rank == 0) {
    const std::vector<double> exact = brakedReelAngle(times);
    for (size_t i = 0; i < times.size(); ++i) worst = std::max(worst, std::fabs(phis[i] - exact[i]));
    final = exact.back();
    for (size_t i = 0; i < times.size(); i += std::max<size_t>(1, times.size() / 5))
      std::printf("t = %.1f s: phi %.8f rad, closed form %.8f rad\n", times[i], phis[i], exact[i]);
  }
  MPI_Bcast(&worst, 1, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  MPI_Bcast(&final, 1, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  MPI_Bcast(&worstMass, 1, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  std::printf("%dD braked reel%s%s: phi(5 s) = %.6f rad; largest |phi - closed form| %.2e rad (%.2e of phi(5 s)); "
              "mass bookkeeping %.2e kg; energy balance within %.2e J of the loads' %.1f J\n", dim,
              ring ? " through a ring" : "", exitLast ? " at the last node" : "", final, worst,
              worst / final, worstMass, worstEnergy, loadWork);
  EXPECT_GT(final, 1.0);                 // it does pay out (measured 2.9 rad in 5 s)
  EXPECT_LT(worst / final, 1e-5);        // measured 2e-6: the tether's strain (1e-5) and its waves
  EXPECT_LT(worstMass, 1e-12);           // round-off
  EXPECT_LT(worstEnergy, 1e-6 * loadWork);  // measured 3.1e-5 J of 404 J (7.6e-8)
  VecDestroy(&X);
  VecDestroy(&V);
}

void drivenReel(int dim) {
  const double speed = 0.2, ramp = 2.0;
  model::SceneDescription sc = hangingTether(dim);
  model::ReelDesc r = reel();
  r.driven = true;
  r.rotation.kind = model::TimeFunction::Kind::SpinUp;
  r.rotation.omega = speed / kReelRadius;
  r.rotation.duration = ramp;
  sc.reels.push_back(r);
  sc.dynamics.tEnd = 8.0;
  solvers::Problem p(PETSC_COMM_WORLD, sc);
  Vec X, V, F;
  PetscCallAbort(PETSC_COMM_WORLD, p.createInitialState(&X, &V));
  PetscCallAbort(PETSC_COMM_WORLD, VecDuplicate(X, &F));
  solvers::Dynamics dyn(p.assembler(), sc.dynamics);
  const model::Model& m = p.model();
  const model::Body& tether = m.bodies()[0];
  const int topRow = tether.posBlock[0] * dim + 1, phiDof = m.reelBlock(0) * dim;
  double worstForce = 0.0, worstTorque = 0.0;
  solvers::Dynamics::StepCallback cb = [&](const solvers::DynamicsStep& st, Vec, Vec) -> PetscErrorCode {
    if (st.time < 4.0 || st.step % 50 != 0) return 0;
    PetscCall(dyn.supportForce(F));
    std::vector<double> f;
    PetscCall(p.assembler().toModelOrder(F, f));
    double fy = 0.0, torque = 0.0;
    if (!f.empty()) {
      fy = f[topRow];
      torque = f[phiDof];
    }
    MPI_Bcast(&fy, 1, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
    MPI_Bcast(&torque, 1, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
    const double paid = kReelRadius * r.rotation.at(st.time).f, weight = kG * (rhoA() * (kL0 + paid) + kBlock);
    worstForce = std::max(worstForce, std::fabs(std::fabs(fy) / weight - 1.0));
    const double eps = weight / (kE * M_PI * kRadius * kRadius);
    worstTorque = std::max(worstTorque, std::fabs(std::fabs(torque) / (kReelRadius * weight * (1.0 + 0.5 * eps)) - 1.0));
    if (st.step % 1000 == 0)
      std::printf("t = %.1f s: paid out %.4f m, exit force %.4f N, reel torque %.4f N m, R x weight below %.4f N m\n",
                  st.time, paid, std::fabs(fy), torque, kReelRadius * weight);
    return 0;
  };
  std::string failure;
  PetscCallAbort(PETSC_COMM_WORLD, dyn.run(X, V, cb, &failure));
  EXPECT_EQ(failure, "");
  std::printf("%dD driven reel after 4 s: exit force against the weight below %.2e, torque against R x it x (1 + eps/2) "
              "%.2e\n", dim, worstForce, worstTorque);
  EXPECT_LT(worstForce, 1e-7);   // as the prescribed payout (test_ale.cpp: 4.9e-9)
  EXPECT_LT(worstTorque, 1e-7);  // measured 5e-9 (against R x the weight alone: 3.75e-6 = 0.51 eps)
  VecDestroy(&X);
  VecDestroy(&V);
  VecDestroy(&F);
}

}  // namespace

TEST(Reel, ABrakedReelPaysOutAsItsClosedFormSays) { brakedReel(2); }
TEST(Reel, ABrakedReelPaysOutAsItsClosedFormSays3d) { brakedReel(3); }
TEST(Reel, ABrakedReelPaysOutThroughARingAsItsClosedFormSays) { brakedReel(2, true); }
TEST(Reel, ABrakedReelAtTheLastNodePaysOutAsItsClosedFormSays3d) { brakedReel(3, false, true); }
TEST(Reel, ADrivenReelIsAPayoutAndTakesTheExitTensionsTorque) { drivenReel(2); }
TEST(Reel, ADrivenReelIsAPayoutAndTakesTheExitTensionsTorque3d) { drivenReel(3); }
