// Verification of the first-order integrators (issue 3; StateSpace.hpp), at -n 1 and -n 2.
//  1. Order in time on a soft flexible pendulum (support/Pendulum.hpp with E = 1e6 Pa, 4 elements:
//     EA = 100 N, 13 times its weight, an elastic rope pendulum whose highest frequency ~4e2 rad/s
//     lets the explicit schemes take steps where their error is above round-off; Kelvin-Voigt
//     damping 3e-4 s): the tip position at t = 1 s (after one swing; at 0.3 s the release transient
//     still shows in the 4th-order rates: 4.6 for ABM4) changes per halving of h at the rate of the
//     scheme: BDF1 1, BDF2 2 (TSBDF, fixed step), RK4 4 (TSRK), ABM4 4 (ours), generalized-alpha 2.
//     All converge to one answer: each scheme's finest tip agrees with RK4's finest within twice its
//     Richardson error estimate (last change / (2^p - 1)).
//  2. Adaptive BDF2 (TSADAPTBASIC on the weighted local error of (u, v)): the tip error against the
//     RK4 reference falls with the tolerance, and the run reports its rejected steps.
//  3. Where the explicit methods fail, on the stiff pendulum of test_dynamics (E = 1e8, 8 elements),
//     with omega_max, the highest frequency of the discrete model, from SLEPc (K x = omega^2 M x at
//     the initial state, largest magnitude):
//     RK4 is stable on undamped modes for h omega_max <= 2 sqrt(2) (|R(i x)|^2 = 1 - x^6/72 + x^8/576,
//     Hairer & Wanner, Solving ODEs II, Sec. IV.2): it runs at 0.95 of that step and stops with an
//     explanation at 1.05 of it. ABM4 (PECE) amplifies undamped modes by 1 + 0.16 (h omega)^6 per
//     step (AdamsBashforthMoulton.hpp): undamped it stops with that explanation; with the damping
//     (real eigenvalues, stable for h |lambda| <= 1.28) the same model runs.
//  4. BDF3-5 on the soft pendulum of 1: BDF3 at rate 3, BDF4 and BDF5 at the rate 2 of TSBDF's
//     backward-Euler start, each more accurate than BDF2 at every step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "support/Pendulum.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

constexpr double kDamping = 3e-4, kEnd = 1.0;
constexpr double H_BDF1 = 1e-3, H_BDF2 = 1e-3, H_RK4 = 2e-3, H_ABM4 = 1e-3, H_ALPHA = 1e-3;

model::SceneDescription softPendulum() { return flexiblePendulum(kDamping, 1e6, 4); }

struct Study {
  double tip[4][2];
  double change[3];  // |tip(h_k) - tip(h_k / 2)|
};

Study halvings(model::DynamicsDesc d, double h0, const char* name) {
  Study s{};
  for (int k = 0; k < 4; ++k) {
    d.dt = h0 / (1 << k);
    d.tEnd = kEnd;
    const PendulumRun r = runPendulum(softPendulum(), d, false);
    s.tip[k][0] = r.tipX;
    s.tip[k][1] = r.tipY;
  }
  for (int k = 0; k < 3; ++k) s.change[k] = std::hypot(s.tip[k][0] - s.tip[k + 1][0], s.tip[k][1] - s.tip[k + 1][1]);
  std::printf("%-8s tip change per halving from h = %.2e: %.3e %.3e %.3e  rates %.2f %.2f; finest tip (%.12f, %.12f)\n",
              name, h0, s.change[0], s.change[1], s.change[2], std::log2(s.change[0] / s.change[1]),
              std::log2(s.change[1] / s.change[2]), s.tip[3][0], s.tip[3][1]);
  return s;
}

double distance(const Study& a, const Study& b) {
  return std::hypot(a.tip[3][0] - b.tip[3][0], a.tip[3][1] - b.tip[3][1]);
}

const Study& rk4Reference() {
  static const Study s = halvings(scheme(model::Integrator::Rk4, 1.0, 0, 0), H_RK4, "rk4");
  return s;
}

// halvings(), run once per name for all the tests of this file (BDF2's serve two of them).
const Study& study(const model::DynamicsDesc& d, double h0, const std::string& name) {
  static std::map<std::string, Study> done;
  auto it = done.find(name);
  if (it == done.end()) it = done.emplace(name, halvings(d, h0, name.c_str())).first;
  return it->second;
}

}  // namespace

