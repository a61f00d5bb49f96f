// Complete elliptic integral of the first kind, for the exact half period of a pendulum released
// at an angle (Landau & Lifshitz, Mechanics, Sec. 11): T/2 = 2 sqrt(I / (m g r)) K(sin(theta0 / 2)).
#pragma once
#include <cmath>

namespace strand::testing {

// K(k) = pi / (2 AGM(1, sqrt(1 - k^2))) (arithmetic-geometric mean; 30 iterations reach round-off).
inline double ellipticK(double k) {
  double a = 1.0, b = std::sqrt(1.0 - k * k);
  for (int i = 0; i < 30; ++i) {
    const double an = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = an;
  }
  return M_PI / (2.0 * a);
}

}  // namespace strand::testing
