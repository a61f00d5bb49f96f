// Exact large-deflection references for an inextensible, unshearable cantilever (Euler elastica):
// length L = 1, clamped at the origin with its tangent along +x, bending stiffness EI.
// Results are in units of L; `angle` is the signed angle of the tip tangent from +x
// (counter-clockwise positive), so a downward tip force gives y < 0 and angle < 0.
// Header-only, no PETSc: used by unit and verification tests as an independent reference.
#pragma once
#include <algorithm>
#include <cmath>

namespace strand::testing {

struct ElasticaTip {
  double x, y, angle;
};

namespace elastica_detail {

// Carlson's symmetric elliptic integrals by duplication (B. C. Carlson, "Numerical computation of
// real or complex elliptic integrals", Numer. Algorithms 10 (1995) 13-26; DLMF 19.36.1-2).
// The truncated series after the loop leaves a relative error of order tol^6 ~ 1e-18.
// RF(x, y, z) = 1/2 int_0^inf dt / sqrt((t + x)(t + y)(t + z)); x, y, z >= 0, at most one zero.
inline double carlsonRF(double x, double y, double z) {
  constexpr double tol = 1e-3;
  double a = (x + y + z) / 3.0;
  for (int it = 0; it < 100; ++it) {
    if (std::max({std::abs(a - x), std::abs(a - y), std::abs(a - z)}) <= tol * a) break;
    const double sx = std::sqrt(x), sy = std::sqrt(y), sz = std::sqrt(z);
    const double lambda = sx * sy + sy * sz + sz * sx;
    x = 0.25 * (x + lambda), y = 0.25 * (y + lambda), z = 0.25 * (z + lambda);
    a = (x + y + z) / 3.0;
  }
  const double X = (a - x) / a, Y = (a - y) / a, Z = -(X + Y);
  const double e2 = X * Y - Z * Z, e3 = X * Y * Z;
  return (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0) / std::sqrt(a);
}

// RD(x, y, z) = 3/2 int_0^inf dt / sqrt((t + x)(t + y)(t + z)^3); x, y >= 0 (not both zero), z > 0.
inline double carlsonRD(double x, double y, double z) {
  constexpr double tol = 1e-3;
  double sum = 0.0, fac = 1.0, a = (x + y + 3.0 * z) / 5.0;
  for (int it = 0; it < 100; ++it) {
    if (std::max({std::abs(a - x), std::abs(a - y), std::abs(a - z)}) <= tol * a) break;
    const double sx = std::sqrt(x), sy = std::sqrt(y), sz = std::sqrt(z);
    const double lambda = sx * sy + sy * sz + sz * sx;
    sum += fac / (sz * (z + lambda));
    fac *= 0.25;
    x = 0.25 * (x + lambda), y = 0.25 * (y + lambda), z = 0.25 * (z + lambda);
    a = (x + y + 3.0 * z) / 5.0;
  }
  const double X = (a - x) / a, Y = (a - y) / a, Z = -(X + Y) / 3.0;
  const double e2 = X * Y - 6.0 * Z * Z, e3 = (3.0 * X * Y - 8.0 * Z * Z) * Z;
  const double e4 = 3.0 * (X * Y - Z * Z) * Z * Z, e5 = X * Y * Z * Z * Z;
  const double series = 1.0 - 3.0 * e2 / 14.0 + e3 / 6.0 + 9.0 * e2 * e2 / 88.0 - 3.0 * e4 / 22.0 -
                        9.0 * e2 * e3 / 52.0 + 3.0 * e5 / 26.0;
  return 3.0 * sum + fac * series / (a * std::sqrt(a));
}

}  // namespace elastica_detail

// Dead vertical (-y) tip force P, loadParameter k = P L^2 / (EI) (k < 0 pulls upward).
//
// Bisshopp & Drucker, Q. Appl. Math. 3 (1945) 272-275; Frisch-Fay, "Flexible Bars" (1962) ch. 3.
// With phi(s) the downward slope, EI phi'' = -P cos(phi), phi(0) = 0, phi'(L) = 0, tip slope alpha:
//   p^2 = (1 + sin alpha) / 2,  sin psi0 = 1 / (p sqrt 2),
//   sqrt(k) = K(p) - F(psi0, p),                        (length condition, solved for alpha)
//   x / L = sqrt(2 sin alpha / k),
//   delta / L = 1 - 2 / sqrt(k) (E(p) - E(psi0, p)).
// The integrals run over [psi0, pi/2]; substituting psi = pi/2 - chi and writing them in Carlson
// form (DLMF 19.25.5, 19.25.7; homogeneity 19.16.1-2) with t = sin alpha gives, free of the
// cancellation the differences above suffer at small loads,
//   sqrt(k) = sqrt(t / (2 (1 - v))) RF(u, 1/2, v),
//   delta / L = t (1 - v RD(u, 1/2, v) / (3 RF(u, 1/2, v))),
//   v = (1 - t) / 2 = sin^2(pi/4 - alpha/2),  u = v / (2 (1 - v)).
// sqrt(k) grows monotonically from 0 to infinity as alpha goes from 0 to pi/2; alpha is found by
// bisection to machine precision.
inline ElasticaTip cantileverTipForce(double loadParameter) {
  using elastica_detail::carlsonRD;
  using elastica_detail::carlsonRF;
  constexpr double halfPi = 1.5707963267948966;
  const double k = std::abs(loadParameter), sign = loadParameter < 0 ? -1.0 : 1.0;
  if (k == 0.0) return {1.0, 0.0, 0.0};
  auto vOf = [](double alpha) { return std::pow(std::sin(0.5 * (halfPi - alpha)), 2); };
  auto rootLoad = [&](double alpha) {  // sqrt(k) as a function of the tip slope alpha
    const double v = vOf(alpha);
    return std::sqrt(std::sin(alpha) / (2 * (1 - v))) * carlsonRF(v / (2 * (1 - v)), 0.5, v);
  };
  const double target = std::sqrt(k);
  double lo = 0.0, hi = halfPi;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (rootLoad(mid) < target ? lo : hi) = mid;
  }
  const double alpha = 0.5 * (lo + hi), t = std::sin(alpha), v = vOf(alpha), u = v / (2 * (1 - v));
  const double delta = t * (1 - v * carlsonRD(u, 0.5, v) / (3 * carlsonRF(u, 0.5, v)));
  return {std::sqrt(2 * t / k), -sign * delta, -sign * alpha};
}

// Tip moment M (counter-clockwise), momentParameter m = M L / (EI): constant curvature m, so the
// cantilever is a circular arc, tip angle m, x = sin(m)/m, y = (1 - cos m)/m; m = 2 pi closes a
// full circle back at the origin.
inline ElasticaTip cantileverTipMoment(double momentParameter) {
  const double m = momentParameter;
  if (m == 0.0) return {1.0, 0.0, 0.0};
  const double h = std::sin(0.5 * m);
  return {std::sin(m) / m, 2.0 * h * h / m, m};
}

}  // namespace strand::testing
