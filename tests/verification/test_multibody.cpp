// Rigid bodies and joints with Lagrange multipliers on the index-3 generalized-alpha TS (issue 3).
// requirement:
//  - compound pendulum (uniform rod, length l, pinned at one end, released horizontally): the
//    angle follows the exact equation of motion I_O phi'' = -m g (l/2) cos(phi), whose half period
//    is 2 sqrt(I_O / (m g l/2)) K(sin 45 deg) (complete elliptic integral, e.g. Landau & Lifshitz,
//    Mechanics, section 11); second order in time for every member of the family; the pin holds to
//    Newton tolerance at every step (< 1e-9 m, no drift); energy bounded at rho_inf = 1;
//  - 20-link chain: no drift (< 1e-9 m), energy error bounded and O(h^2) at rho_inf = 0.9, the same
//    trajectory on one and on all ranks; at rho_inf = 1 (trapezoidal-like) the run blows up or Newton
//    fails, and the run stops with an explanation (index-3 needs high-frequency damping);
//  - a cable clamped by a joint (position and slope direction, Lagrange multipliers) in a rotating
//    frame stretches by the rod value rho Omega^2 L^3 / (3 E) on every mesh (2D; 3D on 5 elements), where the eliminated
//    clamp (whole slope vector held) converges only at first order (tests/verification/test_spin_up.cpp).
#include <gtest/gtest.h>

#include <cmath>

#include "strand/solvers/Dynamics.hpp"
#include "strand/solvers/Schemes.hpp"
#include "support/ExactMotionChecks.hpp"
#include "support/Scenes.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

constexpr double kG = 9.81;

model::DynamicsDesc scheme(model::Integrator integrator, double rhoInf, double dt, double tEnd) {
  model::DynamicsDesc d;
  d.integrator = integrator;
  d.rhoInf = rhoInf;
  d.hhtAlpha = 0.1;
  d.dt = dt;
  d.tEnd = tEnd;
  return d;
}

// Complete elliptic integral of the first kind, K(k) = pi / (2 AGM(1, sqrt(1 - k^2))).
double ellipticK(double k) {
  double a = 1.0, b = std::sqrt(1.0 - k * k);
  for (int i = 0; i < 30; ++i) {
    const double an = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = an;
  }
  return M_PI / (2.0 * a);
}

struct ChainRun {
  double position = 0.0, velocity = 0.0;  // largest constraint violations over all steps
  double e0 = 0.0, maxDrift = 0.0;
  std::vector<double> q;                  // final coordinates (model numbering)
  double omegaEnd = 0.0;                  // final angular velocity of the first link
  std::string failure;
  int steps = 0, rejected = 0;
};

ChainRun runChain(MPI_Comm comm, int links, const model::DynamicsDesc& d, double l = 1.0, double m = 1.0) {
  model::SceneDescription sc = rigidChain(links, l, m);
  sc.dynamics = d;
  solvers::Problem p(comm, sc);
  Vec X, V;
  PetscCallAbort(comm, p.createInitialState(&X, &V));
  ChainRun out;
  solvers::Dynamics dyn(p.assembler(), d);
  solvers::Dynamics::StepCallback cb = [&](const solvers::DynamicsStep& s, Vec, Vec) -> PetscErrorCode {
    if (s.step == 0) out.e0 = s.energy();
    out.maxDrift = std::max(out.maxDrift, std::fabs(s.energy() - out.e0));
    out.position = std::max(out.position, s.constraintPosition);
    out.velocity = std::max(out.velocity, s.constraintVelocity);
    out.steps = s.step;
    out.rejected = s.rejectedSteps;
    return 0;
  };
  PetscCallAbort(comm, dyn.run(X, V, cb, &out.failure));
  PetscCallAbort(comm, p.assembler().gatherToRoot(X, out.q));
  std::vector<double> v;
  PetscCallAbort(comm, p.assembler().gatherToRoot(V, v));  // q0 + V: the angle rate is V (q0 of phi is 0)
  const int n = p.model().numDofs();
  out.q.resize(n);
  v.resize(n);
  MPI_Bcast(out.q.data(), n, MPI_DOUBLE, 0, comm);
  MPI_Bcast(v.data(), n, MPI_DOUBLE, 0, comm);
  out.omegaEnd = v[2 * p.model().rigidBodies()[0].rotBlock];
  VecDestroy(&X);
  VecDestroy(&V);
  return out;
}

