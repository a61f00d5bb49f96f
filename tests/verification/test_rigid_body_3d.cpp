// 3D rigid bodies on natural coordinates (model::RigidBody: centre of mass and body axes a_k, six
// orthonormality equations held by multipliers), against closed-form motions of the symmetric top
// (e.g. Goldstein, Poole & Safko, Classical Mechanics, 3rd ed., sections 5.6 and 5.7):
//  - torque-free axisymmetric body (I1 = I2): the body turns about the fixed angular momentum L at
//    |L| / I1 while spinning about its axis at psi' = omega_3 (I1 - I3) / I1 relative to that
//    turn: A(t) = R(L/|L|, |L| t / I1) A0 R(e_3, psi' t);
//  - heavy symmetric top on a spherical joint, steady precession at tilt theta: with
//    I1' = I1 + m d^2 about the pivot and the spin omega_3 = psi' + phi' cos(theta), the precession
//    rate phi' solves I1' cos(theta) phi'^2 - I3 omega_3 phi' + m g d = 0 (Goldstein Eq. 5.76), and
//    A(t) = R_z(phi' t) R_x(theta) R_z(psi' t).
// Both: the kinetic energy at t = 0 is 1/2 omega^T I omega (the constant mass diag(m, Jbar (x) I),
// Jbar = 1/2 tr(I) - I, is right); second order in time for generalized-alpha, Newmark and BDF2 on
// the GGL form; the frame stays orthonormal and the pivot holds to < 1e-9 at every step. A 3D
// cable carrying two bodies gives the same trajectory on one and on all ranks.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>

#include "strand/solvers/Dynamics.hpp"
#include "strand/solvers/Schemes.hpp"
#include "support/ExactMotionChecks.hpp"
#include "support/Scenes.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

using Mat3 = std::array<double, 9>;  // row-major

Mat3 rotation(model::Vec3 e, double angle) {  // Rodrigues, independent of the model's
  const double n = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
  for (double& x : e) x /= n;
  const double c = std::cos(angle), s = std::sin(angle);
  const double K[9] = {0, -e[2], e[1], e[2], 0, -e[0], -e[1], e[0], 0};
  Mat3 R{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double KK = 0.0;
      for (int k = 0; k < 3; ++k) KK += K[i * 3 + k] * K[k * 3 + j];
      R[i * 3 + j] = (i == j ? 1.0 : 0.0) + s * K[i * 3 + j] + (1.0 - c) * KK;
    }
  return R;
}

Mat3 operator*(const Mat3& A, const Mat3& B) {
  Mat3 C{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) C[i * 3 + j] += A[i * 3 + k] * B[k * 3 + j];
  return C;
}

model::Vec3 turn(const Mat3& A, const model::Vec3& x) {
  model::Vec3 y{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) y[i] += A[i * 3 + j] * x[j];
  return y;
}

model::DynamicsDesc scheme(model::Integrator integrator, double rhoInf, double dt, double tEnd) {
  model::DynamicsDesc d;
  d.integrator = integrator;
  d.rhoInf = rhoInf;
  d.bdfOrder = 2;
  d.hhtAlpha = 0.1;
  d.dt = dt;
  d.tEnd = tEnd;
  return d;
}

struct BodyRun {
  double kinetic0 = 0.0, e0 = 0.0, drift = 0.0;  // energy: at t = 0, largest |E - E0|
  double position = 0.0, velocity = 0.0;           // largest |g| and |G v| over all steps
  std::vector<double> q;                           // final coordinates q = q0 + u (model numbering)
  std::string failure;
};

BodyRun run(MPI_Comm comm, const model::SceneDescription& sc, const model::DynamicsDesc& d) {
  model::SceneDescription scene = sc;
  scene.dynamics = d;
  solvers::Problem p(comm, scene);
  Vec X, V;
  PetscCallAbort(comm, p.createInitialState(&X, &V));
  BodyRun out;
  solvers::Dynamics dyn(p.assembler(), d);
  solvers::Dynamics::StepCallback cb = [&](const solvers::DynamicsStep& s, Vec, Vec) -> PetscErrorCode {
    if (s.step == 0) {
      out.e0 = s.energy();
      out.kinetic0 = s.kinetic;
    }
    out.drift = std::max(out.drift, std::fabs(s.energy() - out.e0));
    out.position = std::max(out.position, s.constraintPosition);
    out.velocity = std::max(out.velocity, s.constraintVelocity);
    return 0;
  };
  PetscCallAbort(comm, dyn.run(X, V, cb, &out.failure));
  PetscCallAbort(comm, p.assembler().gatherToRoot(X, out.q));
  const int n = p.model().numDofs();
  out.q.resize(n);
  MPI_Bcast(out.q.data(), n, MPI_DOUBLE, 0, comm);
  VecDestroy(&X);
  VecDestroy(&V);
  return out;
}

