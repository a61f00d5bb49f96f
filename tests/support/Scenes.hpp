// Scenes built in code for tests: same structures the YAML reader fills.
#pragma once
#include <petscvec.h>

#include <cmath>
#include <string>
#include <vector>

#include "strand/elements/ElementRegistry.hpp"
#include "strand/model/SceneDescription.hpp"
#include "strand/solvers/Problem.hpp"
#include "strand/solvers/StaticSolver.hpp"

namespace strand::testing {

struct Section {
  double E = 2.1e11, A = 1e-4, I = 1e-8, rho = 7850.0;  // steel-like, EA/EI = 1e4 m^-2
};

inline model::BodyDesc straightBody(const std::string& name, int dim, int elements, model::Vec3 start,
                                    model::Vec3 end, const Section& s = {}) {
  model::BodyDesc b;
  b.name = name;
  b.kind = elements::findKind(dim == 2 ? "AncfCable2d" : "AncfCable3d");
  b.elements = elements;
  b.geometry.kind = model::GeometryKind::Line;
  b.geometry.start = start;
  b.geometry.end = end;
  b.section.set("E", s.E);
  b.section.set("A", s.A);
  b.section.set("I", s.I);
  b.section.set("rho", s.rho);
  return b;
}

// Cantilever along +x from the origin, clamped at node 0.
inline model::SceneDescription cantilever(int dim, int elements, double length = 1.0, const Section& s = {}) {
  model::SceneDescription sc;
  sc.file = "(test)";
  sc.dimension = dim;
  sc.bodies.push_back(straightBody("beam", dim, elements, {0, 0, 0}, {length, 0, 0}, s));
  model::SupportDesc clamp;
  clamp.at.body = "beam";
  clamp.at.node = 0;
  clamp.type = model::SupportType::Clamped;
  sc.supports.push_back(clamp);
  return sc;
}

// A steel cable cantilever of solid round section (diameter d; E, rho: Section's steel) under
// gravity along -z, dynamic, released from the straight shape (3D, AncfCable3d). The benchmark of
// issue 3 (L = 1 m, d = 10 mm): bench_cantilever_dynamics and test_dynamics.
inline model::SceneDescription steelCantileverUnderGravity(int elements, double length = 1.0, double d = 0.01) {
  Section s;
  s.A = M_PI * d * d / 4.0;
  s.I = M_PI * d * d * d * d / 64.0;
  model::SceneDescription sc = cantilever(3, elements, length, s);
  sc.analysis = model::Analysis::Dynamic;
  sc.loads.gravity = {0, 0, -9.81};
  return sc;
}

// The spinning beam of seed 001 (section 4.1): L = 10 m, A = 4e-4 m^2, I = 2e-7 m^4,
// rho = 3000 kg/m^3, 2D cables clamped at the origin. With omega0 > 0 the clamp turns with a hub
// whose angle follows the spin-up profile of seed 001 Eq. 57 (Omega0 = omega0, T = duration).
inline model::SceneDescription seed001Beam(double E, int elements, double omega0 = 0.0, double duration = 15.0) {
  Section s;
  s.E = E;
  s.A = 4e-4;
  s.I = 2e-7;
  s.rho = 3000.0;
  model::SceneDescription sc = cantilever(2, elements, 10.0, s);
  if (omega0 > 0.0) {
    sc.analysis = model::Analysis::Dynamic;
    model::HubDesc& hub = sc.supports[0].hub;
    hub.present = true;
    hub.angle.kind = model::TimeFunction::Kind::SpinUp;
    hub.angle.omega = omega0;
    hub.angle.duration = duration;
  }
  return sc;
}

// A planar chain of `links` uniform rigid rods (length l, mass m each, J = m l^2 / 12) lying
// along +x from the origin, pinned to the ground at the origin and to each other end to end;
// gravity -9.81 y. One link is the compound pendulum.
inline model::SceneDescription rigidChain(int links, double l, double m) {
  model::SceneDescription sc;
  sc.file = "(test)";
  sc.dimension = 2;
  sc.analysis = model::Analysis::Dynamic;
  sc.loads.gravity = {0, -9.81, 0};
  for (int k = 0; k < links; ++k) {
    model::RigidBodyDesc r;
    r.name = "link" + std::to_string(k);
    r.mass = m;
    r.inertia = m * l * l / 12.0;
    r.position = {(k + 0.5) * l, 0, 0};
    sc.rigidBodies.push_back(r);
    model::JointDesc j;
    j.type = model::JointType::Pin;
    j.a.kind = model::JointEndDesc::Kind::RigidPoint;
    j.a.body = r.name;
    j.a.point = {-0.5 * l, 0, 0};
    if (k == 0) {
      j.b.kind = model::JointEndDesc::Kind::Ground;
    } else {
      j.b.kind = model::JointEndDesc::Kind::RigidPoint;
      j.b.body = "link" + std::to_string(k - 1);
      j.b.point = {0.5 * l, 0, 0};
    }
    sc.joints.push_back(j);
  }
  return sc;
}

// A 3D damped cable (1 m along x, 4 elements, modulus E) pinned to the ground at node 0 with a
// nodal moment at node 2, its tip clamped (position and slope direction) to a 3D rigid body "box"
// carrying a torque, and a second, turned body "arm" pinned to the first; gravity -9.81 z. Every 3D
// multibody term: natural-coordinate frames and their six orthonormality equations, body points
// and directions, the torque's 1/2 tau x a_k, the moment's slope-following force.
inline model::SceneDescription cableWithTwoBodies3d(double E) {
  Section s;
  s.E = E;
  model::SceneDescription sc = cantilever(3, 4, 1.0, s);
  sc.supports.clear();
  sc.analysis = model::Analysis::Dynamic;
  sc.loads.gravity = {0, 0, -9.81};
  sc.bodies[0].section.set("damping_axial", 2e-3);
  sc.bodies[0].section.set("damping_bending", 2e-3);
  model::NodalLoadDesc moment;
  moment.at.body = "beam";
  moment.at.node = 2;
  moment.moment = {0.1, 0.2, 0.3};
  sc.loads.nodal.push_back(moment);
  model::RigidBodyDesc box, arm;
  box.name = "box";
  box.mass = 0.5;
  box.principalInertia = {2e-3, 3e-3, 4e-3};
  box.position = {1.1, 0, 0};
  box.torque = {0.3, -0.2, 0.5};
  arm.name = "arm";
  arm.mass = 0.2;
  arm.principalInertia = {1e-3, 1.5e-3, 2e-3};
  arm.position = {1.3, 0, 0};
  arm.axis = {0.2, 0.3, 1.0};
  arm.angle = 0.4;
  sc.rigidBodies = {box, arm};
  model::JointDesc root, tip, hinge;
  root.a.kind = model::JointEndDesc::Kind::CableNode;
  root.a.body = "beam";
  root.a.node = 0;
  root.b.kind = model::JointEndDesc::Kind::Ground;
  tip.type = model::JointType::Clamp;
  tip.a = root.a;
  tip.a.node = -1;
  tip.b.kind = model::JointEndDesc::Kind::RigidPoint;
  tip.b.body = "box";
  tip.b.point = {-0.1, 0, 0};
  hinge.a.kind = hinge.b.kind = model::JointEndDesc::Kind::RigidPoint;
  hinge.a.body = "box";
  hinge.a.point = {0.1, 0, 0};
  hinge.b.body = "arm";
  {  // the arm's body-frame point at (1.2, 0, 0): R^T (-0.1, 0, 0), R the arm's initial turn
    const double n = std::sqrt(0.2 * 0.2 + 0.3 * 0.3 + 1.0), e[3] = {0.2 / n, 0.3 / n, 1.0 / n};
    const double c = std::cos(0.4), sn = std::sin(0.4);
    // row 0 of R is R^T's column 0: R_00, R_01, R_02 -> (R^T x)_j = R_0j x_0
    const double R0[3] = {c + (1 - c) * e[0] * e[0], (1 - c) * e[0] * e[1] - sn * e[2], (1 - c) * e[0] * e[2] + sn * e[1]};
    for (int j = 0; j < 3; ++j) hinge.b.point[j] = -0.1 * R0[j];
  }
  sc.joints = {root, tip, hinge};
  return sc;
}

// Pins both end nodes of the named body (a span between two fixed points).
inline void pinEnds(model::SceneDescription& sc, const std::string& body) {
  for (long node : {0L, -1L}) {
    model::SupportDesc p;
    p.at.body = body;
    p.at.node = node;
    p.type = model::SupportType::Pinned;
    sc.supports.push_back(p);
  }
}

inline void addTipLoad(model::SceneDescription& sc, model::Vec3 force, model::Vec3 moment = {0, 0, 0}) {
  model::NodalLoadDesc l;
  l.at.body = sc.bodies[0].name;
  l.at.node = -1;
  l.force = force;
  l.moment = moment;
  sc.loads.nodal.push_back(l);
}

// Static solve on `comm`; returns the full coordinate vector q = q0 + u in model numbering (on
// every rank of comm); *failure receives the solver's failure text (empty on success).
inline std::vector<double> solveStatic(solvers::Problem& p, int loadSteps, std::string* failure = nullptr) {
  MPI_Comm comm = p.dofs().comm();
  Vec X;
  PetscCallAbort(comm, p.dofs().createVector(&X));
  PetscCallAbort(comm, p.assembler().initialState(X));
  std::string why;
  {
    solvers::StaticSolver solver(p.assembler(), loadSteps);
    PetscCallAbort(comm, solver.setFromOptions());
    PetscCallAbort(comm, solver.solve(X, nullptr, &why));
  }
  if (failure) *failure = why;
  std::vector<double> q;
  PetscCallAbort(comm, p.assembler().gatherToRoot(X, q));
  const int n = static_cast<int>(p.model().numDofs());
  q.resize(n);
  MPI_Bcast(q.data(), n, MPI_DOUBLE, 0, comm);
  VecDestroy(&X);
  return q;
}

// Position of node `node` (-1: last) of body `b`.
inline model::Vec3 nodePosition(const solvers::Problem& p, const std::vector<double>& q, int b, int node) {
  const model::Body& body = p.model().bodies()[b];
  const int n = node < 0 ? body.elements : node;
  const int d = p.model().dim();
  model::Vec3 r{0, 0, 0};
  for (int i = 0; i < d; ++i) r[i] = q[body.posBlock[n] * d + i];
  return r;
}

}  // namespace strand::testing