// The compound pendulum's angle phi (from the horizontal, COM at (l/2)(cos phi, sin phi)).
double pendulumAngle(const ChainRun& r) { return r.q[2 * 1]; }  // rotation block of link 0 is block 1

}  // namespace

// phi(t) of the compound pendulum from the exact equation of motion, by RK4 with 2e5 steps per
// second (error ~1e-14); validated against the closed-form half period below.
double referenceAngle(double t) {
  const double c = kG * 0.5 / (1.0 / 3.0);  // m g (l/2) / I_O
  const int n = static_cast<int>(std::ceil(t * 2e5));
  const double h = t / n;
  double phi = 0.0, w = 0.0;
  auto acc = [&](double p) { return -c * std::cos(p); };
  for (int i = 0; i < n; ++i) {
    const double k1p = w, k1w = acc(phi);
    const double k2p = w + 0.5 * h * k1w, k2w = acc(phi + 0.5 * h * k1p);
    const double k3p = w + 0.5 * h * k2w, k3w = acc(phi + 0.5 * h * k2p);
    const double k4p = w + h * k3w, k4w = acc(phi + h * k3p);
    phi += h / 6.0 * (k1p + 2 * k2p + 2 * k3p + k4p);
    w += h / 6.0 * (k1w + 2 * k2w + 2 * k3w + k4w);
  }
  return phi;
}

TEST(Multibody, CompoundPendulumFollowsItsEquationOfMotionAtSecondOrder) {
  // l = 1 m, m = 1 kg: I_O = 1/3 kg m^2, m g l/2 = 4.905 N m; released from phi = 0 it swings to
  // phi = -pi (horizontal, the other side) at T/2 = 2 sqrt(I_O / (m g l/2)) K(sin(pi/4)) = 0.966647 s.
  const double halfPeriod = 2.0 * std::sqrt((1.0 / 3.0) / (kG * 0.5)) * ellipticK(std::sin(M_PI / 4.0));
  EXPECT_NEAR(referenceAngle(halfPeriod), -M_PI, 1e-9);  // the reference integrator is right
  const double tEnd = 0.5, exact = referenceAngle(tEnd), scale = kG * 0.5;
  struct Member {
    model::Integrator integrator;
    double rho;
    const char* name;
  };
  for (const Member& mb : {Member{model::Integrator::GeneralizedAlpha, 1.0, "rho_inf 1"},
                           Member{model::Integrator::GeneralizedAlpha, 0.8, "rho_inf 0.8"},
                           Member{model::Integrator::GeneralizedAlpha, 0.0, "rho_inf 0"},
                           Member{model::Integrator::Newmark, 1.0, "Newmark"},
                           Member{model::Integrator::Hht, 1.0, "HHT 0.1"}}) {
    double err[3], drift[3];
    for (int k = 0; k < 3; ++k) {
      const int steps = 125 << k;
      const ChainRun r = runChain(PETSC_COMM_WORLD, 1, scheme(mb.integrator, mb.rho, tEnd / steps, tEnd));
      ASSERT_EQ(r.failure, "") << mb.name;
      err[k] = std::fabs(pendulumAngle(r) - exact);
      drift[k] = r.maxDrift;
      EXPECT_LT(r.position, 1e-9) << mb.name << ": the pin drifts";
      std::printf("%-12s steps %5d  |phi - phi_ref| %.3e  |g| %.1e  |G v| %.1e  energy drift %.2e of m g l/2\n", mb.name,
                  steps, err[k], r.position, r.velocity, r.maxDrift / scale);
    }
    const double rate = std::log2(err[1] / err[2]), energyRate = std::log2(drift[1] / drift[2]);
    std::printf("%-12s rate %.3f, energy error rate %.3f\n", mb.name, rate, energyRate);
    EXPECT_NEAR(rate, 2.0, 0.15) << mb.name;
    // without numerical dissipation the energy error is that of a second-order method: bounded, O(h^2)
    if (mb.rho == 1.0 && mb.integrator != model::Integrator::Hht) {
      EXPECT_NEAR(energyRate, 2.0, 0.15) << mb.name;
    }
  }
}

