// Assumed modes of the clamped-free beam (seed 001, "AMM"): coordinates d = (axial amplitudes,
// bending amplitudes).
//   axial   phi_i(x) = sin((2i - 1) pi x / (2L)),                         i = 1..na
//   bending phi_j(x) = cosh bx - cos bx - s_j (sinh bx - sin bx),  b = beta_j / L,  j = 1..nb
// with beta_j the roots of 1 + cos(beta) cosh(beta) = 0 (1.8751, 4.6941, 7.8548, ...) and
// s_j = (cosh beta_j + cos beta_j) / (sinh beta_j + sin beta_j) (e.g. Meirovitch, Fundamentals of
// Vibrations, Sec. 8.9). The tip value of a bending mode is +-2. Evaluated in the form
// e^{bx}(1 - s)/2 + e^{-bx}(1 + s)/2 - cos bx + s sin bx, with 1 - s computed without cancellation,
// so that high modes keep their digits.
#pragma once
#include "strand/ffr/DeformationBasis.hpp"

namespace strand::ffr {

class AssumedModes : public DeformationBasis {
public:
  AssumedModes(double length, int axialModes, int bendingModes);
  int size() const override { return _na + _nb; }
  double length() const override { return _L; }
  std::string name() const override;
  void shapes(double x, ShapeRows& rows) const override;
  std::vector<QuadraturePoint> quadrature() const override;
  // beta_j L of the clamped-free beam, j = 1, 2, ... (Newton on cos(b) + 1/cosh(b) = 0)
  static double bendingRoot(int j);

private:
  double _L;
  int _na, _nb;
  std::vector<double> _beta, _s, _oneMinusS;  // per bending mode: beta_j / L, s_j, 1 - s_j
};

}  // namespace strand::ffr
