// Elastic catenary: a perfectly flexible cable of unstretched length L0, weight w per unstretched
// length and axial stiffness EA, hanging between two supports at the same height, span S.
// Constitutive law of Strand's cable (energy EA/2 eps^2 per reference length, Green strain
// eps = (lam^2 - 1)/2): tension T = EA eps lam. (Irvine, Cable Structures, MIT Press 1981, Ch. 1,
// derives the same equilibrium with T = EA (lam - 1); the laws differ at O(eps^2).)
// Equilibrium in the material coordinate s: horizontal force H constant, vertical force
// V(s) = w (L0/2 - s), dx/ds = lam H / T, dz/ds = -lam V / T, T = sqrt(H^2 + V^2).
// H follows from 2 x(L0/2) = S by bisection; integrals by composite 5-point Gauss.
#pragma once
#include <cmath>

namespace strand::testing {

struct ElasticCatenary {
  double H = 0.0;       // horizontal tension [N]
  double midSag = 0.0;  // depth of the mid point below the supports [m]
};

inline double catenaryStretch(double T, double EA) {
  double lam = 1.0;  // Newton on EA (lam^3 - lam) / 2 = T
  for (int it = 0; it < 50; ++it) {
    const double f = 0.5 * EA * (lam * lam * lam - lam) - T, df = 0.5 * EA * (3.0 * lam * lam - 1.0);
    const double d = f / df;
    lam -= d;
    if (std::fabs(d) < 1e-16) break;
  }
  return lam;
}

inline void catenaryHalf(double H, double L0, double w, double EA, double& x, double& z) {
  static const double gx[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
  static const double gw[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665, 0.2369268850561891};
  const int panels = 4000;
  const double h = 0.5 * L0 / panels;
  x = z = 0.0;
  for (int p = 0; p < panels; ++p)
    for (int g = 0; g < 5; ++g) {
      const double s = (p + 0.5 + 0.5 * gx[g]) * h;
      const double V = w * (0.5 * L0 - s), T = std::sqrt(H * H + V * V), lam = catenaryStretch(T, EA);
      x += 0.5 * h * gw[g] * lam * H / T;
      z += 0.5 * h * gw[g] * lam * V / T;
    }
}

inline ElasticCatenary elasticCatenary(double L0, double w, double EA, double S) {
  double lo = 1e-9 * w * L0, hi = 1e9 * w * L0;
  for (int it = 0; it < 200; ++it) {
    const double mid = std::sqrt(lo * hi);
    double x, z;
    catenaryHalf(mid, L0, w, EA, x, z);
    if (2.0 * x > S) hi = mid; else lo = mid;
  }
  ElasticCatenary c;
  c.H = std::sqrt(lo * hi);
  double x;
  catenaryHalf(c.H, L0, w, EA, x, c.midSag);
  return c;
}

}  // namespace strand::testing
