#include "strand/math/Gauss.hpp"

#include <cmath>
#include <stdexcept>

namespace strand::math {

QuadratureRule gaussLegendre(int n) {
  if (n < 1 || n > 8) throw std::invalid_argument("gaussLegendre: n must be in 1..8");
  QuadratureRule rule;
  rule.x.resize(n);
  rule.w.resize(n);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(M_PI * (i + 0.75) / (n + 0.5));  // initial guess on [-1, 1]
    double dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x;  // Legendre recurrence up to P_n
      for (int k = 2; k <= n; ++k) {
        const double pk = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = pk;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::fabs(dx) < 1e-16) break;
    }
    rule.x[n - 1 - i] = 0.5 * (x + 1.0);
    rule.w[n - 1 - i] = 1.0 / ((1.0 - x * x) * dp * dp);  // 2/((1-x^2)P'^2) mapped to [0, 1]
  }
  return rule;
}

}  // namespace strand::math