TEST(Multibody, TwentyLinkChainHoldsItsJointsAndItsEnergyWithHighFrequencyDamping) {
  // 20 links of 0.1 m, 0.1 kg, released horizontally: 1 s of whipping motion
  const double scale = 2.0 * kG * 1.0;  // m_total g L / 2 with m_total = 2 kg, L = 2 m
  double drift[2];
  for (int k = 0; k < 2; ++k) {
    const double h = 1e-3 / (1 << k);
    const ChainRun r = runChain(PETSC_COMM_WORLD, 20, scheme(model::Integrator::GeneralizedAlpha, 0.9, h, 1.0), 0.1, 0.1);
    ASSERT_EQ(r.failure, "");
    drift[k] = r.maxDrift;
    std::printf("chain rho_inf 0.9, h %.1e: |g| %.2e  |G v| %.2e  energy error %.3e of m g L/2\n", h, r.position,
                r.velocity, r.maxDrift / scale);
    EXPECT_LT(r.position, 1e-9);
    EXPECT_LT(r.maxDrift, 1e-3 * scale);
  }
  EXPECT_NEAR(std::log2(drift[0] / drift[1]), 2.0, 0.2) << "energy error O(h^2)";
}

TEST(Multibody, UndampedMemberOnTheChainStopsWithAnExplanation) {
  // rho_inf = 1 (alpha_m = alpha_f = 1/2, gamma = 1/2, beta = 1/4: the trapezoidal rule for
  // linear problems) does not damp the multipliers' error on index-3 constraints (Arnold & Bruls
  // 2007, Sec. 4): measured, Newton fails at t = 0.61 s with h = 1 ms, and at h = 0.5 ms the
  // energy jumps from 1e-3 J to 1e11 J at t = 0.64 s with Newton converging. Both must stop cleanly.
  for (double h : {1e-3, 5e-4}) {
    const ChainRun r = runChain(PETSC_COMM_WORLD, 20, scheme(model::Integrator::GeneralizedAlpha, 1.0, h, 1.0), 0.1, 0.1);
    std::printf("h %.1e: %s\n", h, r.failure.c_str());
    EXPECT_NE(r.failure.find("index-3"), std::string::npos) << r.failure;
    EXPECT_NE(r.failure.find("rho_inf <= 0.9"), std::string::npos) << r.failure;
    EXPECT_NE(r.failure.find("stopped at t = 0."), std::string::npos) << r.failure;
  }
}

TEST(Multibody, ChainTrajectoryIsTheSameOnOneAndOnAllRanks) {
  for (const model::DynamicsDesc& d : {scheme(model::Integrator::GeneralizedAlpha, 0.9, 1e-3, 0.3),
                                       scheme(model::Integrator::Bdf, 1.0, 1e-3, 0.3)}) {
  const ChainRun all = runChain(PETSC_COMM_WORLD, 20, d, 0.1, 0.1);
  const ChainRun one = runChain(PETSC_COMM_SELF, 20, d, 0.1, 0.1);
  ASSERT_EQ(all.failure, "");
  ASSERT_EQ(one.failure, "");
  ASSERT_EQ(all.q.size(), one.q.size());
  double diff = 0.0;
  for (size_t i = 0; i < all.q.size(); ++i) diff = std::max(diff, std::fabs(all.q[i] - one.q[i]));
  std::printf("chain (%s) at t = 0.3 s: largest coordinate difference all ranks vs one rank %.2e\n",
              solvers::schemeName(d).c_str(), diff);
  EXPECT_LT(diff, 1e-8);
  }
}

