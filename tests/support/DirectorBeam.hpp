// The exact large-deflection solution of the continuum model behind the 2D shear-deformable ANCF
// beams: an independent reference for their convergence (tests only).
//
// The elements interpolate r(x, y) = c(x) + y d(x); as the element size goes to zero they converge
// to the one-dimensional "director" continuum with the energy per unit length
//   W(c', d', d) = 1/2 E [A e0^2 + I (e1^2 + 2 e0 e2) + I4 e2^2] + 1/2 E A g0^2 + 2 k G (A s0^2 + I s1^2),
//   e0 = (c'.c' - 1)/2, e1 = c'.d', e2 = d'.d'/2, g0 = (d.d - 1)/2, s0 = c'.d/2, s1 = d'.d/2
// (Green-Lagrange strain of a straight reference, integrated over the rectangular section; seed
// 004 Eq. 2.13-2.18, with the decoupled elasticity of Eq. 2.18). W is written out here on its own,
// not through the element code. Its Euler-Lagrange equations for a cantilever clamped at x = 0
// (c = 0, d = e_y) with a dead force F at the tip centerline and no tip moment:
//   (dW/dc')' = 0,  (dW/dd')' = dW/dd  on (0, L);   dW/dc' = F,  dW/dd' = 0  at x = L.
// The shear and the thickness stretch make these equations stiff (boundary layers of width ~ h at
// the clamp), so they are solved by Chebyshev collocation (Trefethen, Spectral Methods in MATLAB,
// SIAM 2000, ch. 6 and 13) with Newton's method, the force ramped up in increments: spectral
// convergence in the number of points, checked by the test against a finer collocation.
#pragma once
#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <vector>

#include "strand/math/Dual.hpp"

namespace strand::testing {

struct DirectorBeam {
  double E, G, k, A, I, I4, L;

  // dW/dz at z = (c', d', d), written out (a Dual scalar gives the exact Hessian).
  template <class S>
  std::array<S, 6> gradient(const S* z) const {
    const S *c1 = z, *d1 = z + 2, *d = z + 4;
    const S e0 = 0.5 * (c1[0] * c1[0] + c1[1] * c1[1] - 1.0), e1 = c1[0] * d1[0] + c1[1] * d1[1];
    const S e2 = 0.5 * (d1[0] * d1[0] + d1[1] * d1[1]), g0 = 0.5 * (d[0] * d[0] + d[1] * d[1] - 1.0);
    const S s0 = 0.5 * (c1[0] * d[0] + c1[1] * d[1]), s1 = 0.5 * (d1[0] * d[0] + d1[1] * d[1]);
    const S We0 = E * (A * e0 + I * e2), We1 = E * I * e1, We2 = E * (I * e0 + I4 * e2);
    const S Wg0 = E * A * g0, Ws0 = 4.0 * k * G * A * s0, Ws1 = 4.0 * k * G * I * s1;
    std::array<S, 6> g;
    for (int i = 0; i < 2; ++i) {
      g[i] = We0 * c1[i] + We1 * d1[i] + 0.5 * Ws0 * d[i];                   // dW/dc'
      g[2 + i] = We1 * c1[i] + We2 * d1[i] + 0.5 * Ws1 * d[i];               // dW/dd'
      g[4 + i] = Wg0 * d[i] + 0.5 * Ws0 * c1[i] + 0.5 * Ws1 * d1[i];         // dW/dd
    }
    return g;
  }

  // Chebyshev points x_j = L (1 - cos(pi j / N)) / 2 and the differentiation matrix on them.
  static void chebyshev(int N, double L, std::vector<double>& x, Eigen::MatrixXd& Dm) {
    x.resize(N + 1);
    std::vector<double> t(N + 1), c(N + 1);
    for (int j = 0; j <= N; ++j) {
      t[j] = std::cos(M_PI * j / N);  // on [-1, 1], decreasing
      c[j] = (j == 0 || j == N ? 2.0 : 1.0) * (j % 2 ? -1.0 : 1.0);
      x[j] = 0.5 * L * (1.0 - t[j]);
    }
    Dm.setZero(N + 1, N + 1);
    for (int i = 0; i <= N; ++i)
      for (int j = 0; j <= N; ++j)
        if (i != j) Dm(i, j) = c[i] / c[j] / (t[i] - t[j]);
    for (int i = 0; i <= N; ++i) {
      double s = 0.0;
      for (int j = 0; j <= N; ++j)
        if (j != i) s += Dm(i, j);
      Dm(i, i) = -s;
    }
    Dm *= -2.0 / L;  // d/dx = -(2/L) d/dt
  }

