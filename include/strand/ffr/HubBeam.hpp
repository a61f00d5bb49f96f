// The hub-beam in a floating frame (seed 001 Eq. 1-10, 41-50; issue 5): a rigid hub turning by
// theta about a fixed axis, a beam clamped to it at radius a along the frame's x axis, and its
// deformation u = (w1 + c w_c, w2) in that frame, w1 = phi_a d, w2 = phi_b d (DeformationBasis.hpp),
// w_c = -1/2 int_0^x w2'^2 the foreshortening of Eq. 7 (c = 1: first-order model; c = 0: the
// zero-order, "conventional" model, which softens dynamically).
//
// Constant matrices (mu = rho A; integrals over [0, L] by the basis's quadrature):
//   M  = int mu (phi_a^T phi_a + phi_b^T phi_b)        Sx = int mu (a + x) phi_a,  Sy = int mu (a + x) phi_b
//   A  = M3^T - M3, M3 = int mu phi_a^T phi_b (skew)   K  = int EA phi_a'^T phi_a' + EI phi_b''^T phi_b''
//   Gc = int N(x) phi_b'^T phi_b',  N(x) = int_x^L mu (a + s) ds = mu (a (L - x) + (L^2 - x^2)/2)
//   J_ob = int mu (a + x)^2
// Gc is seed 001's a C + D (Eq. 46), integrated by parts: int mu (a + x) H(x) with H of Eq. 42.
// Kinetic and strain energy, keeping w_c only in the centrifugal term as seed 001 does (Eq. 44 ff.):
//   T = 1/2 J(d) w^2 + w b(d).d' + 1/2 d'^T M d',   U = 1/2 d^T K d,   w = theta'
//   J(d) = J_oh + J_ob + 2 Sx d + d^T (M - c Gc) d,  b(d) = Sy^T + A d
// Lagrange's equations (our derivation; seed 001 Eq. 45-50 with its M21 = -b):
//   J(d) theta'' + b.d'' + 2 w s(d).d'                       = tau        s(d) = Sx^T + (M - c Gc) d
//   M d''  + b theta'' + 2 w A d' - w^2 s(d) + K d           = 0
// With the hub driven, theta(t) is given and only the second line is solved (Eq. 56): linear in d.
//
// Unknowns: q = d (driven hub) or q = (theta, d) (free hub). The residual F(t, q, q', q'') and its
// exact partial derivatives are what every integrator uses (HubBeamDynamics.hpp).
#pragma once
#include <Eigen/Dense>

#include <memory>

#include "strand/ffr/DeformationBasis.hpp"
#include "strand/model/SceneDescription.hpp"

namespace strand::ffr {

struct HubBeamMatrices {
  Eigen::MatrixXd M, A, K, Gc;
  Eigen::RowVectorXd Sx, Sy;
  double Job = 0.0;
  Eigen::MatrixXd Htip;  // H(L) = int_0^L phi_b'^T phi_b': w_c(L) = -1/2 d^T H(L) d
  Eigen::RowVectorXd tipAxial, tipBending, tipBendingSlope;  // phi_a(L), phi_b(L), phi_b'(L)
};

HubBeamMatrices integrateMatrices(const DeformationBasis& basis, const model::HubBeamDesc& beam);

// The basis a scene asks for (throws SingularMomentMatrix for an RPIM shape parameter too large).
std::unique_ptr<DeformationBasis> makeBasis(const model::HubBeamDesc& desc);

class HubBeam {
public:
  explicit HubBeam(const model::HubBeamDesc& desc);
  const model::HubBeamDesc& desc() const { return _desc; }
  const DeformationBasis& basis() const { return *_basis; }
  const HubBeamMatrices& matrices() const { return _m; }
  bool driven() const { return _desc.driven; }
  int deformationSize() const { return _n; }
  // number of unknowns: n (driven) or n + 1 (free: theta first)
  int size() const { return _desc.driven ? _n : _n + 1; }
  // the hub's angle, rate and acceleration at t (driven hub)
  model::TimeValue hubMotion(double t) const { return _desc.angle.at(t); }
  // omega_1 = (beta_1 / L)^2 sqrt(EI / (rho A)) of the non-rotating clamped-free beam (3.80 rad/s
  // for seed 001's beam): above it the zero-order model softens
  double firstBendingFrequency() const;
  // the highest natural frequency of the discretized beam on a hub at rest, sqrt(max eig(K, M)):
  // what limits an explicit step (RK4: h omega_max <= 2.8)
  double highestFrequency() const;

  // F(t, q, v, a), v = q', a = q''.
  void residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a,
                Eigen::VectorXd& F) const;
  // J = dF/dq + shiftV dF/dv + shiftA dF/da.
  void jacobian(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a,
                double shiftV, double shiftA, Eigen::MatrixXd& J) const;
  // The generalized mass dF/da (depends on d for a free hub) and the rest, F = mass a - force.
  void mass(const Eigen::VectorXd& q, Eigen::MatrixXd& Mq) const;
  void force(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, Eigen::VectorXd& Q) const;

  // Outputs of a state. Deformation of the tip in the floating frame: u_x = w1 + c w_c, u_y = w2.
  struct Observation {
    double theta = 0.0, omega = 0.0;   // hub angle and rate
    double tipUx = 0.0, tipUy = 0.0, tipVy = 0.0;  // tip deformation [m], d/dt u_y [m/s]
    double kinetic = 0.0, strain = 0.0;
    double hubTorque = 0.0;            // tau: applied (free hub) or needed to drive the hub (driven)
    double angularMomentum = 0.0;      // about the axis: dT/dtheta' = J(d) w + b.d'
  };
  Observation observe(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a) const;

private:
  // the hub's angle, rate and acceleration: prescribed, or the first entries of q, v, a
  void hub(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a, double* theta,
           double* omega, double* alpha) const;
  // s(d) = Sx^T + (M - c Gc) d (= dJ/dd / 2), b(d) = Sy^T + A d, J(d) = J_oh + J_ob + 2 Sx d + d^T (M - c Gc) d
  Eigen::VectorXd centrifugal(const Eigen::Ref<const Eigen::VectorXd>& d) const;
  Eigen::VectorXd coupling(const Eigen::Ref<const Eigen::VectorXd>& d) const;
  double hubInertiaWith(const Eigen::Ref<const Eigen::VectorXd>& d) const;
  model::HubBeamDesc _desc;
  std::unique_ptr<DeformationBasis> _basis;
  HubBeamMatrices _m;
  Eigen::MatrixXd _Ms;  // M - c Gc
  double _c;            // 1 first order, 0 zero order
  int _n;
};

}  // namespace strand::ffr
