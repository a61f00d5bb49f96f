// Hermite shape functions tabulated at the Gauss points of one rule, shared by all cable elements.
#pragma once
#include <array>
#include <vector>

#include "strand/math/Gauss.hpp"
#include "strand/math/Hermite.hpp"

namespace strand::elements {

struct CableShapeTable {
  math::QuadratureRule rule;
  std::vector<math::HermiteValues> at;  // one per Gauss point

  explicit CableShapeTable(int gaussPoints) : rule(math::gaussLegendre(gaussPoints)) {
    for (double x : rule.x) at.push_back(math::hermite(x));
  }
  int size() const { return rule.size(); }
};

}  // namespace strand::elements
