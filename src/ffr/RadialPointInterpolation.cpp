#include "strand/ffr/RadialPointInterpolation.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace strand::ffr {

namespace {

// The multiquadric f(r) = (r^2 + c^2)^q and its first three derivatives in the signed distance r.
struct Multiquadric {
  double c2, q;
  void eval(double r, double f[4]) const {
    const double s = r * r + c2;
    const double p = std::pow(s, q - 3.0);  // s^{q-3}; the others follow by multiplication
    const double s1 = p * s * s, s0 = s1 * s;  // s^{q-1}, s^q
    f[0] = s0;
    f[1] = 2 * q * r * s1;
    f[2] = 2 * q * s1 + 4 * q * (q - 1) * r * r * p * s;
    f[3] = 12 * q * (q - 1) * r * p * s + 8 * q * (q - 1) * (q - 2) * r * r * r * p;
  }
};

std::string fmt(double v) {
  std::ostringstream o;
  o.precision(3);
  o << v;
  return o.str();
}

}  // namespace

RadialPointInterpolation::RadialPointInterpolation(double length, const RpimParameters& p)
    : _L(length), _dc(length / (p.nodes - 1)), _p(p) {
  if (!(p.alphaS >= 1.0))
    throw std::invalid_argument("RPIM: alpha_s = " + fmt(p.alphaS) + " < 1 leaves points with one support node");
  // One evaluation per distinct support, so that a singular moment matrix is found here, before
  // any solve. Cell supports: one per cell. Point supports change where x crosses x_i +- d_s:
  // those points and the midpoints between them.
  std::vector<double> probes{0.0, _L};
  const int cells = p.nodes - 1;
  for (int c = 0; c < cells; ++c) probes.push_back((c + 0.5) * _dc);
  if (!p.cellSupport) {
    std::vector<double> breaks{0.0, _L};
    const double ds = p.alphaS * _dc;
    for (int i = 0; i < p.nodes; ++i)
      for (double b : {i * _dc - ds, i * _dc + ds})
        if (b > 0.0 && b < _L) breaks.push_back(b);
    std::sort(breaks.begin(), breaks.end());
    for (size_t k = 0; k + 1 < breaks.size(); ++k) probes.push_back(0.5 * (breaks[k] + breaks[k + 1]));
    probes.insert(probes.end(), breaks.begin(), breaks.end());
  }
  ShapeRows rows;
  for (double x : probes) shapes(x, rows);
}

std::string RadialPointInterpolation::name() const {
  return "rpim " + std::to_string(_p.nodes) + " nodes, alpha_c " + fmt(_p.alphaC) +
         (_p.cellSupport ? "" : ", point supports");
}

std::vector<int> RadialPointInterpolation::support(double x) const {
  const double ds = _p.alphaS * _dc * (1.0 + 1e-12);
  if (_p.cellSupport) {
    const int c = std::clamp(static_cast<int>(std::floor(x / _dc)), 0, _p.nodes - 2);
    x = (c + 0.5) * _dc;
  }
  std::vector<int> s;
  for (int i = 0; i < _p.nodes; ++i)
    if (std::abs(x - i * _dc) <= ds) s.push_back(i);
  return s;
}

