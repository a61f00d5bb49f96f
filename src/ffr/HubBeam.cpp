#include "strand/ffr/HubBeam.hpp"

#include "strand/ffr/AssumedModes.hpp"
#include "strand/ffr/HermiteFem.hpp"
#include "strand/ffr/RadialPointInterpolation.hpp"

namespace strand::ffr {

HubBeamMatrices integrateMatrices(const DeformationBasis& basis, const model::HubBeamDesc& b) {
  const int n = basis.size();
  const double mu = b.rho * b.A, EA = b.E * b.A, EI = b.E * b.I, L = basis.length(), a = b.hubRadius;
  HubBeamMatrices m;
  Eigen::MatrixXd M3 = Eigen::MatrixXd::Zero(n, n);
  m.M = m.K = m.Gc = m.Htip = Eigen::MatrixXd::Zero(n, n);
  m.Sx = m.Sy = Eigen::RowVectorXd::Zero(n);
  ShapeRows r;
  for (const QuadraturePoint& qp : basis.quadrature()) {
    basis.shapes(qp.x, r);
    const double w = qp.weight, x = qp.x;
    const double N = mu * (a * (L - x) + 0.5 * (L * L - x * x));  // centrifugal tension per Omega^2
    m.M.noalias() += (w * mu) * (r.axial.transpose() * r.axial + r.bending.transpose() * r.bending);
    M3.noalias() += (w * mu) * r.axial.transpose() * r.bending;
    m.K.noalias() += w * (EA * r.axialSlope.transpose() * r.axialSlope +
                          EI * r.bendingCurvature.transpose() * r.bendingCurvature);
    m.Gc.noalias() += (w * N) * r.bendingSlope.transpose() * r.bendingSlope;
    m.Htip.noalias() += w * r.bendingSlope.transpose() * r.bendingSlope;
    m.Sx += (w * mu * (a + x)) * r.axial;
    m.Sy += (w * mu * (a + x)) * r.bending;
  }
  m.A = M3.transpose() - M3;
  m.Job = mu * (std::pow(a + L, 3) - std::pow(a, 3)) / 3.0;
  basis.shapes(L, r);
  m.tipAxial = r.axial;
  m.tipBending = r.bending;
  m.tipBendingSlope = r.bendingSlope;
  return m;
}

std::unique_ptr<DeformationBasis> makeBasis(const model::HubBeamDesc& d) {
  switch (d.method) {
    case model::HubBeamMethod::AssumedModes: return std::make_unique<AssumedModes>(d.length, d.axialModes, d.bendingModes);
    case model::HubBeamMethod::Fem: return std::make_unique<HermiteFem>(d.length, d.elements);
    case model::HubBeamMethod::Rpim:
      return std::make_unique<RadialPointInterpolation>(
          d.length, RpimParameters{d.nodes, d.alphaC, d.q, d.alphaS, d.gaussPoints, d.cellSupport});
  }
  return nullptr;
}

HubBeam::HubBeam(const model::HubBeamDesc& desc)
    : _desc(desc), _basis(makeBasis(desc)), _m(integrateMatrices(*_basis, desc)),
      _c(desc.coupling == model::HubBeamCoupling::FirstOrder ? 1.0 : 0.0), _n(_basis->size()) {
  _Ms = _m.M - _c * _m.Gc;
}

double HubBeam::firstBendingFrequency() const {
  const double beta = AssumedModes::bendingRoot(1) / _desc.length;
  return beta * beta * std::sqrt(_desc.E * _desc.I / (_desc.rho * _desc.A));
}

double HubBeam::highestFrequency() const {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(_m.K, _m.M, Eigen::EigenvaluesOnly);
  return std::sqrt(es.eigenvalues().maxCoeff());
}

Eigen::VectorXd HubBeam::centrifugal(const Eigen::Ref<const Eigen::VectorXd>& d) const {
  return _m.Sx.transpose() + _Ms * d;
}

Eigen::VectorXd HubBeam::coupling(const Eigen::Ref<const Eigen::VectorXd>& d) const {
  return _m.Sy.transpose() + _m.A * d;
}

double HubBeam::hubInertiaWith(const Eigen::Ref<const Eigen::VectorXd>& d) const {
  return _desc.hubInertia + _m.Job + 2 * _m.Sx.dot(d) + d.dot(_Ms * d);
}

void HubBeam::hub(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a,
                  double* theta, double* omega, double* alpha) const {
  if (_desc.driven) {
    const model::TimeValue h = _desc.angle.at(t);
    *theta = h.f, *omega = h.df, *alpha = h.ddf;
  } else {
    *theta = q[0], *omega = v[0], *alpha = a.size() ? a[0] : 0.0;
  }
}

void HubBeam::residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a,
                       Eigen::VectorXd& F) const {
  double th, w, al;
  hub(t, q, v, a, &th, &w, &al);
  const auto d = q.tail(_n), dv = v.tail(_n), da = a.tail(_n);
  const Eigen::VectorXd s = centrifugal(d);
  const Eigen::VectorXd b = coupling(d);
  F.resize(size());
  F.tail(_n) = _m.M * da + al * b + (2 * w) * (_m.A * dv) - (w * w) * s + _m.K * d;
  if (!_desc.driven) {
    const double J = hubInertiaWith(d);
    F[0] = J * al + b.dot(da) + 2 * w * s.dot(dv) - _desc.torque.at(t).f;
  }
}