  // The solution on N + 1 Chebyshev points: c and d at each (4 unknowns per point, point-major).
  struct Solution {
    std::vector<double> x, u;
    std::array<double, 2> tip() const { return {u[u.size() - 4], u[u.size() - 3]}; }
  };

  Eigen::VectorXd residual(const Eigen::VectorXd& u, const Eigen::MatrixXd& Dm, const double* F) const {
    const int n = static_cast<int>(Dm.rows());
    Eigen::MatrixXd fields(n, 4);  // c_x, c_y, d_x, d_y per point
    for (int j = 0; j < n; ++j)
      for (int a = 0; a < 4; ++a) fields(j, a) = u[4 * j + a];
    const Eigen::MatrixXd deriv = Dm * fields;
    Eigen::MatrixXd nm(n, 4), kk(n, 2);  // dW/dc', dW/dd' and dW/dd per point
    for (int j = 0; j < n; ++j) {
      const double z[6] = {deriv(j, 0), deriv(j, 1), deriv(j, 2), deriv(j, 3), fields(j, 2), fields(j, 3)};
      const std::array<double, 6> g = gradient(z);
      for (int a = 0; a < 4; ++a) nm(j, a) = g[a];
      kk(j, 0) = g[4];
      kk(j, 1) = g[5];
    }
    const Eigen::MatrixXd dnm = Dm * nm;
    Eigen::VectorXd r(4 * n);
    for (int j = 0; j < n; ++j) {
      r[4 * j + 0] = dnm(j, 0);
      r[4 * j + 1] = dnm(j, 1);
      r[4 * j + 2] = dnm(j, 2) - kk(j, 0);
      r[4 * j + 3] = dnm(j, 3) - kk(j, 1);
    }
    // clamp at x = 0 (j = 0) and the free end at x = L (j = n - 1), scaled like the interior rows
    const double s = E * A / L;
    r[0] = s * u[0];
    r[1] = s * u[1];
    r[2] = s * u[2];
    r[3] = s * (u[3] - 1.0);
    r[4 * (n - 1) + 0] = (nm(n - 1, 0) - F[0]) / L;
    r[4 * (n - 1) + 1] = (nm(n - 1, 1) - F[1]) / L;
    r[4 * (n - 1) + 2] = nm(n - 1, 2) / L;
    r[4 * (n - 1) + 3] = nm(n - 1, 3) / L;
    return r;
  }

  Solution cantilever(const double* F, int N = 48, int increments = 10) const {
    Solution s;
    Eigen::MatrixXd Dm;
    chebyshev(N, L, s.x, Dm);
    const int m = 4 * (N + 1);
    Eigen::VectorXd u(m);
    for (int j = 0; j <= N; ++j) {
      u[4 * j + 0] = s.x[j];
      u[4 * j + 1] = 0.0;
      u[4 * j + 2] = 0.0;
      u[4 * j + 3] = 1.0;
    }
    for (int inc = 1; inc <= increments; ++inc) {
      const double Fi[2] = {F[0] * inc / increments, F[1] * inc / increments};
      for (int it = 0; it < 30; ++it) {
        const Eigen::VectorXd r = residual(u, Dm, Fi);
        Eigen::MatrixXd J(m, m);
        for (int c = 0; c < m; ++c) {  // Jacobian by central differences (test code)
          const double h = 1e-7 * std::max(1.0, std::fabs(u[c]));
          Eigen::VectorXd up = u, um = u;
          up[c] += h;
          um[c] -= h;
          J.col(c) = (residual(up, Dm, Fi) - residual(um, Dm, Fi)) / (2.0 * h);
        }
        const Eigen::VectorXd du = J.partialPivLu().solve(r);
        u -= du;
        if (du.lpNorm<Eigen::Infinity>() < 1e-14 * L) break;
      }
    }
    s.u.assign(u.data(), u.data() + m);
    return s;
  }
};

}  // namespace strand::testing
