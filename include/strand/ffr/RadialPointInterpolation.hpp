// Meshfree radial point interpolation (RPIM) of the beam's deformation (seed 001 Eq. 11-37, after
// Wang & Liu, Int. J. Numer. Meth. Eng. 54 (2002) 1623; Liu & Gu, An Introduction to Meshfree
// Methods, 2005). `nodes` field nodes evenly spaced on [0, L] (node 0 clamped), spacing d_c.
// At a point x the support is every node within d_s = alpha_s d_c (Eq. 21); with the multiquadric
//   R(r) = (r^2 + (alpha_c d_c)^2)^q                                              (Eq. 14)
// and the linear polynomial p = [1, x] (Eq. 15, m = 2):
//  - axial w1: u(x) = sum R(x - x_i) a_i + p(x) b with u(x_k) = u_k on the support and
//    P^T a = 0 (Eq. 22-36): the symmetric moment matrix G = [R0 P; P^T 0] (Eq. 32);
//  - bending w2, whose nodes carry the deflection and the rotation (seed 001 Eq. 40, "phi_y, phi_theta"):
//    Hermite-type RPIM, w(x) = sum R(x - x_i) a_i - sum R'(x - x_i) b_i + p(x) c, with w and w'
//    interpolated at every support node and the constraints sum p(x_i) a_i + p'(x_i) b_i = 0; its
//    moment matrix is symmetric too.
// The shape functions are phi(x) = G^{-1} r(x) (Eq. 34; r(x) the basis row) and their derivatives
// G^{-1} r'(x), G^{-1} r''(x). They have the Kronecker property (Eq. 37), so the clamp removes node
// 0's coordinates. Integration: Gauss points on the background cells between nodes (Eq. 51-52).
//
// A large alpha_c makes R nearly a constant plus a parabola over the support and G numerically
// singular (seed 001 section 4: alpha_c > 7 fails). The constructor estimates the reciprocal
// condition number of every moment matrix the basis can meet (one per distinct support) and
// throws SingularMomentMatrix when one falls below RpimParameters::minReciprocalCondition (1e-12:
// the shape functions would have lost more than 4 of 16 digits).
#pragma once
#include <stdexcept>

#include "strand/ffr/DeformationBasis.hpp"

namespace strand::ffr {

struct RpimParameters {
  int nodes = 11;
  double alphaC = 3.0, q = 1.03, alphaS = 2.5;
  int gaussPoints = 4;
  bool cellSupport = true;  // false: point supports (seed 001)
  double minReciprocalCondition = 1e-12;  // below it a moment matrix is refused (0: never)
};

class SingularMomentMatrix : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

class RadialPointInterpolation : public DeformationBasis {
public:
  RadialPointInterpolation(double length, const RpimParameters& p);
  int size() const override { return 3 * (_p.nodes - 1); }
  double length() const override { return _L; }
  std::string name() const override;
  void shapes(double x, ShapeRows& rows) const override;
  std::vector<QuadraturePoint> quadrature() const override;
  // Smallest reciprocal condition number (LU estimate) of the moment matrices met so far.
  double worstReciprocalCondition() const { return _worstRcond; }

private:
  std::vector<int> support(double x) const;
  double _L, _dc;
  RpimParameters _p;
  mutable double _worstRcond = 1.0;
};

}  // namespace strand::ffr