// The largest entry of A - exact (A: the frame blocks of body `body`, a_k its columns) and the
// distance of the centre of mass from `centre`.
double frameError(const solvers::Problem& p, const std::vector<double>& q, int body, const Mat3& exact) {
  const int a = p.model().rigidBodies()[body].rotBlock;
  double e = 0.0;
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) e = std::max(e, std::fabs(q[(a + k) * 3 + i] - exact[i * 3 + k]));
  return e;
}

struct Member {
  model::Integrator integrator;
  double rho;
  const char* name;
};
const Member kMembers[] = {{model::Integrator::GeneralizedAlpha, 0.8, "alpha 0.8"},
                           {model::Integrator::Hht, 1.0, "HHT 0.1"},
                           {model::Integrator::Bdf, 1.0, "BDF2 GGL"}};

// Torque-free symmetric top: m = 1.5 kg, I = (0.02, 0.02, 0.012) kg m^2, turned by 0.3 rad about
// x, body-frame angular velocity (2, 0, 15) rad/s.
struct FreeTop {
  double m = 1.5;
  model::Vec3 I{0.02, 0.02, 0.012}, omegaBody{2.0, 0.0, 15.0};
  Mat3 A0 = rotation({1, 0, 0}, 0.3);
  model::SceneDescription scene() const {
    model::SceneDescription sc;
    sc.file = "(test)";
    sc.dimension = 3;
    sc.analysis = model::Analysis::Dynamic;
    model::RigidBodyDesc r;
    r.name = "top";
    r.mass = m;
    r.principalInertia = I;
    r.position = {0.1, 0.2, 0.3};
    r.axis = {1, 0, 0};
    r.angle = 0.3;
    r.angularVelocity = turn(A0, omegaBody);
    sc.rigidBodies.push_back(r);
    return sc;
  }
  Mat3 exact(double t) const {
    model::Vec3 Lb{I[0] * omegaBody[0], I[1] * omegaBody[1], I[2] * omegaBody[2]};
    const model::Vec3 L = turn(A0, Lb);
    const double Ln = std::sqrt(L[0] * L[0] + L[1] * L[1] + L[2] * L[2]);
    const double psiRate = omegaBody[2] * (I[0] - I[2]) / I[0];
    return rotation(L, Ln * t / I[0]) * A0 * rotation({0, 0, 1}, psiRate * t);
  }
};

