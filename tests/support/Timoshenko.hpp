// Natural frequencies of a uniform Timoshenko cantilever (clamped at x = 0, free at x = L), computed
// independently of the elements (tests only). With shear k G A and rotary inertia rho I,
//   k G A (w'' - theta') + rho A omega^2 w = 0,   E I theta'' + k G A (w' - theta) + rho I omega^2 theta = 0,
// clamped: w = theta = 0; free: E I theta' = 0 and k G A (w' - theta) = 0 (Timoshenko 1921; e.g.
// Han, Benaroya & Wei, J. Sound Vib. 225 (1999)). For the state x = (w, w', theta, theta') the
// equations are x' = A(omega) x, so x(L) = exp(A L) x(0) with x(0) = (0, p, 0, q); the natural
// frequencies are the roots of the 2 x 2 determinant of the free-end conditions in (p, q), bracketed
// on a fine grid and bisected. Both spectra come out (above the cut-off sqrt(k G A / (rho I)) the
// second one).
#pragma once
#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>
#include <cmath>
#include <vector>

namespace strand::testing {

struct TimoshenkoBeam {
  double EI, kGA, rhoA, rhoI, L;

  double determinant(double omega) const {
    const double w2 = omega * omega;
    Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
    A(0, 1) = 1.0;                                   // w' = x2
    A(1, 0) = -rhoA * w2 / kGA;                      // w'' = theta' - rho A omega^2 / (k G A) w
    A(1, 3) = 1.0;
    A(2, 3) = 1.0;                                   // theta' = x4
    A(3, 1) = -kGA / EI;                             // theta'' = -(k G A (w' - theta) + rho I omega^2 theta) / E I
    A(3, 2) = (kGA - rhoI * w2) / EI;
    const Eigen::Matrix4d T = (A * L).exp();
    // free-end rows: theta'(L) = 0 and w'(L) - theta(L) = 0, for x(0) = e2 (p) and e4 (q)
    const double a = T(3, 1), b = T(3, 3), c = T(1, 1) - T(2, 1), d = T(1, 3) - T(2, 3);
    return a * d - b * c;
  }

  // The first `count` natural frequencies [rad/s] below omegaMax.
  std::vector<double> frequencies(int count, double omegaMax, int grid = 20000) const {
    std::vector<double> out;
    double w0 = omegaMax * 1e-6, f0 = determinant(w0);
    for (int i = 1; i <= grid && static_cast<int>(out.size()) < count; ++i) {
      const double w1 = omegaMax * i / grid, f1 = determinant(w1);
      if ((f0 > 0) != (f1 > 0)) {
        double a = w0, b = w1, fa = f0;
        for (int it = 0; it < 100; ++it) {
          const double m = 0.5 * (a + b), fm = determinant(m);
          if ((fm > 0) == (fa > 0)) a = m, fa = fm;
          else b = m;
        }
        out.push_back(0.5 * (a + b));
      }
      w0 = w1;
      f0 = f1;
    }
    return out;
  }
};

}  // namespace strand::testing
