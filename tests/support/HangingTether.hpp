// A steel tether (r = 5 mm, 10 m, 20 ALE elements) hanging from a pinned exit with a 5 kg block
// on a joint at its other end, gravity ramped in over 1 s, generalized-alpha (rho_inf 0.5, dt 2 ms):
// the deploying tether of the payout and reel tests (tests/verification/test_ale.cpp,
// test_reel.cpp), whose material the caller sets moving.
#pragma once
#include <cmath>

#include "strand/elements/ElementRegistry.hpp"
#include "strand/model/SceneDescription.hpp"

namespace strand::testing {

inline constexpr double kL0 = 10.0, kRadius = 5e-3, kRho = 7850.0, kE = 2e11, kBlock = 5.0, kG = 9.81;

inline double rhoA() { return kRho * M_PI * kRadius * kRadius; }

// The tether with its block, gravity ramped over 1 s; the reel added by the caller. exitLast: the
// body runs from the block up to the exit (the exit is its last node).
inline model::SceneDescription hangingTether(int dim, bool exitLast = false) {
  model::SceneDescription sc;
  sc.file = "(test)";
  sc.dimension = dim;
  sc.analysis = model::Analysis::Dynamic;
  model::BodyDesc b;
  b.name = "tether";
  b.kind = elements::findKind(dim == 2 ? "AleCable2d" : "AleCable3d");
  b.elements = 20;
  b.geometry.kind = model::GeometryKind::Line;
  b.geometry.start = {0, exitLast ? -kL0 : 0.0, 0};
  b.geometry.end = {0, exitLast ? 0.0 : -kL0, 0};
  b.section.numbers = {{"E", kE}, {"A", M_PI * kRadius * kRadius}, {"I", M_PI * std::pow(kRadius, 4) / 4.0}, {"rho", kRho}};
  sc.bodies.push_back(b);
  model::SupportDesc top;
  top.at.body = "tether";
  top.at.node = exitLast ? -1 : 0;
  top.type = model::SupportType::Pinned;
  sc.supports.push_back(top);
  model::RigidBodyDesc block;
  block.name = "block";
  block.mass = kBlock;
  block.inertia = 0.01;
  block.principalInertia = {0.01, 0.01, 0.01};
  block.position = {0, -kL0, 0};
  sc.rigidBodies.push_back(block);
  model::JointDesc pin;
  pin.type = model::JointType::Pin;
  pin.a.kind = model::JointEndDesc::Kind::CableNode;
  pin.a.body = "tether";
  pin.a.node = exitLast ? 0 : -1;
  pin.b.kind = model::JointEndDesc::Kind::RigidPoint;
  pin.b.body = "block";
  sc.joints.push_back(pin);
  sc.loads.gravity = {0, -kG, 0};
  sc.loads.timed = true;
  sc.loads.function.kind = model::TimeFunction::Kind::Ramp;
  sc.loads.function.start = 0.0;
  sc.loads.function.end = 1.0;
  sc.loads.function.value = 1.0;
  sc.dynamics.integrator = model::Integrator::GeneralizedAlpha;
  sc.dynamics.rhoInf = 0.5;
  sc.dynamics.dt = 2e-3;
  return sc;
}

}  // namespace strand::testing