// Heavy symmetric top: m = 1 kg, I = (0.004, 0.004, 0.006) kg m^2 about the centre of mass, which
// sits d = 0.1 m up the symmetry axis from a spherical joint at the origin; gravity -9.81 z; tilt
// theta = 0.4 rad (about x), spin omega_3 = 40 rad/s, the slow steady precession.
struct HeavyTop {
  double m = 1.0, d = 0.1, g = 9.81, theta = 0.4, spin = 40.0;
  model::Vec3 I{0.004, 0.004, 0.006};
  double precession() const {  // the slow root of I1' cos(theta) phi'^2 - I3 omega_3 phi' + m g d = 0
    const double a = (I[0] + m * d * d) * std::cos(theta), b = I[2] * spin, c = m * g * d;
    return (b - std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
  }
  double psiRate() const { return spin - precession() * std::cos(theta); }
  Mat3 exact(double t) const {
    return rotation({0, 0, 1}, precession() * t) * rotation({1, 0, 0}, theta) * rotation({0, 0, 1}, psiRate() * t);
  }
  model::SceneDescription scene() const {
    model::SceneDescription sc;
    sc.file = "(test)";
    sc.dimension = 3;
    sc.analysis = model::Analysis::Dynamic;
    sc.loads.gravity = {0, 0, -g};
    const Mat3 A0 = rotation({1, 0, 0}, theta);
    const model::Vec3 a3{A0[2], A0[5], A0[8]};
    model::Vec3 w{0, 0, precession()};
    for (int i = 0; i < 3; ++i) w[i] += psiRate() * a3[i];
    model::RigidBodyDesc r;
    r.name = "top";
    r.mass = m;
    r.principalInertia = I;
    r.position = {d * a3[0], d * a3[1], d * a3[2]};
    r.axis = {1, 0, 0};
    r.angle = theta;
    r.angularVelocity = w;
    r.velocity = {w[1] * r.position[2] - w[2] * r.position[1], w[2] * r.position[0] - w[0] * r.position[2],
                  w[0] * r.position[1] - w[1] * r.position[0]};
    sc.rigidBodies.push_back(r);
    model::JointDesc pivot;
    pivot.type = model::JointType::Pin;
    pivot.a.kind = model::JointEndDesc::Kind::RigidPoint;
    pivot.a.body = "top";
    pivot.a.point = {0, 0, -d};
    pivot.b.kind = model::JointEndDesc::Kind::Ground;
    sc.joints.push_back(pivot);
    return sc;
  }
};

// Every member of kMembers at 250, 500 and 1000 steps to tEnd against the exact frame: the error
// (largest entry of A - A_exact) falls at rate 2 +- 0.2, the constraints hold (|g| < 1e-9, GGL also
// |G v|), and check(run, error) asserts the case's own quantities.
void expectSecondOrder(const char* label, const model::SceneDescription& sc, const Mat3& exact, double tEnd,
                       const std::function<void(const Member&, const BodyRun&, double)>& check) {
  solvers::Problem p(PETSC_COMM_WORLD, sc);
  for (const Member& mb : kMembers) {
    double err[3];
    for (int k = 0; k < 3; ++k) {
      const int steps = 250 << k;
      const BodyRun r = run(PETSC_COMM_WORLD, sc, scheme(mb.integrator, mb.rho, tEnd / steps, tEnd));
      ASSERT_EQ(r.failure, "") << mb.name;
      err[k] = frameError(p, r.q, 0, exact);
      EXPECT_LT(r.position, 1e-9) << mb.name << ": a joint or the frame drifts";
      if (mb.integrator == model::Integrator::Bdf) {
        EXPECT_LT(r.velocity, 1e-9) << mb.name << ": GGL holds the velocity level too";
      }
      check(mb, r, err[k]);
      std::printf("%s %-10s steps %4d  |A - A_exact| %.3e  |g| %.1e  |G v| %.1e  energy drift %.2e J\n", label,
                  mb.name, steps, err[k], r.position, r.velocity, r.drift);
    }
    const double rate = std::log2(err[1] / err[2]);
    std::printf("%s %-10s rate %.3f\n", label, mb.name, rate);
    EXPECT_NEAR(rate, 2.0, 0.2) << label << " " << mb.name;
  }
}

}  // namespace

TEST(RigidBody3d, TorqueFreeSymmetricTopFollowsEulersSolutionAtSecondOrder) {
  const FreeTop top;
  const double tEnd = 1.0, kinetic = 0.5 * (top.I[0] * 4.0 + top.I[2] * 225.0);  // 1/2 omega^T I omega
  const model::SceneDescription sc = top.scene();
  std::printf("free top: kinetic energy 1/2 omega^T I omega = %.4f J\n", kinetic);
  expectSecondOrder("free top", sc, top.exact(tEnd), tEnd, [&](const Member&, const BodyRun& r, double) {
    EXPECT_NEAR(r.kinetic0 / kinetic, 1.0, 1e-13) << "the kinetic energy of the initial spin";
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(r.q[i], sc.rigidBodies[0].position[i], 1e-12) << "the centre of mass rests";
  });
}

// The frame's six equations are index-3 constraints on generalized-alpha: without high-frequency
// damping (Newmark, rho_inf = 1) the multipliers' error grows until Newton fails, and the run
// stops saying so (the 2D chain does the same, test_multibody.cpp).
TEST(RigidBody3d, UndampedNewmarkOnTheFrameEquationsStopsWithAnExplanation) {
  const FreeTop top;
  const BodyRun r = run(PETSC_COMM_WORLD, top.scene(), scheme(model::Integrator::Newmark, 1.0, 4e-3, 1.0));
  std::printf("%s\n", r.failure.c_str());
  EXPECT_NE(r.failure.find("Newmark"), std::string::npos);
  EXPECT_NE(r.failure.find("Use rho_inf <= 0.9"), std::string::npos);
}