TEST(Integrators, EveryFirstOrderSchemeConvergesAtItsOrderToTheSameTip) {
  model::DynamicsDesc bdf1 = scheme(model::Integrator::Bdf, 1.0, 0, 0), bdf2 = bdf1;
  bdf1.bdfOrder = 1;
  bdf2.bdfOrder = 2;
  struct Case {
    const char* name;
    model::DynamicsDesc d;
    double h0;
    int order;
  };
  const Case cases[] = {{"bdf1", bdf1, H_BDF1, 1},
                        {"bdf2", bdf2, H_BDF2, 2},
                        {"abm4", scheme(model::Integrator::Abm4, 1.0, 0, 0), H_ABM4, 4},
                        {"alpha 1", scheme(model::Integrator::GeneralizedAlpha, 1.0, 0, 0), H_ALPHA, 2}};
  const Study& ref = rk4Reference();
  // rate windows: +-0.1 at orders 1 and 2 (as test_dynamics), +-0.25 at order 4
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(std::log2(ref.change[k] / ref.change[k + 1]), 4.0, 0.25) << "rk4";
  for (const Case& c : cases) {
    const Study& s = study(c.d, c.h0, c.name);
    for (int k = 0; k < 2; ++k)
      EXPECT_NEAR(std::log2(s.change[k] / s.change[k + 1]), c.order, c.order == 4 ? 0.25 : 0.1) << c.name;
    // Richardson estimates of the error of the finest runs (this scheme's and the reference's)
    const double richardson = s.change[2] / ((1 << c.order) - 1), refError = ref.change[2] / 15.0;
    std::printf("  %-8s finest tip - rk4 finest tip: %.3e (Richardson error estimates %.3e, rk4 %.3e)\n", c.name,
                distance(s, ref), richardson, refError);
    EXPECT_LT(distance(s, ref), 2.0 * (richardson + refError)) << c.name;
  }
}

TEST(Integrators, AdaptiveBdfErrorFallsWithTheTolerance) {
  const Study& ref = rk4Reference();
  double err[3];
  const double rtol[3] = {1e-3, 1e-4, 1e-5};
  for (int k = 0; k < 3; ++k) {
    model::DynamicsDesc d = scheme(model::Integrator::Bdf, 1.0, 1e-4, kEnd);
    d.adaptive = true;
    d.rtol = rtol[k];
    d.atol = rtol[k] * 1e-2;
    const PendulumRun r = runPendulum(softPendulum(), d, false);
    err[k] = std::hypot(r.tipX - ref.tip[3][0], r.tipY - ref.tip[3][1]);
    std::printf("adaptive bdf2 rtol %.0e atol %.0e: %d steps, %d rejected, tip error %.3e m\n", d.rtol, d.atol, r.steps,
                r.rejected, err[k]);
    EXPECT_GT(r.steps, 0);
  }
  EXPECT_LT(err[1], err[0]);
  EXPECT_LT(err[2], err[1]);
}