void HubBeam::jacobian(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a,
                       double shiftV, double shiftA, Eigen::MatrixXd& Jm) const {
  double th, w, al;
  hub(t, q, v, a, &th, &w, &al);
  const auto d = q.tail(_n), dv = v.tail(_n), da = a.tail(_n);
  Jm.resize(size(), size());
  const int o = _desc.driven ? 0 : 1;
  Jm.block(o, o, _n, _n) = al * _m.A - (w * w) * _Ms + _m.K + (2 * w * shiftV) * _m.A + shiftA * _m.M;
  if (!_desc.driven) {
    const Eigen::VectorXd s = centrifugal(d);
    const Eigen::VectorXd b = coupling(d);
    const double J = hubInertiaWith(d);
    Jm(0, 0) = shiftV * 2 * s.dot(dv) + shiftA * J;
    // dF_theta/dd: alpha dJ/dd + d(b.da)/dd + 2 w d(s.dv)/dd, with d(b.da)/dd = A^T da = -A da
    Jm.block(0, 1, 1, _n) = (2 * al * s - _m.A * da + (2 * w) * (_Ms * dv) + shiftV * 2 * w * s + shiftA * b).transpose();
    Jm.block(1, 0, _n, 1) = shiftV * (2 * (_m.A * dv) - (2 * w) * s) + shiftA * b;
  }
}

void HubBeam::mass(const Eigen::VectorXd& q, Eigen::MatrixXd& Mq) const {
  Mq.resize(size(), size());
  const int o = _desc.driven ? 0 : 1;
  Mq.block(o, o, _n, _n) = _m.M;
  if (!_desc.driven) {
    const auto d = q.tail(_n);
    const Eigen::VectorXd b = coupling(d);
    Mq(0, 0) = hubInertiaWith(d);
    Mq.block(0, 1, 1, _n) = b.transpose();
    Mq.block(1, 0, _n, 1) = b;
  }
}

void HubBeam::force(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, Eigen::VectorXd& Q) const {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(size());
  residual(t, q, v, zero, Q);
  Q = -Q;  // driven: contains -alpha b, the load of the hub's given acceleration
}

HubBeam::Observation HubBeam::observe(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                      const Eigen::VectorXd& a) const {
  Observation o;
  double al;
  hub(t, q, v, a, &o.theta, &o.omega, &al);
  const auto d = q.tail(_n), dv = v.tail(_n), da = a.tail(_n);
  const Eigen::VectorXd s = centrifugal(d);
  const Eigen::VectorXd b = coupling(d);
  const double J = hubInertiaWith(d);
  o.tipUx = _m.tipAxial.dot(d) - 0.5 * _c * d.dot(_m.Htip * d);
  o.tipUy = _m.tipBending.dot(d);
  o.tipVy = _m.tipBending.dot(dv);
  const double w = o.omega;
  o.kinetic = 0.5 * J * w * w + w * b.dot(dv) + 0.5 * dv.dot(_m.M * dv);
  o.strain = 0.5 * d.dot(_m.K * d);
  o.hubTorque = _desc.driven ? J * al + b.dot(da) + 2 * w * s.dot(dv) : _desc.torque.at(t).f;
  o.angularMomentum = J * w + b.dot(dv);
  return o;
}

}  // namespace strand::ffr
