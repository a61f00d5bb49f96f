// A link carried by a driven hub (issue 3: joints on a driven body, consistent start, support
// forces), with an exact solution; used by tests/verification/test_multibody.cpp (2D),
// tests/verification/test_rigid_body_3d.cpp (3D, through runAgainstExactMotion) and
// tests/benchmarks/bench_joints.cpp.
#pragma once
#include <petsctime.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "strand/solvers/Dynamics.hpp"
#include "support/Scenes.hpp"

namespace strand::testing {

// A link carried by a driven hub: hub (I_h = 2 kg m^2, fixed x, y) turned by
// psi(t) = a sin(w t + phi0) (a = 0.5 rad, 0.5 Hz, phi0 = pi/4: it starts turning *and*
// accelerating), a rigid link (m = 3 kg, J = 0.7 kg m^2) pinned at its centre of mass to the hub
// point p = (0.8, 0.3) m, no gravity. The scene's hub angle (0) is the one at t = 0, so the hub turns
// by psi(t) - psi(0). The pin at the centre leaves the link's angle free and unloaded, so the exact
// motion is known for all t (Newton's laws for the link and the hub), with R = R(psi(t) - psi(0)):
//   link centre  x = R p,   link angle = its initial one,
//   pin force on the link  F = m (psi'' e_z x R p - psi'^2 R p),
//   drive torque  tau = (I_h + m |p|^2) psi'',  ground force on the hub = F,
// and the energy T = (I_h + m |p|^2) psi'^2 / 2 equals T(0) + the drive's work.
// The start must already be consistent: the link at rest is given the pin's velocity psi'(0) e_z x
// R p by the projection [M G^T; G 0][v; nu] = [M v; -G_s v_p], and its acceleration from the
// prescribed psi''(0) (Dynamics::consistentAcceleration).
inline constexpr double kHubInertia = 2.0, kLinkMass = 3.0, kDriveAmplitude = 0.5, kDriveOmega = M_PI,
                 kDrivePhase = M_PI / 4.0;
inline constexpr double kPin[2] = {0.8, 0.3};

inline model::TimeValue drive(double t) {
  const double s = std::sin(kDriveOmega * t + kDrivePhase), c = std::cos(kDriveOmega * t + kDrivePhase);
  return {kDriveAmplitude * s, kDriveAmplitude * kDriveOmega * c, -kDriveAmplitude * kDriveOmega * kDriveOmega * s};
}

// The same drive as the scene's time function (a hub's `rotation`).
inline model::TimeFunction driveFunction() {
  model::TimeFunction f;
  f.kind = model::TimeFunction::Kind::Sine;
  f.amplitude = kDriveAmplitude;
  f.frequency = kDriveOmega / (2.0 * M_PI);
  f.phase = kDrivePhase;
  return f;
}

struct CarriedLink {
  double startVelocity = 0.0;  // |G v| at t = 0
  double startTorque = 0.0, startForce = 0.0;  // |error| at t = 0, relative to the peak torque / force
  double torque = 0.0, force = 0.0, position = 0.0;  // largest errors over the run (relative; m)
  double energy = 0.0;         // max |T - T(0) - W_drive| relative to the peak kinetic energy
  double seconds = 0.0;        // wall time of Dynamics::run (including the monitors above)
  long steps = 0, newton = 0;
  std::string failure;
};

// A pin (2D) or spherical joint (3D) from the centre of rigid body "link" to the point p of "hub".
inline void pinLinkCentreToHub(model::SceneDescription& sc, const model::Vec3& p) {
  model::JointDesc pin;
  pin.type = model::JointType::Pin;
  pin.a.kind = model::JointEndDesc::Kind::RigidPoint;
  pin.a.body = "link";
  pin.b.kind = model::JointEndDesc::Kind::RigidPoint;
  pin.b.body = "hub";
  pin.b.point = p;
  sc.joints.push_back(pin);
}

// Errors of one state against the exact motion: the link's centre [m], and the drive torque and the
// ground force on the hub relative to their peaks.
struct MotionErrors {
  double position = 0.0, torque = 0.0, force = 0.0;
};
// (model, t, q = q0 + u in model order, support force f in model order) -> errors; called on rank 0.
using ExactMotion = std::function<MotionErrors(const model::Model& m, double t, const std::vector<double>& q,
                                               const std::vector<double>& f)>;

// Runs scene sc with d and records, at every step, the largest errors of `exact` and of the energy
// balance (relative to peakKinetic), and the start's |G v| and errors.
inline CarriedLink runAgainstExactMotion(model::SceneDescription sc, const model::DynamicsDesc& d, double peakKinetic,
                                         const ExactMotion& exact) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  sc.dynamics = d;
  solvers::Problem p(comm, sc);
  Vec X, V, F;
  PetscCallAbort(comm, p.createInitialState(&X, &V));
  PetscCallAbort(comm, VecDuplicate(X, &F));
  solvers::Dynamics dyn(p.assembler(), d);
  CarriedLink out;
  double e0 = 0.0;
  solvers::Dynamics::StepCallback cb = [&](const solvers::DynamicsStep& st, Vec Xs, Vec) -> PetscErrorCode {
    PetscFunctionBeginUser;
    if (st.step == 0) {
      e0 = st.energy();
      out.startVelocity = st.constraintVelocity;
    }
    out.energy = std::max(out.energy, std::fabs(st.energy() - e0) / peakKinetic);
    std::vector<double> q, f;
    PetscCall(p.assembler().gatherToRoot(Xs, q));
    PetscCall(dyn.supportForce(F));
    PetscCall(p.assembler().toModelOrder(F, f));
    MotionErrors e;
    if (!q.empty()) e = exact(p.model(), st.time, q, f);
    double err[3] = {e.position, e.torque, e.force};
    MPI_Bcast(err, 3, MPI_DOUBLE, 0, comm);
    if (st.step == 0) {
      out.startTorque = err[1];
      out.startForce = err[2];
    }
    out.position = std::max(out.position, err[0]);
    out.torque = std::max(out.torque, err[1]);
    out.force = std::max(out.force, err[2]);
    out.steps = st.step;
    out.newton += st.newtonIterations;
    PetscFunctionReturn(0);
  };
  PetscLogDouble t0, t1;
  PetscCallAbort(comm, PetscTime(&t0));
  PetscCallAbort(comm, dyn.run(X, V, cb, &out.failure));
  PetscCallAbort(comm, PetscTime(&t1));
  out.seconds = t1 - t0;
  VecDestroy(&X);
  VecDestroy(&V);
  VecDestroy(&F);
  return out;
}

