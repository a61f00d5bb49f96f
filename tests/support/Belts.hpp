// Belt scenes built in code (issue 34): a closed belt wrapped counterclockwise around two pulleys.
#pragma once
#include <petsclog.h>

#include <cmath>
#include <string>
#include <vector>

#include "strand/model/SceneDescription.hpp"
#include "support/Scenes.hpp"

namespace strand::testing {

struct BeltLoop {
  double radius = 0.5;      // both pulleys [m]
  double distance = 1.0;    // between their centres, along x [m]
  int elements = 100;
  double EA = 1e5;          // E = 1e9 Pa, A = EA / E; I = 1e-12 m^4; rho = 1000 kg/m^3
  double stretch = 1.0;     // initial_stretch (pretension)
  double stiffness = 1e7;   // contact penalty [N/m^2], 4 points per element, frictionless
};

// Pulleys "a" (at the origin) and "b" (at distance on x), fixed; the belt "belt" as a closed wrap
// around both; contact with both; x held at node 0, the middle of the lower span (a closed path
// starts there): the loop cannot slide round the pulleys at rest, and by symmetry the support takes
// no force. Static analysis (the caller sets another).
inline model::SceneDescription closedBelt(const BeltLoop& spec) {
  model::SceneDescription sc;
  sc.file = "(test)";
  sc.dimension = 2;
  Section s;
  s.E = 1e9;
  s.A = spec.EA / s.E;
  s.I = 1e-12;
  s.rho = 1000.0;
  model::BodyDesc belt = straightBody("belt", 2, spec.elements, {0, 0, 0}, {1, 0, 0}, s);
  belt.geometry.kind = model::GeometryKind::Wrap;
  belt.geometry.closed = true;
  belt.initialStretch = spec.stretch;
  model::ContactDesc c;
  c.body = belt.name;
  c.law.stiffness = spec.stiffness;
  c.points = 4;
  for (int k = 0; k < 2; ++k) {
    model::PulleyDesc p;
    p.name = k == 0 ? "a" : "b";
    p.center = {k * spec.distance, 0.0, 0.0};
    p.radius = spec.radius;
    sc.pulleys.push_back(p);
    c.pulleys.push_back(p.name);
    model::WrapTurn w;
    w.center = p.center;
    w.radius = p.radius;
    w.sense = 1;
    belt.geometry.wrap.push_back(w);
  }
  sc.bodies.push_back(belt);
  model::SupportDesc hold;
  hold.at.body = belt.name;
  hold.at.node = 0;
  hold.type = model::SupportType::Fixed;
  hold.dofs = {0};
  sc.supports.push_back(hold);
  sc.contacts.push_back(c);
  return sc;
}

// The cable's axial force at the stretch lambda: EA times its Green strain times the stretch.
inline double cableTension(double EA, double lambda) { return EA * 0.5 * (lambda * lambda - 1.0) * lambda; }

// The stretch |r'| at a node of a cable body from the coordinates q (model numbering; 2D).
inline double nodeStretch(const model::Body& b, const std::vector<double>& q, int node) {
  const int blk = b.block(node, 1);
  return std::hypot(q[2 * blk], q[2 * blk + 1]) / b.blockScale(1);
}

// The node of body b nearest (x, y) in the configuration q (absolute coordinates, model order). A
// belt's material nodes travel: the one at a span's middle changes as the belt runs.
inline int nodeNearest(const model::Body& b, const std::vector<double>& q, double x, double y) {
  int best = 0;
  double dmin = 1e300;
  for (int n = 0; n < b.elements; ++n) {  // a closed belt's last node is its first
    const int blk = b.block(n, 0);
    const double d = std::hypot(q[2 * blk] / b.blockScale(0) - x, q[2 * blk + 1] / b.blockScale(0) - y);
    if (d < dmin) dmin = d, best = n;
  }
  return best;
}

// Seconds spent so far in the contact's log event (Strand:Asm:Contact), on this rank.
inline double contactSeconds() {
  PetscLogEvent ev;
  PetscEventPerfInfo info;
  PetscCallAbort(PETSC_COMM_WORLD, PetscLogEventGetId("Strand:Asm:Contact", &ev));
  PetscCallAbort(PETSC_COMM_WORLD, PetscLogEventGetPerfInfo(0, ev, &info));
  return info.time;
}

// The two-pulley drive of Pechstein & Gerstmayr (Multibody Syst. Dyn. 30, 2013) as set up in the
// THREAD belt-drive study (issue 34): a closed belt (EA = 8000 N, EI = 4/3e-3 N m^2, rho A =
// 8.288e-3 kg/m, height 1e-4 m, reference strain -0.05) around pulleys "a" (the driver, 0 -> 12 rad/s
// over 0.05 .. 0.6 s) and "b" (J = 0.25 kg m^2, damping 2 N m s, load torque 25 (1 - cos(2 pi (t - 1)))
// / 2 N m over 1 .. 1.5 s, then 25 N m) of radius 0.09995 m (the belt's centerline at 0.1 m), 0.1 pi m
// apart; bristle friction mu = 0.5 with stiffness kt, normal penalty 1e8 N/m^2; gravity 9.81 m/s^2.
// meshes/two-pulley-drive.yaml is the same scene with kt = 1e9 (and dynamics.step_cuts: 3).
inline model::SceneDescription twoPulleyDrive(int elements, double kt = 1e8) {
  BeltLoop spec;
  spec.radius = 0.1;  // the wrap: the belt's centerline
  spec.distance = 0.1 * std::acos(-1.0);
  spec.elements = elements;
  spec.EA = 8000.0;
  spec.stretch = 1.0 / 0.95;
  spec.stiffness = 1e8;
  model::SceneDescription sc = closedBelt(spec);
  sc.analysis = model::Analysis::Dynamic;
  sc.supports.clear();  // the pulleys hold the loop
  model::BodyDesc& belt = sc.bodies[0];
  belt.section.set("I", 4.0 / 3.0 * 1e-12);                   // E = 1e9 Pa, A = 8e-6 m^2
  belt.section.set("rho", 1036.0 * 0.08 * 1e-4 / (8000.0 / 1e9));  // rho A = 1036 kg/m^3 x 0.08 m x 1e-4 m
  sc.loads.gravity = {0, -9.81, 0};
  for (model::PulleyDesc& p : sc.pulleys) p.radius = 0.1 - 5e-5;
  model::PulleyDesc& driver = sc.pulleys[0];
  driver.speed.kind = model::TimeFunction::Kind::Ramp;
  driver.speed.start = 0.05;
  driver.speed.end = 0.6;
  driver.speed.value = 12.0;
  model::PulleyDesc& driven = sc.pulleys[1];
  driven.inertia = 0.25;
  driven.damping = 2.0;
  driven.torque.kind = model::TimeFunction::Kind::CosineRamp;
  driven.torque.start = 1.0;
  driven.torque.end = 1.5;
  driven.torque.value = -25.0;
  contact::ContactLaw& law = sc.contacts[0].law;
  law.offset = 5e-5;
  law.friction = contact::FrictionLaw::Bristle;
  law.mu = 0.5;
  law.tangentialStiffness = kt;
  return sc;
}

}  // namespace strand::testing
