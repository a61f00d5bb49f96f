// requirement: Gauss-Legendre rules integrate polynomials of degree 2n-1 exactly on [0, 1];
// Hermite shape functions interpolate values and slopes at the element ends (seed 003 Eq. 70).
#include <gtest/gtest.h>

#include <cmath>

#include "strand/math/Gauss.hpp"
#include "strand/math/Hermite.hpp"

using namespace strand::math;

TEST(GaussLegendre, ExactForDegree2nMinus1) {
  for (int n = 1; n <= 8; ++n) {
    const QuadratureRule r = gaussLegendre(n);
    for (int p = 0; p <= 2 * n - 1; ++p) {
      double sum = 0.0;
      for (int g = 0; g < n; ++g) sum += r.w[g] * std::pow(r.x[g], p);
      EXPECT_NEAR(sum, 1.0 / (p + 1), 1e-15) << "n=" << n << " p=" << p;
    }
  }
}

TEST(GaussLegendre, RejectsUnsupportedSizes) {
  EXPECT_THROW(gaussLegendre(0), std::invalid_argument);
  EXPECT_THROW(gaussLegendre(9), std::invalid_argument);
}

TEST(Hermite, InterpolatesEndValuesAndSlopes) {
  const HermiteValues h0 = hermite(0.0), h1 = hermite(1.0);
  const double s0[4] = {1, 0, 0, 0}, d0[4] = {0, 1, 0, 0}, s1[4] = {0, 0, 1, 0}, d1[4] = {0, 0, 0, 1};
  for (int a = 0; a < 4; ++a) {
    EXPECT_DOUBLE_EQ(h0.s[a], s0[a]);
    EXPECT_DOUBLE_EQ(h0.ds[a], d0[a]);
    EXPECT_DOUBLE_EQ(h1.s[a], s1[a]);
    EXPECT_DOUBLE_EQ(h1.ds[a], d1[a]);
  }
}

TEST(Hermite, DerivativesMatchDifferenceQuotients) {
  const double eta = 0.37, h = 1e-6;
  const HermiteValues c = hermite(eta), p = hermite(eta + h), m = hermite(eta - h);
  for (int a = 0; a < 4; ++a) {
    EXPECT_NEAR(c.ds[a], (p.s[a] - m.s[a]) / (2 * h), 1e-9);
    EXPECT_NEAR(c.dds[a], (p.ds[a] - m.ds[a]) / (2 * h), 1e-8);
  }
}
