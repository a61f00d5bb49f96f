// The two-pulley belt drive of Pechstein & Gerstmayr (Multibody Syst. Dyn. 30, 2013), as set up in
// the THREAD belt-drive study (issue 34; docs/validation.md, "Two-pulley drive"), against the
// closed forms of creep theory (Johnson, Contact Mechanics, 1985, ch. 8; Kong & Parker 2005).
//
// A closed belt (EA = 8000 N, EI = 4/3e-3 N m^2, rho A = 8.288e-3 kg/m, height 1e-4 m, reference
// strain -0.05) around two pulleys of radius 0.09995 m (its centerline at r = 0.1 m) whose centres
// lie 0.1 pi m apart; mu = 0.5 (the bristle law); gravity 9.81. The driver turns at 0 -> 12 rad/s
// over 0.05 .. 0.6 s; the driven pulley (J = 0.25 kg m^2, damping 2 N m s) carries a load torque
// 25 (1 - cos(2 pi (t - 1))) / 2 N m over 1 .. 1.5 s, then 25 N m. In the steady state:
//   torque balance  (T1 - T2) r = c omega2 + 25 N m   (T1, T2: the tight and slack spans' tensions)
//   speed ratio     omega2 / omega1 = lambda2 / lambda1: the belt's material flux v / lambda is the
//                   same in both spans, and it leaves each pulley at the pulley's surface speed
//                   (the stick arc lies at the entry); (1 + T2/EA) / (1 + T1/EA) to first order
//   slip arcs       on each pulley, at its exit side, phi_s = ln(T1 / T2) / mu (Euler-Eytelwein over
//                   the slip arc); stick over the rest of the wrap (asserted: the slipping points
//                   reach to within two points' spacing of where the belt leaves the pulley)
//
// requirement: the belt's torque on the driven pulley equals c omega2 + 25 N m (2e-3), the span
//   tensions' (T1 - T2) r too (5e-3), and the creep 1 - omega2/omega1 equals 1 - lambda2/lambda1
//   (1e-2; measured 8.0e-3 at k_t = 1e8, 4.5e-3 at 1e9: the elastic stick's creep);
// requirement: the energy balance (kinetic + strain + contact penalty + potential + dissipated -
//   work of the contact's other forces and the loads) closes while the drive runs: its change from
//   0.05 s (the driver starts) to the end below 1e-4 of the work done (measured 8e-7 of 560 J at
//   k_t = 1e8, 4.4e-5 at 1e9).
//   Before that the belt, laid on the pulleys at zero gap with its pretension, sinks into them: a
//   radial contact mode beyond 1/dt that rho_inf damps out (0.066 J lost; docs/contact.md);
// requirement: the slip arcs approach ln(T1/T2)/mu as the bristle stiffness k_t grows. The elastic
//   stick carries part of the tension change before the points slip: a micro-slip zone that rigid
//   stick has not, the shear lag of a string on a tangential elastic foundation, of length
//   l = sqrt(EA / k_t), so the deficit falls as k_t^(-1/2). Measured (the mean of the arcs sampled
//   every 0.05 s over 1.9 .. 2.45 s; each sample within +-0.7 % of it, the points' spacing):
//   5.0 % short at k_t = 1e8 N/m^2, 2.9 % at 3e8, 1.7 % at 1e9 (the scene's; 100 and 200 elements,
//   4 and 8 points per element alike: converged in elements and contact points). Asserted: below 2 % at 1e9 (issue 34), and the ratio
//   of the deficits at 1e8 and 1e9 near sqrt(10) = 3.16 (2.2 .. 4.5);
// requirement: -n 1 and -n 2 give the same speeds and tensions (this test runs on both).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "strand/solvers/Dynamics.hpp"
#include "support/Belts.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

constexpr double kCentres = 0.1 * 3.141592653589793;  // the pulleys' centres' distance [m]
constexpr double kR = 0.1, kEA = 8000.0, kMu = 0.5, kLoad = 25.0, kDamping = 2.0;
constexpr double kWindowStart = 1.9, kSampleEvery = 0.05;  // the slip arcs' and speeds' samples [s]
constexpr int kSamples = 12;                                // 1.9, 1.95, .., 2.45 s

struct Steady {
  std::string failure;
  double omega1 = 0, omega2 = 0, torque2 = 0;  // speeds; the belt's torque on the driven pulley
  double ratio = 0;                            // omega2 / omega1, the mean of the window's samples
  double lambda[2] = {0, 0}, T[2] = {0, 0};    // stretch (the window's mean) and tension at the middle of the lower, upper span
  double slipArc[2] = {0, 0};                  // per pulley: the mean angle its slipping points span [rad]
  std::vector<double> arcSamples[2];           // ... every kSampleEvery from kWindowStart
  double exitGap[2] = {0, 0};                  // at the end: from the slip arc to the belt's exit [rad]
  double spacing = 0;                          // the contact points' mean angular spacing on a wrap [rad]
  long newton = 0;
  int steps = 0;
  double energyStart = 0, energyEnd = 0, loadWork = 0;  // the balance E at t = 0.05 s and the end; the work done
};

