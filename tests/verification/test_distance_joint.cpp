// Dynamic verification of the distance joint (issue 3; JointType::Distance, the kernel
// |a - b| - L = 0 of include/strand/elements/Constraint.hpp, its multiplier the tension), at -n 1
// and -n 2. tests/unit/test_constraint.cpp checks its equations (exact derivatives); this checks the
// motion they produce.
//
// Scene: a rigid body ("bob", m = 2 kg, J = 0.05 kg m^2 about its centre of mass) whose centre of
// mass is held at the distance l = 1.2 m from the ground point (0, 0) by a distance joint, released
// at rest from (l, 0) (horizontal) under gravity -9.81 y, spinning about its centre at 3 rad/s.
// Exact motion:
//  - the joint force acts along the line through the centre of mass, so it has no moment about it:
//    the body's spin is constant (Euler's second law), phi(t) = 3 t, and the centre of mass moves as
//    a simple pendulum of length l, theta'' = -(g/l) cos(theta) (theta from +x, theta(0) = 0), here
//    integrated by RK4 with 64 substeps per step of the run;
//  - half period T/2 = 2 sqrt(l/g) K(sin(theta0/2)) for the amplitude theta0 = 90 deg from the
//    vertical (Landau & Lifshitz, Mechanics, Sec. 11, Problem 1; K the complete elliptic integral of
//    the first kind): the centre crosses the bottom at T/4 and turns back at T/2 at (-l, 0);
//  - rod tension (radial Newton law m v^2 / l = T - m g cos(psi), psi from the downward vertical, and
//    energy v^2 = 2 g l cos(psi)): T = m (v^2 / l + g cos(psi)) = 3 m g cos(psi) = -3 m g sin(theta).
// requirement: |a - b| = l to < 1e-9 m at every step (index 3 on generalized-alpha, GGL on BDF2); the
// spin constant to the Newton tolerance (1e-8); the centre's path, the tension (the joint's multiplier) and the times of
// the bottom crossing and of the turning point converge to the exact ones at rate 2 (+-0.1 for
// errors over the run, +-0.15 for the two times) for generalized-alpha (rho_inf 0.9) and BDF2.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "strand/solvers/Dynamics.hpp"
#include "strand/solvers/Schemes.hpp"
#include "support/ExactPendulum.hpp"
#include "support/Scenes.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

constexpr double kG = 9.81, kL = 1.2, kM = 2.0, kJ = 0.05, kSpin = 3.0;
constexpr int kSubsteps = 64;  // reference RK4 substeps per step of the run

// theta(t) of theta'' = -(g/l) cos(theta), theta(0) = theta'(0) = 0, by RK4 with n steps to tEnd;
// theta[i] at t = i tEnd / n.
std::vector<double> referenceSwing(double tEnd, int n) {
  const double c = kG / kL, h = tEnd / n;
  std::vector<double> theta{0.0};
  double th = 0.0, w = 0.0;
  for (int i = 0; i < n; ++i) {
    pendulumRk4Step(c, h, th, w);
    theta.push_back(th);
  }
  return theta;
}

model::SceneDescription bobOnADistanceJoint() {
  model::SceneDescription sc;
  sc.file = "(test)";
  sc.dimension = 2;
  sc.analysis = model::Analysis::Dynamic;
  sc.loads.gravity = {0, -kG, 0};
  model::RigidBodyDesc b;
  b.name = "bob";
  b.mass = kM;
  b.inertia = kJ;
  b.position = {kL, 0, 0};
  b.angularVelocity = {0, 0, kSpin};
  sc.rigidBodies.push_back(b);
  model::JointDesc j;  // docs/scene-reference.md, "joints": {type: distance, a: {body: bob}, b: {ground: [0, 0]}, length: 1.2}
  j.type = model::JointType::Distance;
  j.a.kind = model::JointEndDesc::Kind::RigidPoint;
  j.a.body = "bob";  // point (0, 0): the centre of mass
  j.b.kind = model::JointEndDesc::Kind::Ground;
  j.length = kL;
  sc.joints.push_back(j);
  return sc;
}

