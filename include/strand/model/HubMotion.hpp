// Prescribed rigid rotation of supported node coordinates (a clamp on a turning hub, design
// section 3: a rheonomic constraint, eliminated). For the rotation R(psi) by the angle psi(t) about
// the unit axis e through the center c, a position block follows r(t) = c + R(psi) (r0 - c) and a
// slope block r'(t) = R(psi) r0'. With w = R(psi) w0 (w0 = r0 - c or r0'):
//   dw/dt = psi' e x w,   d2w/dt2 = psi'' e x w + psi'^2 e x (e x w).
// r0 is the scene's geometry, the one at t = 0: the rotation is by psi(t) - psi(0) (a drive such as
// a sine with a phase may start at psi(0) != 0).
#pragma once
#include <vector>

#include "strand/model/SceneDescription.hpp"

namespace strand::model {

struct HubMotion {
  Vec3 center{}, axis{0.0, 0.0, 1.0};
  TimeFunction angle;
  // the moved blocks (model numbering) and whether each is a slope block
  std::vector<int> blocks;
  std::vector<char> slope;

  // Displacement u = q(t) - q0, velocity and acceleration of block k (index into `blocks`) with
  // reference coordinates q0 (dim entries); dim = 2 rotates in the xy plane.
  void state(int k, const double* q0, int dim, double t, double* u, double* v, double* a) const;
  // A vector w0 of the scene's geometry turned with the hub: w = R(psi(t) - psi(0)) w0 and its rate
  // dw/dt (null: not wanted); state() applies it to each moved block, io::Probes to the hub's axes.
  Vec3 turn(const Vec3& w0, double t, Vec3* rate = nullptr) const;
};

}  // namespace strand::model
