// Lagrange interpolation on arbitrary nodes, for BDF on a non-uniform history (solvers/StrandBdf,
// ffr/HubBeamDense): the derivative of the basis at the first node (the BDF coefficients) and its
// values at a point (the predictor's extrapolation).
#pragma once
#include <vector>

namespace strand::math {

// l_j'(T0) of the basis on the nodes T: l_0'(T0) = sum_{i>0} 1/(T0 - Ti),
// l_j'(T0) = prod_{i != 0, j} (T0 - Ti) / prod_{i != j} (Tj - Ti).
inline std::vector<double> lagrangeDerivativeAtFirst(const std::vector<double>& T) {
  const size_t m = T.size();
  std::vector<double> c(m, 0.0);
  for (size_t i = 1; i < m; ++i) c[0] += 1.0 / (T[0] - T[i]);
  for (size_t j = 1; j < m; ++j) {
    double num = 1.0, den = 1.0;
    for (size_t i = 0; i < m; ++i) {
      if (i == j) continue;
      if (i != 0) num *= T[0] - T[i];
      den *= T[j] - T[i];
    }
    c[j] = num / den;
  }
  return c;
}

// l_j(t) of the basis on the nodes T.
inline std::vector<double> lagrangeValues(const std::vector<double>& T, double t) {
  std::vector<double> c(T.size(), 1.0);
  for (size_t j = 0; j < T.size(); ++j)
    for (size_t i = 0; i < T.size(); ++i)
      if (i != j) c[j] *= (t - T[i]) / (T[j] - T[i]);
  return c;
}

}  // namespace strand::math