struct SwingRun {
  double monitorG = 0.0, length = 0.0;  // max |g| (monitor) and max ||r| - l| from the coordinates [m]
  double spin = 0.0, spinRate = 0.0;    // max |phi - 3 t| [rad], max |phi' - 3| [rad/s]
  double path = 0.0;                    // max |r - r_exact| / l
  double tension = 0.0;                 // max |lambda - T_exact| / (3 m g)
  double bottom = -1.0, turn = -1.0;    // times of theta = -pi/2 and of v_y = 0 near theta = -pi [s]
  std::string failure;
};

// Runs the scene with d to tEnd = N dt; the errors are taken on rank 0 and broadcast.
SwingRun swing(const model::DynamicsDesc& d, int N) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  const std::vector<double> ref = referenceSwing(d.tEnd, N * kSubsteps);
  model::SceneDescription sc = bobOnADistanceJoint();
  sc.dynamics = d;
  solvers::Problem p(comm, sc);
  Vec X, V;
  PetscCallAbort(comm, p.createInitialState(&X, &V));
  solvers::Dynamics dyn(p.assembler(), d);
  // The default Newton (kept matrix). Its stop at 1e-3 of the first correction is what makes the
  // tension converge here: with the old absolute stop (-dyn_newton_kept_tolerance 0) the
  // index-3 multiplier, positions times s = 1/(beta h^2), carried the Newton error into the
  // scheme's spurious root, an oscillation from step to step, and the tension error grew as h fell
  // (4.95e-5, 1.15e-4, 1.98e-3 of 3 m g at h = 2, 1, 0.5 ms; full Newton and now the default:
  // 4.95e-5, 1.24e-5, 3.09e-6).
  const model::RigidBody& rb = p.model().rigidBodies()[0];
  const int lambdaDof = p.model().joints()[0].lambdaBlocks[0] * 2;
  SwingRun out;
  double prevTheta = 0.0, prevTime = 0.0, prevVy = 0.0;
  solvers::Dynamics::StepCallback cb = [&](const solvers::DynamicsStep& s, Vec Xs, Vec Vs) -> PetscErrorCode {
    PetscFunctionBeginUser;
    out.monitorG = std::max(out.monitorG, s.constraintPosition);
    std::vector<double> q, v;
    PetscCall(p.assembler().gatherToRoot(Xs, q));
    PetscCall(p.assembler().gatherToRoot(Vs, v));
    if (q.empty()) PetscFunctionReturn(0);  // not rank 0
    const double x = q[rb.posBlock * 2], y = q[rb.posBlock * 2 + 1], vy = v[rb.posBlock * 2 + 1];
    const double r = std::hypot(x, y);
    out.length = std::max(out.length, std::fabs(r - kL));
    out.spin = std::max(out.spin, std::fabs(q[rb.rotBlock * 2] - kSpin * s.time));
    out.spinRate = std::max(out.spinRate, std::fabs(v[rb.rotBlock * 2] - kSpin));
    const long n = std::lround(s.time / d.dt);
    const double thetaRef = ref[n * kSubsteps];
    out.path = std::max(out.path, std::hypot(x - kL * std::cos(thetaRef), y - kL * std::sin(thetaRef)) / kL);
    // the multiplier unknown is lambda / s (s = the constraint scale: index 3 shiftA, GGL 1/dt^2);
    // for g = |a - b| - l the force on the bob is -lambda (a - b)/|a - b|: lambda is the tension
    const double lambda = q[lambdaDof] * p.assembler().constraintScale();
    out.tension = std::max(out.tension, std::fabs(lambda + 3.0 * kM * kG * std::sin(thetaRef)) / (3.0 * kM * kG));
    // continuous angle of the centre in (-3pi/2, pi/2]: it swings from 0 through -pi/2 to -pi
    double theta = std::atan2(y, x);
    if (theta > M_PI / 2) theta -= 2.0 * M_PI;
    if (s.step > 0 && out.bottom < 0.0 && theta < -M_PI / 2 && prevTheta >= -M_PI / 2)
      out.bottom = prevTime + (s.time - prevTime) * (-M_PI / 2 - prevTheta) / (theta - prevTheta);
    // rising to theta = -pi the centre moves up (v_y = -l theta' > 0); at the turning point v_y
    // changes sign at the rate -g, linearly, so the crossing is interpolated to O(h^2)
    if (s.step > 0 && out.turn < 0.0 && theta < -3.0 * M_PI / 4 && prevVy > 0.0 && vy <= 0.0)
      out.turn = prevTime + (s.time - prevTime) * prevVy / (prevVy - vy);
    prevTheta = theta;
    prevTime = s.time;
    prevVy = vy;
    PetscFunctionReturn(0);
  };
  PetscCallAbort(comm, dyn.run(X, V, cb, &out.failure));
  // from rank 0's gathered coordinates (monitorG is the monitor's global value on every rank)
  double e[7] = {out.length, out.spin, out.spinRate, out.path, out.tension, out.bottom, out.turn};
  MPI_Bcast(e, 7, MPI_DOUBLE, 0, comm);
  out.length = e[0];
  out.spin = e[1];
  out.spinRate = e[2];
  out.path = e[3];
  out.tension = e[4];
  out.bottom = e[5];
  out.turn = e[6];
  VecDestroy(&X);
  VecDestroy(&V);
  return out;
}

}  // namespace

