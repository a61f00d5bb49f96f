// The simply supported spinning shaft under an axially moving, rotating load, by modal series
// (tests only): seed 000 sec. 4.3, Eq. 59-61 (Katz, J. Sound Vib. 246 (2001); Katz, Lee, Ulsoy &
// Scott, J. Sound Vib. 122 (1988)):
//   EJ U_zzzz + rho A U_tt - rho J (U_zztt - 2 i Omega U_zzt) = P delta(z - z0 - v t) e^{i omega t},
// U = U1 + i U2, U = U_t = 0 at t = 0, U = U_zz = 0 at z = 0, l. With U = sum a_n(t) sin(k_n z),
// k_n = n pi / l, beta_n = (J / A) k_n^2 (the Rayleigh rotary inertia), each mode obeys
//   a'' - i g a' + w0^2 a = f sin(k_n (z0 + v t)) e^{i omega t},
//   g = 2 Omega beta / (1 + beta),  w0^2 = EJ k^4 / (rho A (1 + beta)),  f = 2 P / (rho A l (1 + beta)).
// The forcing is a sum of two exponentials C e^{i rho t}, rho = omega +- k v; each has the
// particular response C e^{i rho t} / (w0^2 + g rho - rho^2) and, for zero initial conditions, the
// free whirls A1 e^{i s1 t} + A2 e^{i s2 t}, s1,2 = (g +- sqrt(g^2 + 4 w0^2)) / 2 (the forward and
// backward whirl; the seed's omega_n1, omega_n2), A1 + A2 = -C', s1 A1 + s2 A2 = -rho C'. This is
// Eq. 62-63 in closed form per mode. beta = 0 (Euler-Bernoulli, the VLBSE's bending model, in
// which the spin does not enter) gives s = +-w0.
#pragma once
#include <cmath>
#include <complex>

namespace strand::testing {

struct MovingLoadShaft {
  double EJ, rhoA, JoverA, l, P, v, omega, z0 = 0.0, Omega = 0.0;
  bool rayleigh = false;  // include beta_n (rotary inertia and the gyroscopic spin term)

  // U(z, t) = U1 + i U2 with `terms` modes.
  std::complex<double> deflection(double z, double t, int terms = 200) const {
    using C = std::complex<double>;
    const C I(0.0, 1.0);
    C U = 0.0;
    for (int n = 1; n <= terms; ++n) {
      const double k = n * M_PI / l, beta = rayleigh ? JoverA * k * k : 0.0;
      const double g = 2.0 * Omega * beta / (1.0 + beta), w02 = EJ * k * k * k * k / (rhoA * (1.0 + beta));
      const double f = 2.0 * P / (rhoA * l * (1.0 + beta));
      const double root = std::sqrt(g * g + 4.0 * w02), s1 = 0.5 * (g + root), s2 = 0.5 * (g - root);
      // sin(k z0 + k v t) e^{i omega t} = [e^{i k z0} e^{i (omega + k v) t} - e^{-i k z0} e^{i (omega - k v) t}] / (2 i)
      const C c[2] = {f * std::exp(I * (k * z0)) / (2.0 * I), -f * std::exp(-I * (k * z0)) / (2.0 * I)};
      const double rho[2] = {omega + k * v, omega - k * v};
      C a = 0.0;
      for (int j = 0; j < 2; ++j) {
        const C cp = c[j] / (w02 + g * rho[j] - rho[j] * rho[j]);
        const C A1 = cp * (s2 - rho[j]) / (s1 - s2), A2 = -cp - A1;
        a += cp * std::exp(I * (rho[j] * t)) + A1 * std::exp(I * (s1 * t)) + A2 * std::exp(I * (s2 * t));
      }
      U += a * std::sin(k * z);
    }
    return U;
  }
  // The static midspan deflection under P at midspan, P l^3 / (48 EJ): the normalization U_s.
  double staticMidspan() const { return P * l * l * l / (48.0 * EJ); }
};

}  // namespace strand::testing