// The slip arcs at time t: per pulley, the angle its slipping points span on the wrapped half (x < 0
// for the driver at the origin, x > 0 beyond the driven one's centre); n slipping points span
// n - 1 gaps between their angles, and each stands for one gap of the arc.
struct SlipArcs {
  double arc[2] = {0, 0};
  double exitGap[2] = {0, 0};  // from the slip arc's end to where the belt leaves the pulley [rad]
  double spacing = 0;  // the contact points' mean angular spacing on a wrap [rad]
};
SlipArcs slipArcs(solvers::Problem& p, const model::SceneDescription& sc, Vec X, Vec V, double t) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  std::vector<assembly::Assembler::ContactPointOut> points;
  PetscCallAbort(comm, p.assembler().contactPoints(X, V, t, points));
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  int touching[2] = {0, 0}, slipping[2] = {0, 0};
  for (const auto& pt : points) {
    if (!pt.state.touching) continue;
    const model::Vec3& c = sc.pulleys[pt.pulley].center;
    const double dx = pt.r[0] - c[0], dy = pt.r[1] - c[1];
    if (pt.pulley == 0 ? dx > 0.0 : dx < 0.0) continue;  // the onset's few points beyond the wrap
    ++touching[pt.pulley];
    if (pt.state.sticking) continue;
    ++slipping[pt.pulley];
    double a = std::atan2(dx, -dy);  // driven: 0 .. pi from the bottom ccw; driver: -pi .. 0
    if (pt.pulley == 0) a = -a;      // driver: 0 .. pi from the bottom clockwise
    lo[pt.pulley] = std::min(lo[pt.pulley], a);
    hi[pt.pulley] = std::max(hi[pt.pulley], a);
  }
  MPI_Allreduce(MPI_IN_PLACE, lo, 2, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(MPI_IN_PLACE, hi, 2, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Allreduce(MPI_IN_PLACE, touching, 2, MPI_INT, MPI_SUM, comm);
  MPI_Allreduce(MPI_IN_PLACE, slipping, 2, MPI_INT, MPI_SUM, comm);
  SlipArcs out;
  for (int k = 0; k < 2; ++k) out.arc[k] = slipping[k] > 1 ? (hi[k] - lo[k]) * slipping[k] / (slipping[k] - 1.0) : 0.0;
  // the belt runs counterclockwise: it leaves the driver at its bottom (angle 0 as measured), the
  // driven pulley at its top (pi)
  out.exitGap[0] = lo[0];
  out.exitGap[1] = std::acos(-1.0) - hi[1];
  out.spacing = std::acos(-1.0) / std::max(1, (touching[0] + touching[1]) / 2);
  return out;
}

Steady runDrive(int elements, double kt, double dt, double tEnd) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  const model::SceneDescription sc = twoPulleyDrive(elements, kt);
  model::DynamicsDesc dd;
  dd.rhoInf = 0.8;
  dd.stepCuts = 3;  // a stiff k_t fails Newton in a few steps (k_t = 1e9: about 35 of 12,250): halve those
  dd.dt = dt;
  dd.tEnd = tEnd;
  solvers::Problem p(comm, sc);
  Vec X, V;
  PetscCallAbort(comm, p.createInitialState(&X, &V));
  Steady s;
  {
    solvers::Dynamics dyn(p.assembler(), dd);
    PetscCallAbort(comm, dyn.setFromOptions());
    double nextSample = kWindowStart;
    solvers::Dynamics::StepCallback cb = [&](const solvers::DynamicsStep& st, Vec Xs, Vec Vs) -> PetscErrorCode {
      s.newton += st.newtonIterations;
      s.steps = st.step;
      if (st.time <= 0.05 + 1e-9) s.energyStart = st.energy();
      s.energyEnd = st.energy();
      s.loadWork = st.loadWork;
      if (st.time >= nextSample - 1e-9) {  // the slip arcs over the steady state's window
        const SlipArcs a = slipArcs(p, sc, Xs, Vs, st.time);
        for (int k = 0; k < 2; ++k) s.arcSamples[k].push_back(a.arc[k]);
        std::vector<assembly::Assembler::PulleyLoad> load;
        PetscCall(p.assembler().pulleyLoads(Xs, Vs, st.time, load));
        s.ratio += load[1].speed / load[0].speed / kSamples;
        std::vector<double> q;
        PetscCall(p.assembler().gatherToRoot(Xs, q));
        q.resize(p.model().numDofs());
        MPI_Bcast(q.data(), static_cast<int>(q.size()), MPI_DOUBLE, 0, comm);
        const model::Body& b = p.model().bodies()[0];
        for (int k = 0; k < 2; ++k)  // the node nearest the middle of the lower (k = 0), upper span
          s.lambda[k] += nodeStretch(b, q, nodeNearest(b, q, 0.5 * kCentres, k == 0 ? -kR : kR)) / kSamples;
        nextSample += kSampleEvery;
      }
      return 0;
    };
    PetscCallAbort(comm, dyn.run(X, V, cb, &s.failure));
  }
  std::vector<assembly::Assembler::PulleyLoad> load;
  PetscCallAbort(comm, p.assembler().pulleyLoads(X, V, tEnd, load));
  s.omega1 = load[0].speed;
  s.omega2 = load[1].speed;
  s.torque2 = load[1].torque;
  const SlipArcs last = slipArcs(p, sc, X, V, tEnd);
  s.spacing = last.spacing;
  s.exitGap[0] = last.exitGap[0];
  s.exitGap[1] = last.exitGap[1];
  for (int k = 0; k < 2; ++k) {
    for (double a : s.arcSamples[k]) s.slipArc[k] += a;
    s.slipArc[k] /= std::max<size_t>(1, s.arcSamples[k].size());
  }
  for (int k = 0; k < 2; ++k) s.T[k] = cableTension(kEA, s.lambda[k]);
  VecDestroy(&X);
  VecDestroy(&V);
  return s;
}

}  // namespace