void RadialPointInterpolation::shapes(double x, ShapeRows& r) const {
  const int n = size();
  for (Eigen::RowVectorXd* v : {&r.axial, &r.axialSlope, &r.bending, &r.bendingSlope, &r.bendingCurvature})
    v->setZero(n);
  const std::vector<int> s = support(x);
  const int m = static_cast<int>(s.size());
  if (m < 2)
    throw std::invalid_argument("RPIM: the support of x = " + fmt(x) + " m holds " + std::to_string(m) +
                                " node(s); alpha_s = " + fmt(_p.alphaS) + " must reach at least 2 nodes");
  const Multiquadric R{std::pow(_p.alphaC * _dc, 2), _p.q};
  double f[4];
  auto check = [&](const Eigen::PartialPivLU<Eigen::MatrixXd>& lu, const char* field) {
    const double rc = lu.rcond();
    if (rc < _worstRcond) _worstRcond = rc;
    if (!(rc >= _p.minReciprocalCondition))
      throw SingularMomentMatrix("RPIM: the " + std::string(field) + " moment matrix at x = " + fmt(x) +
                                 " m is numerically singular (reciprocal condition " + fmt(rc) + " < " +
                                 fmt(_p.minReciprocalCondition) + ") with alpha_c = " + fmt(_p.alphaC) +
                                 ", q = " + fmt(_p.q) + "; seed 001 section 4 recommends alpha_c = 2 to 7");
  };
  // axial: G = [R0 P; P^T 0], rows r(x) = [R(x - x_i), 1, x]
  {
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(m + 2, m + 2);
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(m + 2, 2);
    for (int k = 0; k < m; ++k) {
      const double xk = s[k] * _dc;
      for (int i = 0; i < m; ++i) {
        R.eval(xk - s[i] * _dc, f);
        G(k, i) = f[0];
      }
      G(k, m) = G(m, k) = 1.0;
      G(k, m + 1) = G(m + 1, k) = xk;
      R.eval(x - xk, f);
      rhs(k, 0) = f[0];
      rhs(k, 1) = f[1];
    }
    rhs(m, 0) = 1.0;
    rhs(m + 1, 0) = x;
    rhs(m + 1, 1) = 1.0;
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(G);
    check(lu, "axial");
    const Eigen::MatrixXd phi = lu.solve(rhs);
    for (int k = 0; k < m; ++k) {
      if (s[k] == 0) continue;  // clamped node
      const int c = 3 * (s[k] - 1);
      r.axial[c] = phi(k, 0);
      r.axialSlope[c] = phi(k, 1);
    }
  }
  // bending, Hermite type: unknowns (a_i, b_i, c); rows: value at k, slope at k, two constraints
  {
    const int N = 2 * m + 2;
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(N, N);
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(N, 3);
    for (int k = 0; k < m; ++k) {
      const double xk = s[k] * _dc;
      for (int i = 0; i < m; ++i) {
        R.eval(xk - s[i] * _dc, f);
        G(k, i) = f[0];
        G(k, m + i) = -f[1];
        G(m + k, i) = f[1];
        G(m + k, m + i) = -f[2];
      }
      // polynomial columns and the constraint rows (symmetric)
      G(k, 2 * m) = G(2 * m, k) = 1.0;
      G(k, 2 * m + 1) = G(2 * m + 1, k) = xk;
      G(m + k, 2 * m + 1) = G(2 * m + 1, m + k) = 1.0;
      R.eval(x - xk, f);
      for (int d = 0; d < 3; ++d) {
        rhs(k, d) = f[d];
        rhs(m + k, d) = -f[d + 1];
      }
    }
    rhs(2 * m, 0) = 1.0;
    rhs(2 * m + 1, 0) = x;
    rhs(2 * m + 1, 1) = 1.0;
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(G);
    check(lu, "bending");
    const Eigen::MatrixXd phi = lu.solve(rhs);
    for (int k = 0; k < m; ++k) {
      if (s[k] == 0) continue;
      const int c = 3 * (s[k] - 1);
      for (int d = 0; d < 2; ++d) {  // deflection, rotation
        r.bending[c + 1 + d] = phi(k + d * m, 0);
        r.bendingSlope[c + 1 + d] = phi(k + d * m, 1);
        r.bendingCurvature[c + 1 + d] = phi(k + d * m, 2);
      }
    }
  }
}

std::vector<QuadraturePoint> RadialPointInterpolation::quadrature() const {
  return cellQuadrature(_L, _p.nodes - 1, _p.gaussPoints);
}

}  // namespace strand::ffr
