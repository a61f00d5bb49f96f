// The shape-function slots of one cable element at its Gauss points, as a structure of arrays:
// X[a][g] for slot a and point g. The points are padded with zero-weight copies of the last point
// to an even count P, and the element kernels are instantiated for each P: their loops over the
// points then have a compile-time trip count and vectorize (docs/performance.md, "Assembly").
#pragma once
#include <type_traits>

namespace strand::elements {

struct CablePointTable {
  static constexpr int kMax = 8;  // the scene reader allows 2..8 Gauss points
  int count = 0;                  // Gauss points
  int padded = 0;                 // count rounded up to even
  double B1[4][kMax], B2[4][kMax];              // slot x-derivatives (the kernels need no values)
  double wl[kMax];                              // Gauss weight times element length; 0 on the padding
  double wB1[4][kMax], wB2[4][kMax];            // wl B1, wl B2: the chain rule's weights
};

// Call f(std::integral_constant<int, P>) with P the table's padded point count.
template <class F>
decltype(auto) withPaddedPoints(const CablePointTable& t, F&& f) {
  switch (t.padded) {
    case 2: return f(std::integral_constant<int, 2>{});
    case 4: return f(std::integral_constant<int, 4>{});
    case 6: return f(std::integral_constant<int, 6>{});
    default: return f(std::integral_constant<int, 8>{});
  }
}

}  // namespace strand::elements
