#include "strand/ffr/AssumedModes.hpp"

#include <cmath>

namespace strand::ffr {

double AssumedModes::bendingRoot(int j) {
  // cos(b) cosh(b) + 1 = 0  <=>  f(b) = cos(b) + 1/cosh(b) = 0; the root is near (2j - 1) pi / 2.
  double b = (2 * j - 1) * M_PI / 2 + (j == 1 ? 0.3 : 0.0);
  for (int it = 0; it < 50; ++it) {
    const double f = std::cos(b) + 1.0 / std::cosh(b);
    const double df = -std::sin(b) - std::tanh(b) / std::cosh(b);
    const double step = f / df;
    b -= step;
    if (std::abs(step) < 1e-15 * b) break;
  }
  return b;
}

AssumedModes::AssumedModes(double length, int axialModes, int bendingModes)
    : _L(length), _na(axialModes), _nb(bendingModes) {
  for (int j = 1; j <= _nb; ++j) {
    const double bl = bendingRoot(j);
    const double den = std::sinh(bl) + std::sin(bl);
    _beta.push_back(bl / _L);
    _s.push_back((std::cosh(bl) + std::cos(bl)) / den);
    // 1 - s = (sinh + sin - cosh - cos) / den = (-e^{-bl} + sin - cos) / den: no cancellation
    _oneMinusS.push_back((-std::exp(-bl) + std::sin(bl) - std::cos(bl)) / den);
  }
}

std::string AssumedModes::name() const {
  return "modes " + std::to_string(_na) + "+" + std::to_string(_nb);
}

void AssumedModes::shapes(double x, ShapeRows& r) const {
  const int n = size();
  for (Eigen::RowVectorXd* v : {&r.axial, &r.axialSlope, &r.bending, &r.bendingSlope, &r.bendingCurvature})
    v->setZero(n);
  for (int i = 0; i < _na; ++i) {
    const double k = (2 * i + 1) * M_PI / (2 * _L);
    r.axial[i] = std::sin(k * x);
    r.axialSlope[i] = k * std::cos(k * x);
  }
  for (int j = 0; j < _nb; ++j) {
    const double b = _beta[j], s = _s[j], bx = b * x;
    const double hp = 0.5 * std::exp(bx) * _oneMinusS[j], hm = 0.5 * std::exp(-bx) * (1.0 + s);
    const int c = _na + j;
    r.bending[c] = hp + hm - std::cos(bx) + s * std::sin(bx);
    r.bendingSlope[c] = b * (hp - hm + std::sin(bx) + s * std::cos(bx));
    r.bendingCurvature[c] = b * b * (hp + hm + std::cos(bx) - s * std::sin(bx));
  }
}

std::vector<QuadraturePoint> AssumedModes::quadrature() const {
  // 8 Gauss points on each of 4 cells per half-wave of the highest mode: converged to round-off.
  const int waves = std::max(_na, _nb) + 1;
  return cellQuadrature(_L, 4 * waves, 8);
}

}  // namespace strand::ffr
