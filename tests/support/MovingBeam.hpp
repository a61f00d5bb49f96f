// Free vibration of an axially moving, pinned-pinned Euler-Bernoulli beam, computed independently
// of the elements (tests only): seed 000 Eq. 54 (Wickert & Mote, J. Appl. Mech. 57 (1990)),
//   rho w_tt + 2 rho v w_xt + EI w_xxxx - (T - rho v^2) w_xx = 0,   w = w_xx = 0 at x = 0, l,
// with rho the mass per length, T the tension and v the transport speed. Galerkin on the sine
// series w = sum_{n=1}^{K} a_n(t) sin(n pi x / l) (complete for these ends) gives
//   (rho l / 2) a'' + G a' + K a = 0,   K_nn = (l/2) (EI (n pi/l)^4 + (T - rho v^2)(n pi/l)^2),
//   G_mn = 2 rho v m n (1 - (-1)^(m+n)) / (m^2 - n^2) (m != n; skew-symmetric),
// solved as a first-order eigenproblem; the frequencies converge with K (K = 40: 1e-8 relative).
// An eigenpair (i omega, a) gives the real motion w = Re(sum a_n sin(n pi x/l) e^{i omega t}).
#pragma once
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

namespace strand::testing {

struct MovingBeam {
  double rho, EI, T, v, l;

  struct Mode {
    double omega;
    std::vector<std::complex<double>> a;  // series coefficients, scaled so max |w| ~ 1
    // w, w_x, w_t, w_xt at x and t = 0
    void state(double x, double l, double* w, double* wx, double* wt, double* wxt) const {
      std::complex<double> s(0), sx(0);
      for (size_t n = 0; n < a.size(); ++n) {
        const double k = (n + 1) * M_PI / l;
        s += a[n] * std::sin(k * x);
        sx += a[n] * k * std::cos(k * x);
      }
      const std::complex<double> io(0.0, omega);
      *w = s.real();
      *wx = sx.real();
      *wt = (io * s).real();
      *wxt = (io * sx).real();
    }
  };

  // The lowest `count` modes with K sine terms.
  std::vector<Mode> modes(int K, int count) const {
    using namespace Eigen;
    MatrixXd Minv = MatrixXd::Identity(K, K) * (2.0 / (rho * l)), Kd = MatrixXd::Zero(K, K), G = MatrixXd::Zero(K, K);
    for (int m = 1; m <= K; ++m) {
      const double k = m * M_PI / l;
      Kd(m - 1, m - 1) = 0.5 * l * (EI * std::pow(k, 4) + (T - rho * v * v) * k * k);
      for (int n = 1; n <= K; ++n)
        if (m != n) G(m - 1, n - 1) = 2.0 * rho * v * m * n * (1.0 - std::pow(-1.0, m + n)) / double(m * m - n * n);
    }
    MatrixXd S = MatrixXd::Zero(2 * K, 2 * K);
    S.topRightCorner(K, K) = MatrixXd::Identity(K, K);
    S.bottomLeftCorner(K, K) = -Minv * Kd;
    S.bottomRightCorner(K, K) = -Minv * G;
    EigenSolver<MatrixXd> es(S);
    std::vector<Mode> out;
    for (int j = 0; j < 2 * K; ++j) {
      const std::complex<double> lam = es.eigenvalues()[j];
      if (lam.imag() <= 0.0) continue;  // one of each conjugate pair
      Mode md;
      md.omega = lam.imag();
      double big = 0.0;
      for (int n = 0; n < K; ++n) big = std::max(big, std::abs(es.eigenvectors()(n, j)));
      for (int n = 0; n < K; ++n) md.a.push_back(es.eigenvectors()(n, j) / big);
      out.push_back(md);
    }
    std::sort(out.begin(), out.end(), [](const Mode& x, const Mode& y) { return x.omega < y.omega; });
    if (static_cast<int>(out.size()) > count) out.resize(count);
    return out;
  }
};

}  // namespace strand::testing