// The 2D case above.
inline CarriedLink carryLink(const model::DynamicsDesc& d) {
  model::SceneDescription sc;
  sc.file = "(test)";
  sc.dimension = 2;
  sc.analysis = model::Analysis::Dynamic;
  model::RigidBodyDesc hub;
  hub.name = "hub";
  hub.mass = 10.0;
  hub.inertia = kHubInertia;
  hub.fixed = {0, 1};
  hub.driven = true;
  hub.rotation = driveFunction();
  sc.rigidBodies.push_back(hub);
  model::RigidBodyDesc link;
  link.name = "link";
  link.mass = kLinkMass;
  link.inertia = 0.7;
  link.position = {kPin[0], kPin[1], 0.0};
  sc.rigidBodies.push_back(link);
  pinLinkCentreToHub(sc, {kPin[0], kPin[1], 0.0});
  const double p2 = kPin[0] * kPin[0] + kPin[1] * kPin[1], inertia = kHubInertia + kLinkMass * p2;
  const double peakTorque = inertia * kDriveAmplitude * kDriveOmega * kDriveOmega;
  const double peakForce = kLinkMass * std::sqrt(p2) * kDriveAmplitude * kDriveOmega * kDriveOmega;
  const double peakKinetic = 0.5 * inertia * std::pow(kDriveAmplitude * kDriveOmega, 2);
  auto exact = [=](const model::Model& m, double t, const std::vector<double>& q, const std::vector<double>& f) {
    const model::RigidBody &h = m.rigidBodies()[0], &l = m.rigidBodies()[1];
    const model::TimeValue psi = drive(t);
    const double c = std::cos(psi.f - drive(0.0).f), s = std::sin(psi.f - drive(0.0).f);
    const double rx = c * kPin[0] - s * kPin[1], ry = s * kPin[0] + c * kPin[1];  // R p
    const double ax = -psi.ddf * ry - psi.df * psi.df * rx, ay = psi.ddf * rx - psi.df * psi.df * ry;
    MotionErrors e;
    e.position = std::hypot(q[l.posBlock * 2] - rx, q[l.posBlock * 2 + 1] - ry);
    e.torque = std::fabs(f[h.rotBlock * 2] - inertia * psi.ddf) / peakTorque;
    e.force = std::hypot(f[h.posBlock * 2] - kLinkMass * ax, f[h.posBlock * 2 + 1] - kLinkMass * ay) / peakForce;
    return e;
  };
  return runAgainstExactMotion(sc, d, peakKinetic, exact);
}

}  // namespace strand::testing
