// The exact motion of a rigid pendulum released at an angle, for references: the complete
// elliptic integral of its half period (Landau & Lifshitz, Mechanics, Sec. 11:
// T/2 = 2 sqrt(I / (m g r)) K(sin(theta0 / 2))) and an RK4 step of its equation of motion.
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

// One classical RK4 step of h for theta'' = -c cos(theta) (theta from the horizontal; c = m g r / I
// about the pivot), on the angle theta and its rate w.
inline void pendulumRk4Step(double c, double h, double& theta, double& w) {
  auto acc = [c](double p) { return -c * std::cos(p); };
  const double k1p = w, k1w = acc(theta);
  const double k2p = w + 0.5 * h * k1w, k2w = acc(theta + 0.5 * h * k1p);
  const double k3p = w + 0.5 * h * k2w, k3w = acc(theta + 0.5 * h * k2p);
  const double k4p = w + h * k3w, k4w = acc(theta + h * k3p);
  theta += h / 6.0 * (k1p + 2 * k2p + 2 * k3p + k4p);
  w += h / 6.0 * (k1w + 2 * k2w + 2 * k3w + k4w);
}

}  // namespace strand::testing
