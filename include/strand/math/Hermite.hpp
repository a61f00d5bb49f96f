// Cubic Hermite shape functions on eta in [0, 1] (seed 003 Eq. 69-71):
//   s1 = 1 - 3 eta^2 + 2 eta^3,  s2 = eta - 2 eta^2 + eta^3,  s3 = 3 eta^2 - 2 eta^3,  s4 = eta^3 - eta^2,
// with r(eta) = s1 r_1 + s2 l r_1' + s3 r_2 + s4 l r_2' for an element of length l.
#pragma once
#include <array>

namespace strand::math {

struct HermiteValues {
  std::array<double, 4> s, ds, dds;  // s_a, ds_a/deta, d2s_a/deta2
};

inline HermiteValues hermite(double eta) {
  const double e2 = eta * eta, e3 = e2 * eta;
  HermiteValues h;
  h.s = {1.0 - 3.0 * e2 + 2.0 * e3, eta - 2.0 * e2 + e3, 3.0 * e2 - 2.0 * e3, e3 - e2};
  h.ds = {-6.0 * eta + 6.0 * e2, 1.0 - 4.0 * eta + 3.0 * e2, 6.0 * eta - 6.0 * e2, 3.0 * e2 - 2.0 * eta};
  h.dds = {-6.0 + 12.0 * eta, -4.0 + 6.0 * eta, 6.0 - 12.0 * eta, 6.0 * eta - 2.0};
  return h;
}

}  // namespace strand::math
