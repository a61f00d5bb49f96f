#include "strand/ffr/DeformationBasis.hpp"

#include "strand/math/Gauss.hpp"

namespace strand::ffr {

std::vector<QuadraturePoint> cellQuadrature(double length, int cells, int points) {
  const math::QuadratureRule rule = math::gaussLegendre(points);
  const double h = length / cells;
  std::vector<QuadraturePoint> q;
  q.reserve(static_cast<size_t>(cells) * points);
  for (int c = 0; c < cells; ++c)
    for (int g = 0; g < rule.size(); ++g) q.push_back({(c + rule.x[g]) * h, rule.w[g] * h});
  return q;
}

}  // namespace strand::ffr