TEST(DistanceJoint, BodyOnADistanceJointSwingsAsASimplePendulumAndKeepsItsSpin) {
  const double quarter = std::sqrt(kL / kG) * ellipticK(std::sin(M_PI / 4.0));  // T/4 = 0.6484602 s
  const double tEnd = 2.1 * quarter;  // past the turning point at T/2
  {  // the reference integrator is right: it reaches theta = -pi at T/2 (closed form)
    const std::vector<double> ref = referenceSwing(2.0 * quarter, 200000);
    EXPECT_NEAR(ref.back(), -M_PI, 1e-9);
  }
  for (model::Integrator integrator : {model::Integrator::GeneralizedAlpha, model::Integrator::Bdf}) {
    SwingRun r[3];
    for (int k = 0; k < 3; ++k) {
      const int N = 680 << k;  // h = 2.0, 1.0, 0.5 ms
      model::DynamicsDesc d;   // rho_inf 0.9, BDF order 2 (GGL): the defaults
      d.integrator = integrator;
      d.dt = tEnd / N;
      d.tEnd = tEnd;
      r[k] = swing(d, N);
      ASSERT_EQ(r[k].failure, "");
      std::printf("%-17s h %.3e: max ||r| - l| %.1e m (monitor %.1e), spin %.1e rad, %.1e rad/s; path %.3e l, "
                  "tension %.3e of 3mg; bottom at %.9f s (T/4 %+.3e), turn at %.9f s (T/2 %+.3e)\n",
                  solvers::schemeName(d).c_str(), d.dt, r[k].length, r[k].monitorG, r[k].spin, r[k].spinRate, r[k].path,
                  r[k].tension, r[k].bottom, r[k].bottom - quarter, r[k].turn, r[k].turn - 2.0 * quarter);
      EXPECT_LT(r[k].length, 1e-9) << "the distance joint drifts";
      EXPECT_LT(r[k].monitorG, 1e-9);
      // 1e-8: Newton's step test (|du| < 1e-12 |q| per step, |q| <= 5) over N <= 2720 steps allows
      // 1.4e-8 rad; a joint force with a moment arm e about the centre would turn the body by about
      // T e t^2 / (2 J) ~ 1e3 e rad/m within the swing, i.e. more than 1e-8 rad for e > 1e-11 m
      EXPECT_LT(r[k].spin, 1e-8) << "the joint force has a moment about the centre of mass";
      EXPECT_LT(r[k].spinRate, 1e-8);
      ASSERT_GT(r[k].bottom, 0.0);
      ASSERT_GT(r[k].turn, 0.0);
    }
    const char* name = integrator == model::Integrator::Bdf ? "BDF2" : "generalized-alpha";
    auto rate = [&](auto get) { return std::log2(std::fabs(get(r[1]) / get(r[2]))); };
    const double path = rate([](const SwingRun& s) { return s.path; });
    const double tension = rate([](const SwingRun& s) { return s.tension; });
    const double bottom = rate([&](const SwingRun& s) { return s.bottom - quarter; });
    const double turn = rate([&](const SwingRun& s) { return s.turn - 2.0 * quarter; });
    std::printf("%s rates: path %.3f, tension %.3f, bottom crossing %.3f, turning point %.3f\n", name, path, tension,
                bottom, turn);
    EXPECT_NEAR(path, 2.0, 0.1) << name;
    EXPECT_NEAR(tension, 2.0, 0.1) << name;
    EXPECT_NEAR(bottom, 2.0, 0.15) << name;
    EXPECT_NEAR(turn, 2.0, 0.15) << name;
  }
}