TEST(Integrators, ExplicitSchemesStopWithAnExplanationWhereTheyAreUnstable) {
  const double omega = highestFrequency(flexiblePendulum());
  const double limit = 2.0 * std::sqrt(2.0) / omega;
  std::printf("omega_max = %.6e rad/s (SLEPc); RK4 limit 2 sqrt(2) / omega_max = %.4e s\n", omega, limit);
  // Below the limit RK4 damps every undamped mode (|R(ix)|^2 = 1 - x^6/72 + x^8/576 < 1 for
  // 0 < x < 2 sqrt(2)): the energy it loses is that of the rope's axial and bending vibration excited
  // by releasing it straight under gravity, fastest for the modes near the limit (x = 2.69: |R|^2 =
  // 0.49 per step); the swing itself (omega ~ 4 rad/s, x ~ 1e-3) loses x^6/72 ~ 1e-20 per step.
  // Measured loss / (m g L/2) over 0.1 s: 7.30e-9 at 0.95 of the limit (9.2e-10 at 0.5, 7.95e-9 at
  // 0.99; over 0.05 / 0.2 s at 0.95: 5.3e-9 / 9.7e-9). Asserted: a loss, the largest |E - E0| at the
  // end (no energy created), below 1.5e-8 (twice the measured loss).
  const PendulumRun below = pendulum(scheme(model::Integrator::Rk4, 1.0, 0.95 * limit, 0.1));
  std::printf("rk4 at 0.95 of the limit: energy drift / (m g L/2) %.3e, E(end) - E(0) %.3e\n", below.maxDrift / below.scale,
              (below.eEnd - below.e0) / below.scale);
  EXPECT_LT(below.maxDrift / below.scale, 1.5e-8);
  EXPECT_NEAR((below.eEnd - below.e0) / below.scale, -below.maxDrift / below.scale, 1e-14) << "RK4 created energy";
  const PendulumRun above = pendulum(scheme(model::Integrator::Rk4, 1.0, 1.05 * limit, 0.1), 0.0, true);
  std::printf("rk4 at 1.05 of the limit: %s\n", above.failure.c_str());
  EXPECT_NE(above.failure.find("RK4 is stable only while dt omega_max <= 2 sqrt(2)"), std::string::npos);
  EXPECT_NE(above.failure.find("blown up"), std::string::npos);
  // ABM4: undamped, the highest mode grows from round-off; damped, the same scheme runs
  const PendulumRun undamped = pendulum(scheme(model::Integrator::Abm4, 1.0, 8e-5, 1.0), 0.0, true);
  std::printf("abm4 undamped, h omega_max = %.2f: %s\n", 8e-5 * omega, undamped.failure.c_str());
  EXPECT_NE(undamped.failure.find("amplifies undamped oscillations"), std::string::npos);
  const PendulumRun damped = pendulum(scheme(model::Integrator::Abm4, 1.0, 5e-5, 1.0), kDamping);
  EXPECT_EQ(damped.failure, "");
}

// BDF runs on our TS type strand_bdf (solvers/StrandBdf.hpp), whose history goes into checkpoints;
// it must be PETSc's TSBDF step by step (same start, coefficients, predictor, error estimate and
// step control), so every BDF number measured on TSBDF stands. Flexible pendulum, 0.3 s: fixed
// steps of 1 ms, BDF1-3 (BDF3, not A-stable, blows up on this undamped rope at t = 0.197 s: on
// both, with the same message); adaptive BDF1-3 (rtol 1e-4, atol 1e-6, first step 1 ms) for 0.03 s:
// the same accepted and rejected steps. (Later, round-off differences between the two Lagrange
// weight computations flip an accept/reject decision where the error estimate is near 1: BDF3 at
// step 454, t = 0.0375 s, BDF1 at step 2470, t = 0.138 s; BDF2 stays equal to 0.3 s.)
TEST(Integrators, StrandBdfIsPetscTsbdfStepByStep) {
  const model::SceneDescription sc = flexiblePendulum();
  for (int order : {1, 2, 3, -1, -2, -3}) {  // negative: adaptive
    model::DynamicsDesc d = scheme(model::Integrator::Bdf, 1.0, 1e-3, order > 0 ? 0.3 : 0.03);
    d.bdfOrder = std::abs(order);
    d.adaptive = order < 0;
    d.rtol = 1e-4;
    d.atol = 1e-6;
    const PendulumRun ours = runPendulum(sc, d, order == 3);
    PetscCallAbort(PETSC_COMM_WORLD, PetscOptionsSetValue(nullptr, "-dyn_ts_type", "bdf"));
    PetscCallAbort(PETSC_COMM_WORLD,
                   PetscOptionsSetValue(nullptr, "-dyn_ts_bdf_order", std::to_string(d.bdfOrder).c_str()));
    const PendulumRun petsc = runPendulum(sc, d, order == 3, true);
    PetscCallAbort(PETSC_COMM_WORLD, PetscOptionsClearValue(nullptr, "-dyn_ts_type"));
    PetscCallAbort(PETSC_COMM_WORLD, PetscOptionsClearValue(nullptr, "-dyn_ts_bdf_order"));
    const double diff = std::hypot(ours.tipX - petsc.tipX, ours.tipY - petsc.tipY);
    std::printf("BDF%d %s: strand_bdf tip (%.12f, %.12f) after %d steps (%d rejected), TSBDF differs by %.2e m "
                "(%d steps, %d rejected)\n", d.bdfOrder, d.adaptive ? "adaptive" : "fixed", ours.tipX, ours.tipY,
                ours.steps, ours.rejected, diff, petsc.steps, petsc.rejected);
    EXPECT_LT(diff, 1e-12);
    EXPECT_EQ(ours.steps, petsc.steps);
    EXPECT_EQ(ours.rejected, petsc.rejected);
    EXPECT_EQ(ours.failure, petsc.failure);
    if (order == 3) {
      EXPECT_NE(ours.failure.find("stopped at t = 0.197 s"), std::string::npos) << ours.failure;
    }
  }
}

