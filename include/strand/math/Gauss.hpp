// Gauss-Legendre rules on [0, 1], n = 1..8 points, exact for polynomials of degree 2n - 1.
#pragma once
#include <vector>

namespace strand::math {

struct QuadratureRule {
  std::vector<double> x, w;  // points in [0, 1], weights summing to 1
  int size() const { return static_cast<int>(x.size()); }
};

// Nodes from Newton's method on the Legendre polynomial; accurate to machine precision.
QuadratureRule gaussLegendre(int n);

}  // namespace strand::math
