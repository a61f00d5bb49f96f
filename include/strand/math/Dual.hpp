// Forward-mode dual number with N derivative directions.
//
// Element forces are templated on the scalar type, and instantiating them with Dual<N> gives the
// exact Jacobian: the tests compare every hand-derived tangent against it, and one production
// path uses it, the damped ALE kinds' tangent (AleCable.hpp, dualTangent; docs/architecture.md,
// "Element kinds": why that one is not hand-derived).
#pragma once
#include <array>
#include <cmath>

namespace strand::math {

template <int N>
struct Dual {
  double v = 0.0;
  std::array<double, N> d{};

  Dual() = default;
  Dual(double value) : v(value) {}  // NOLINT: implicit from constants, like a double
  static Dual variable(double value, int direction) {
    Dual x(value);
    x.d[direction] = 1.0;
    return x;
  }

  Dual& operator+=(const Dual& o) { v += o.v; for (int i = 0; i < N; ++i) d[i] += o.d[i]; return *this; }
  Dual& operator-=(const Dual& o) { v -= o.v; for (int i = 0; i < N; ++i) d[i] -= o.d[i]; return *this; }
  Dual& operator*=(const Dual& o) {
    for (int i = 0; i < N; ++i) d[i] = d[i] * o.v + v * o.d[i];
    v *= o.v;
    return *this;
  }
  Dual& operator/=(const Dual& o) {
    const double inv = 1.0 / o.v;
    for (int i = 0; i < N; ++i) d[i] = (d[i] - v * inv * o.d[i]) * inv;
    v *= inv;
    return *this;
  }
};

template <int N> Dual<N> operator+(Dual<N> a, const Dual<N>& b) { return a += b; }
template <int N> Dual<N> operator-(Dual<N> a, const Dual<N>& b) { return a -= b; }
template <int N> Dual<N> operator*(Dual<N> a, const Dual<N>& b) { return a *= b; }
template <int N> Dual<N> operator/(Dual<N> a, const Dual<N>& b) { return a /= b; }
template <int N> Dual<N> operator+(Dual<N> a, double b) { a.v += b; return a; }
template <int N> Dual<N> operator+(double b, Dual<N> a) { a.v += b; return a; }
template <int N> Dual<N> operator-(Dual<N> a, double b) { a.v -= b; return a; }
template <int N> Dual<N> operator-(double b, const Dual<N>& a) { return Dual<N>(b) - a; }
template <int N> Dual<N> operator-(const Dual<N>& a) { return Dual<N>(0.0) - a; }
template <int N> Dual<N> operator*(Dual<N> a, double b) { a.v *= b; for (auto& x : a.d) x *= b; return a; }
template <int N> Dual<N> operator*(double b, Dual<N> a) { return a * b; }
template <int N> Dual<N> operator/(Dual<N> a, double b) { return a * (1.0 / b); }
template <int N> Dual<N> operator/(double b, const Dual<N>& a) { return Dual<N>(b) / a; }

template <int N>
Dual<N> sqrt(const Dual<N>& a) {
  Dual<N> r(std::sqrt(a.v));
  const double g = 0.5 / r.v;
  for (int i = 0; i < N; ++i) r.d[i] = g * a.d[i];
  return r;
}

template <int N>
Dual<N> tanh(const Dual<N>& a) {
  Dual<N> r(std::tanh(a.v));
  const double g = 1.0 - r.v * r.v;
  for (int i = 0; i < N; ++i) r.d[i] = g * a.d[i];
  return r;
}

inline double value(double x) { return x; }
template <int N> double value(const Dual<N>& x) { return x.v; }

}  // namespace strand::math