TEST(Multibody, JointClampGivesTheRodStretchOnEveryMesh) {
  // seed 001 beam (L = 10 m, E = 70 GPa, rho = 3000 kg/m^3) turning steadily at 4 rad/s, in the
  // rotating frame: rod theory u(L) = rho Omega^2 L^3 / (3 E) = 0.228571 mm.
  const double omega = 4.0, L = 10.0, E = 70e9, rho = 3000.0;
  const double rod = rho * omega * omega * L * L * L / (3.0 * E);
  const double strain = rho * omega * omega * L * L / (2.0 * E);  // largest axial strain (root)
  double first = 0.0;
  for (int elements : {2, 5, 10}) {
    for (bool joint : {false, true}) {
      model::SceneDescription sc = seed001Beam(E, elements);
      if (elements == 5) {  // 3D: the clamp has 5 equations (position, two slope normals) in two multiplier blocks
        Section sec;
        sec.E = E;
        sec.A = 4e-4;
        sec.I = 2e-7;
        sec.rho = rho;
        sc = cantilever(3, elements, L, sec);
      }
      sc.rotation.present = true;
      sc.rotation.omega = omega;
      if (joint) {
        sc.supports.clear();
        model::JointDesc j;
        j.type = model::JointType::Clamp;
        j.a.kind = model::JointEndDesc::Kind::CableNode;
        j.a.body = "beam";
        j.a.node = 0;
        j.b.kind = model::JointEndDesc::Kind::Ground;
        sc.joints.push_back(j);
      }
      solvers::Problem p(PETSC_COMM_WORLD, sc);
      std::string failure;
      const std::vector<double> q = solveStatic(p, 1, &failure);
      ASSERT_EQ(failure, "");
      const double stretch = nodePosition(p, q, 0, -1)[0] - L;
      std::printf("%dD %2d elements, %-16s stretch %.9e m, relative error vs rod %+.3e\n", p.model().dim(),
                  elements, joint ? "clamp joint" : "clamped support", stretch, stretch / rod - 1.0);
      if (joint) {
        // the remaining difference is the geometric nonlinearity (Green strain), of the order of the strain
        EXPECT_LT(std::fabs(stretch / rod - 1.0), strain);
        if (elements == 2) first = stretch;
        EXPECT_NEAR(stretch, first, 1e-9 * rod) << "the cubic displacement is exact on every mesh";
      } else {
        EXPECT_GT(std::fabs(stretch / rod - 1.0), 0.1 / elements);  // first order, as the eliminated clamp fixes u'(0)
      }
    }
  }
}

// BDF on the GGL stabilized index-2 form (solvers/ConstrainedStateSpace.hpp): the compound
// pendulum's angle converges at the order of the scheme for BDF1 and BDF2, and GGL holds the pin at
// position *and* velocity level at every step (|g|, |G v| < 1e-9: no drift at either). BDF3 is
// more accurate than BDF2 but converges at order 2, not 3: TSBDF starts with a backward-Euler half
// step (TSBDF_Restart, PETSc 3.18 src/ts/impls/bdf/bdf.c), whose local error O(h^2) stays in the
// global error (measured rate 1.92; the same holds without joints).
TEST(Multibody, BdfOnTheStabilizedIndexTwoFormConvergesAtItsOrderWithoutDrift) {
  const double tEnd = 0.5, exact = referenceAngle(tEnd);
  double bdf2Error = 0.0;
  for (int order : {1, 2, 3}) {
    double err[3];
    for (int k = 0; k < 3; ++k) {
      const int steps = 250 << k;
      model::DynamicsDesc d = scheme(model::Integrator::Bdf, 1.0, tEnd / steps, tEnd);
      d.bdfOrder = order;
      const ChainRun r = runChain(PETSC_COMM_WORLD, 1, d);
      ASSERT_EQ(r.failure, "") << "BDF" << order;
      err[k] = std::fabs(pendulumAngle(r) - exact);
      std::printf("BDF%d GGL steps %5d  |phi - phi_ref| %.3e  |g| %.1e  |G v| %.1e  energy error %.2e of m g l/2\n",
                  order, steps, err[k], r.position, r.velocity, r.maxDrift / (kG * 0.5));
      EXPECT_LT(r.position, 1e-9);
      EXPECT_LT(r.velocity, 1e-9);
    }
    const double rate = std::log2(err[1] / err[2]);
    std::printf("BDF%d GGL rate %.3f\n", order, rate);
    EXPECT_NEAR(rate, std::min(order, 2), 0.15) << "BDF" << order;
    if (order == 3) {
      EXPECT_LT(err[2], 0.05 * bdf2Error) << "BDF3 against BDF2 on 1000 steps";
    }
    if (order == 2) bdf2Error = err[2];
  }
}