// BDF3, BDF4 and BDF5 (strand_bdf, fixed step) on the soft damped pendulum of the order study, h0 =
// 1e-3 ... 1.25e-4. Each step adds the scheme's own error, h^{k+1} y^{(k+1)} / (k+1) (error constant
// -1/(k+1)), but the start adds an O(h^2) error too: TSBDF's first step is a backward-Euler half step
// whose error (h/2)^2/2 y''(0) the following steps carry with a weight w_k (0.70, 1.47, 1.12 for
// BDF3-5; predicted and checked to 0.07 % on the compound pendulum in test_multibody.cpp). So the
// global error is C_k h^k + c w_k h^2 / 8: rate k while the first term dominates, 2 when h is small.
// Measured (change of the tip per halving): BDF3 1.06e-5, 1.29e-6, 1.55e-7 (rates 3.04, 3.05: its own
// term still dominates, w_3 being small), BDF4 1.91e-6, 3.69e-7, 8.51e-8 (2.37, 2.12: passing from 4 to
// the start's 2), BDF5 1.05e-6, 2.54e-7, 6.30e-8 (2.04, 2.01: the start's 2). Asserted: those rates
// (BDF3 3 +- 0.15; BDF4 falling, the last 2 +- 0.2; BDF5 2 +- 0.1); the finest tip within twice the
// Richardson estimates (for the observed order) of RK4's finest; and at every step a tip error
// against RK4's finest below BDF2's at the same step.
TEST(Integrators, HigherBdfOrdersConvergeAtTheRateTheirStartAllows) {
  const Study& ref = rk4Reference();
  model::DynamicsDesc d = scheme(model::Integrator::Bdf, 1.0, 0, 0);
  d.bdfOrder = 2;
  const Study& bdf2 = study(d, H_BDF2, "bdf2");
  auto tipError = [&](const Study& s, int k) {
    return std::hypot(s.tip[k][0] - ref.tip[3][0], s.tip[k][1] - ref.tip[3][1]);
  };
  for (int order : {3, 4, 5}) {
    d.bdfOrder = order;
    const std::string name = "bdf" + std::to_string(order);
    const Study s = halvings(d, H_BDF2, name.c_str());
    const double r0 = std::log2(s.change[0] / s.change[1]), r1 = std::log2(s.change[1] / s.change[2]);
    if (order == 3) {
      EXPECT_NEAR(r0, 3.0, 0.15) << name;
      EXPECT_NEAR(r1, 3.0, 0.15) << name;
    } else if (order == 4) {
      EXPECT_GT(r0, r1) << name << ": from its own order towards the start's 2";
      EXPECT_NEAR(r1, 2.0, 0.2) << name;
    } else {
      EXPECT_NEAR(r0, 2.0, 0.1) << name;
      EXPECT_NEAR(r1, 2.0, 0.1) << name;
    }
    const int p = order == 3 ? 3 : 2;
    const double richardson = s.change[2] / ((1 << p) - 1), refError = ref.change[2] / 15.0;
    std::printf("  %-8s finest tip - rk4 finest tip: %.3e (Richardson error estimates %.3e, rk4 %.3e); tip errors %.2e %.2e "
                "%.2e %.2e (bdf2 %.2e %.2e %.2e %.2e)\n",
                name.c_str(), distance(s, ref), richardson, refError, tipError(s, 0), tipError(s, 1), tipError(s, 2),
                tipError(s, 3), tipError(bdf2, 0), tipError(bdf2, 1), tipError(bdf2, 2), tipError(bdf2, 3));
    EXPECT_LT(distance(s, ref), 2.0 * (richardson + refError)) << name;
    for (int k = 0; k < 4; ++k) EXPECT_LT(tipError(s, k), tipError(bdf2, k)) << name << " against bdf2, step " << k;
  }
}