TEST(RigidBody3d, HeavyTopPrecessesSteadilyAtSecondOrder) {
  const HeavyTop top;
  const double tEnd = 0.5;
  std::printf("heavy top: precession phi' = %.6f rad/s, psi' = %.6f rad/s\n", top.precession(), top.psiRate());
  const Mat3 exact = top.exact(tEnd);
  const model::SceneDescription sc = top.scene();
  const int c = solvers::Problem(PETSC_COMM_WORLD, sc).model().rigidBodies()[0].posBlock;
  expectSecondOrder("heavy top", sc, exact, tEnd, [&](const Member& mb, const BodyRun& r, double err) {
    for (int i = 0; i < 3; ++i)  // the centre of mass is d a_3
      EXPECT_NEAR(r.q[c * 3 + i], top.d * exact[i * 3 + 2], 2.0 * top.d * err + 1e-12) << mb.name;
  });
}

// A 3D cable carrying two rigid bodies (one clamped to its tip, one pinned to that; torque, nodal
// moment, gravity; support/Scenes.hpp) swings for 0.2 s: the same trajectory on all ranks as on one.
TEST(RigidBody3d, CableWithTwoBodiesHasTheSameTrajectoryOnOneAndOnAllRanks) {
  const model::SceneDescription sc = cableWithTwoBodies3d(1e7);
  for (const Member& mb : {kMembers[0], kMembers[2]}) {
    const model::DynamicsDesc d = scheme(mb.integrator, mb.rho, 1e-3, 0.2);
    const BodyRun all = run(PETSC_COMM_WORLD, sc, d);
    const BodyRun one = run(PETSC_COMM_SELF, sc, d);
    ASSERT_EQ(all.failure, "") << mb.name;
    ASSERT_EQ(one.failure, "") << mb.name;
    ASSERT_EQ(all.q.size(), one.q.size());
    double diff = 0.0;
    for (size_t i = 0; i < all.q.size(); ++i) diff = std::max(diff, std::fabs(all.q[i] - one.q[i]));
    std::printf("cable with two bodies (%s) at t = 0.2 s: largest coordinate difference all ranks vs one %.2e, "
                "|g| %.1e\n", mb.name, diff, all.position);
    EXPECT_LT(diff, 1e-8) << mb.name;
    EXPECT_LT(all.position, 1e-9) << mb.name;
  }
}

