#include "strand/ffr/HermiteFem.hpp"

#include <algorithm>
#include <cmath>

namespace strand::ffr {

HermiteFem::HermiteFem(double length, int elements) : _L(length), _N(elements) {}

std::string HermiteFem::name() const { return "fem " + std::to_string(_N) + " elements"; }

void HermiteFem::shapes(double x, ShapeRows& r) const {
  const int n = size();
  for (Eigen::RowVectorXd* v : {&r.axial, &r.axialSlope, &r.bending, &r.bendingSlope, &r.bendingCurvature})
    v->setZero(n);
  const double le = _L / _N;
  const int e = std::clamp(static_cast<int>(std::floor(x / le)), 0, _N - 1);
  const double xi = x / le - e;
  // element nodes e (left) and e + 1 (right); node k >= 1 has coordinates at 3(k - 1)
  const double na[2] = {1.0 - xi, xi}, dna[2] = {-1.0 / le, 1.0 / le};
  const double h[4] = {1 - 3 * xi * xi + 2 * xi * xi * xi, le * (xi - 2 * xi * xi + xi * xi * xi),
                       3 * xi * xi - 2 * xi * xi * xi, le * (-xi * xi + xi * xi * xi)};
  const double dh[4] = {(-6 * xi + 6 * xi * xi) / le, 1 - 4 * xi + 3 * xi * xi, (6 * xi - 6 * xi * xi) / le,
                        -2 * xi + 3 * xi * xi};
  const double ddh[4] = {(-6 + 12 * xi) / (le * le), (-4 + 6 * xi) / le, (6 - 12 * xi) / (le * le),
                         (-2 + 6 * xi) / le};
  for (int a = 0; a < 2; ++a) {
    const int node = e + a;
    if (node == 0) continue;  // clamped
    const int c = 3 * (node - 1);
    r.axial[c] = na[a];
    r.axialSlope[c] = dna[a];
    for (int k = 0; k < 2; ++k) {
      r.bending[c + 1 + k] = h[2 * a + k];
      r.bendingSlope[c + 1 + k] = dh[2 * a + k];
      r.bendingCurvature[c + 1 + k] = ddh[2 * a + k];
    }
  }
}

std::vector<QuadraturePoint> HermiteFem::quadrature() const { return cellQuadrature(_L, _N, 4); }

}  // namespace strand::ffr