// Measured at t = 2.45 s (the load reached 25 N m at 1.5 s), 100 elements, 4 points each,
// dt = 2e-4 s (up to 3 halvings where Newton fails), rho_inf = 0.8; the bristle stiffness
// k_t = 1e8 N/m^2 and 1e9; speeds, stretches and slip arcs are the means of 12 samples over
// 1.9 .. 2.45 s (the driven pulley's torsional swing, decaying over 2 J / c = 0.25 s, and the
// points' spacing make single samples scatter).
TEST(TwoPulleyDrive, SteadyStateFollowsCreepTheory) {
  double deficit[2];
  const double kts[2] = {1e8, 1e9};
  for (int run = 0; run < 2; ++run) {
    const Steady s = runDrive(100, kts[run], 2e-4, 2.45);
    ASSERT_TRUE(s.failure.empty()) << s.failure;
    const int tight = s.T[1] > s.T[0] ? 1 : 0, slack = 1 - tight;
    const double T1 = s.T[tight], T2 = s.T[slack];
    const double torque = kDamping * s.omega2 + kLoad;
    ASSERT_EQ(s.arcSamples[0].size(), static_cast<size_t>(kSamples));
    const double ratio = s.ratio, creep = s.lambda[slack] / s.lambda[tight];
    const double linear = (1.0 + T2 / kEA) / (1.0 + T1 / kEA);
    const double arc = std::log(T1 / T2) / kMu;
    deficit[run] = 1.0 - 0.5 * (s.slipArc[0] + s.slipArc[1]) / arc;
    int rank;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    if (rank == 0) {
      std::printf("two-pulley drive, k_t = %g N/m^2, t = 2.45 s, %d steps, %.2f Newton iterations per step\n",
                  kts[run], s.steps, double(s.newton) / s.steps);
      std::printf("  speeds %.5f, %.5f rad/s: ratio %.6f; lambda2/lambda1 %.6f (%.2e of the creep 1 - ratio), "
                  "(1 + T2/EA)/(1 + T1/EA) %.6f\n",
                  s.omega1, s.omega2, ratio, creep, std::abs(ratio - creep) / (1.0 - creep), linear);
      std::printf("  spans: T1 %.3f N, T2 %.3f N; (T1 - T2) r = %.4f N m, belt torque on the driven pulley %.4f N m, "
                  "c omega2 + 25 = %.4f N m\n",
                  T1, T2, (T1 - T2) * kR, s.torque2, torque);
      std::printf("  slip arcs (mean over %zu samples) %.4f (driver), %.4f (driven) rad; ln(T1/T2)/mu = %.4f rad "
                  "(%.2f %% short); point spacing %.4f rad\n",
                  s.arcSamples[0].size(), s.slipArc[0], s.slipArc[1], arc, 100.0 * deficit[run], s.spacing);
      std::printf("  the slip arcs end %.4f, %.4f rad before the belt leaves the pulley\n", s.exitGap[0], s.exitGap[1]);
      std::printf("  energy balance from 0.05 s: %.3e J of %.2f J of work\n", s.energyEnd - s.energyStart, s.loadWork);
    }
    EXPECT_NEAR(s.torque2 / torque, 1.0, 2e-3);
    EXPECT_NEAR((T1 - T2) * kR / torque, 1.0, 5e-3);
    EXPECT_NEAR((1.0 - ratio) / (1.0 - creep), 1.0, 1e-2);
    EXPECT_LT(std::abs(s.energyEnd - s.energyStart), 1e-4 * s.loadWork);
    for (int k = 0; k < 2; ++k) EXPECT_LT(s.exitGap[k], 2.0 * s.spacing) << "pulley " << k;  // at the exit side
  }
  EXPECT_LT(deficit[1], 0.02);
  EXPECT_GT(deficit[0] / deficit[1], 2.2);
  EXPECT_LT(deficit[0] / deficit[1], 4.5);
}