// The 20-link chain on BDF2 (GGL): no drift at position or velocity level (< 1e-9), energy only
// dissipated (BDF2 damps, E(t) <= E(0) up to solver tolerance), its loss O(h^2); adaptive BDF2 with
// the multipliers out of the error norm finishes with its joints held.
TEST(Multibody, TwentyLinkChainOnBdfHoldsItsJointsAtBothLevels) {
  const double scale = 2.0 * kG * 1.0;  // m_total g L / 2
  double drift[2];
  for (int k = 0; k < 2; ++k) {
    const double h = 1e-3 / (1 << k);
    const ChainRun r = runChain(PETSC_COMM_WORLD, 20, scheme(model::Integrator::Bdf, 1.0, h, 0.5), 0.1, 0.1);
    ASSERT_EQ(r.failure, "");
    drift[k] = r.maxDrift;
    std::printf("chain BDF2 GGL, h %.1e: |g| %.2e  |G v| %.2e  energy error %.3e of m g L/2\n", h, r.position,
                r.velocity, r.maxDrift / scale);
    EXPECT_LT(r.position, 1e-9);
    EXPECT_LT(r.velocity, 1e-9);
    EXPECT_LT(r.maxDrift, 1e-2 * scale);
  }
  std::printf("chain BDF2 GGL energy error rate %.3f\n", std::log2(drift[0] / drift[1]));
  EXPECT_NEAR(std::log2(drift[0] / drift[1]), 2.0, 0.2) << "energy error O(h^2)";
  model::DynamicsDesc d = scheme(model::Integrator::Bdf, 1.0, 1e-4, 0.5);
  d.adaptive = true;
  const ChainRun r = runChain(PETSC_COMM_WORLD, 20, d, 0.1, 0.1);
  std::printf("chain adaptive BDF2 GGL (rtol 1e-4, atol 1e-6), %d steps, %d rejected: |g| %.2e  |G v| %.2e  energy error %.3e of m g L/2  %s\n",
              r.steps, r.rejected, r.position, r.velocity, r.maxDrift / scale, r.failure.c_str());
  ASSERT_EQ(r.failure, "");
  EXPECT_LT(r.position, 1e-9);
  EXPECT_LT(r.velocity, 1e-9);
}

// Index-3 BDF with the multipliers in the error norm (constraint_form: index3, adaptive): the local
// error estimate of lambda does not fall with h (Brenan, Campbell & Petzold, Numerical Solution of
// IVPs in DAEs, 1996, Sec. 3.2 and 5.4: index-3 variables must be left out of the error test), so
// the step is rejected until the TS gives up. The run must stop cleanly, say why and what to use.
TEST(Multibody, IndexThreeBdfWithMultipliersInTheErrorNormStopsWithAnExplanation) {
  model::DynamicsDesc d = scheme(model::Integrator::Bdf, 1.0, 1e-3, 1.0);
  d.adaptive = true;
  d.constraintForm = model::DynamicsDesc::ConstraintForm::Index3;
  const ChainRun r = runChain(PETSC_COMM_WORLD, 1, d);
  std::printf("%s\n", r.failure.c_str());
  EXPECT_NE(r.failure.find("index-3"), std::string::npos) << r.failure;
  EXPECT_NE(r.failure.find("ggl"), std::string::npos) << r.failure;
  EXPECT_NE(r.failure.find("stopped at t = "), std::string::npos) << r.failure;
}

// The link carried by a driven hub (tests/support/CarriedLink.hpp) on generalized-alpha (index 3) and on BDF2
// (GGL, the stabilized index-2 form): a consistent start (|G v(0)|, the drive torque and the pin
// force at t = 0 exact to round-off), the pin held, and the drive torque
// and ground force (the support force, from the scheme's own acceleration and multipliers)
// converging to the exact ones at second order, with the energy balance T - T(0) = W_drive closing at
// second order. Without its perturbed start (Dynamics::perturbedStart) generalized-alpha's torque is
// first order, 3.6e-3 of its peak at h = 1 ms (Arnold & Bruls 2007's O(h) transient of A and
// lambda); with it 9.6e-6.
TEST(Multibody, LinkCarriedByADrivenHubMatchesNewtonsLawsFromAConsistentStart) {
  expectSecondOrderAgainstExactMotion("link on a driven hub", 2.0, carryLink);  // one period of the drive
}
