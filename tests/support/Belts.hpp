// Belt scenes built in code (issue 34): a closed belt wrapped counterclockwise around two pulleys.
#pragma once
#include <string>

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

}  // namespace strand::testing