namespace {

// A 3D driven hub carrying a link: the hub (m = 10 kg, principal inertia (2, 3, 4) kg m^2 along the
// world axes at t = 0, centre fixed at the origin) turns about the tilted axis e = (1, 0, 2)/sqrt(5)
// by psi(t) - psi(0), psi = 0.5 sin(pi t + pi/4) rad (it starts turning and accelerating); a link
// (m = 3 kg) is held by a spherical joint at its centre of mass to the hub point p = (0.8, 0.3, -0.2) m.
// No gravity. The joint at the centre leaves the link's rotation free and unloaded (it keeps its
// initial frame), so with R = R_e(psi(t) - psi(0)), exactly (Newton and Euler for link and hub):
//   link centre  x = R p;   ground force on the hub centre = m x'' (the link's inertia force);
//   drive torque about e:  tau . e = (e^T I e + m |p_perp|^2) psi'',  p_perp = p - (p . e) e,
// the torque taken from the support force on the hub's axes a_k as tau = sum_k a_k x f_k
// (virtual work f_k . (dtheta x a_k) = dtheta . a_k x f_k); and T - T(0) = W_drive.
struct DrivenHub3d {
  static constexpr double kHubMass = 10.0;  // the link's mass and the drive psi: CarriedLink.hpp's
  model::Vec3 e{1.0 / std::sqrt(5.0), 0.0, 2.0 / std::sqrt(5.0)};
  model::Vec3 I{2.0, 3.0, 4.0}, p{0.8, 0.3, -0.2};
  double axialInertia() const {  // e^T I e + m |p_perp|^2
    const double pe = p[0] * e[0] + p[1] * e[1] + p[2] * e[2];
    double perp2 = 0.0, eIe = 0.0;
    for (int i = 0; i < 3; ++i) {
      perp2 += std::pow(p[i] - pe * e[i], 2);
      eIe += I[i] * e[i] * e[i];
    }
    return eIe + kLinkMass * perp2;
  }
  model::SceneDescription scene() const {
    model::SceneDescription sc;
    sc.file = "(test)";
    sc.dimension = 3;
    sc.analysis = model::Analysis::Dynamic;
    model::RigidBodyDesc hub;
    hub.name = "hub";
    hub.mass = kHubMass;
    hub.principalInertia = I;
    hub.fixed = {0, 1, 2};
    hub.driven = true;
    hub.rotation = driveFunction();
    hub.rotationAxis = e;
    sc.rigidBodies.push_back(hub);
    model::RigidBodyDesc link;
    link.name = "link";
    link.mass = kLinkMass;
    link.principalInertia = {0.5, 0.6, 0.7};
    link.position = p;
    sc.rigidBodies.push_back(link);
    pinLinkCentreToHub(sc, p);
    return sc;
  }
};

// The largest errors of a run against the exact motion (tests/support/CarriedLink.hpp).
CarriedLink runDrivenHub(const DrivenHub3d& c, const model::DynamicsDesc& d) {
  const double peak = kDriveAmplitude * kDriveOmega * kDriveOmega;  // |psi''| max (and |psi'|^2 max)
  const double peakTorque = c.axialInertia() * peak;
  const double radius = std::sqrt(c.p[0] * c.p[0] + c.p[1] * c.p[1] + c.p[2] * c.p[2]);
  // scales: |x''| <= |p| (|psi''| + psi'^2) <= 2 |p| a w^2 (a <= 1); T <= J_e (a w)^2 / 2
  const double peakForce = kLinkMass * radius * 2.0 * peak;
  const double peakKinetic = 0.5 * c.axialInertia() * std::pow(kDriveAmplitude * kDriveOmega, 2);
  const double psi0 = drive(0.0).f;
  auto exact = [&](const model::Model& m, double t, const std::vector<double>& q, const std::vector<double>& f) {
    const model::RigidBody &h = m.rigidBodies()[0], &l = m.rigidBodies()[1];
    const model::TimeValue s = drive(t);
    const model::Vec3 x = turn(rotation(c.e, s.f - psi0), c.p);
    // x'' = psi'' e x x + psi'^2 e x (e x x)
    const model::Vec3 ex{c.e[1] * x[2] - c.e[2] * x[1], c.e[2] * x[0] - c.e[0] * x[2], c.e[0] * x[1] - c.e[1] * x[0]};
    const model::Vec3 eex{c.e[1] * ex[2] - c.e[2] * ex[1], c.e[2] * ex[0] - c.e[0] * ex[2], c.e[0] * ex[1] - c.e[1] * ex[0]};
    double dx = 0.0, df = 0.0;
    for (int i = 0; i < 3; ++i) {
      dx += std::pow(q[l.posBlock * 3 + i] - x[i], 2);
      df += std::pow(f[h.posBlock * 3 + i] - kLinkMass * (s.ddf * ex[i] + s.df * s.df * eex[i]), 2);
    }
    double tau = 0.0;  // e . sum_k a_k x f_k
    for (int k = 0; k < 3; ++k) {
      const double* a = &q[(h.rotBlock + k) * 3];
      const double* fk = &f[(h.rotBlock + k) * 3];
      const double axf[3] = {a[1] * fk[2] - a[2] * fk[1], a[2] * fk[0] - a[0] * fk[2], a[0] * fk[1] - a[1] * fk[0]};
      for (int i = 0; i < 3; ++i) tau += c.e[i] * axf[i];
    }
    MotionErrors e;
    e.position = std::sqrt(dx);
    e.force = std::sqrt(df) / peakForce;
    e.torque = std::fabs(tau - c.axialInertia() * s.ddf) / peakTorque;
    return e;
  };
  return runAgainstExactMotion(c.scene(), d, peakKinetic, exact);
}

}  // namespace

// A driven 3D rigid body (rigid_bodies[].rotation with rotation_axis): its axes are prescribed and
// eliminated like a turning hub (no frame equations). The link it carries (DrivenHub3d) follows the
// exact motion, and the support force on the hub gives the ground force and the drive torque about
// the axis at second order on generalized-alpha (rho_inf 0.9) and BDF2-GGL, exact at t = 0.
TEST(RigidBody3d, DrivenHubCarriesALinkAsNewtonAndEulerSay) {
  const DrivenHub3d c;
  expectSecondOrderAgainstExactMotion("3D driven hub", 2.0, [&](const model::DynamicsDesc& d) { return runDrivenHub(c, d); });
}
