// Mode tracking over a parameter sweep and detection of frequency veering and crossing (design
// section 4; seed 003: loci veering and mode shift). Pure functions on frequencies and MAC values.
//
// MAC(phi, psi) = |phi^H M psi|^2 / ((phi^H M phi)(psi^H M psi)) (modal assurance criterion).
// Loci are the sorted frequencies omega_1(p) < omega_2(p) < ...; a *tracked* mode follows its shape
// from point to point by the largest MAC.
//   veering:  two neighbouring loci approach to a minimum gap and repel; across the approach their
//             shapes exchange (mode shift), and at the closest point each shape is a mixture of the
//             two (MAC with either end shape < 0.9);
//   crossing: two loci touch without interaction: the shapes stay pure, and tracking by MAC swaps
//             the sorted order.
#pragma once
#include <functional>
#include <string>
#include <vector>

namespace strand::solvers {

// macNext[i][a * count + b]: MAC between sorted mode a at point i and sorted mode b at point i + 1.
// Returns label[i][a]: the tracked mode (its sorted index at point 0) that sorted mode a of point i
// continues. Greedy assignment by decreasing MAC.
std::vector<std::vector<int>> trackModes(const std::vector<std::vector<double>>& macNext, int count);

struct LociEvent {
  std::string kind;          // "veering" or "crossing"
  int lower = 0;             // sorted locus index a (0-based) of the pair (a, a + 1)
  int point = 0;             // sweep point of the minimum gap
  double parameter = 0.0;    // parameter value of the minimum gap (parabola in gap^2 through 3 points)
  double gap = 0.0;          // minimum gap omega_{a+1} - omega_a (units of omega), same fit
  double frequency = 0.0;    // mean of the two frequencies there
  double exchange = 0.0;     // min(MAC(a at left end, a+1 at right end), MAC(a+1 left, a right))
  double mixing = 0.0;       // max MAC of the lower shape at the minimum with the two left-end shapes
  bool modeShift = false;    // exchange > 0.5
  int left = 0, right = 0;   // points where the shapes were compared (gap grown to 5 x its minimum)
  bool refined = false;      // the numbers come from a local sweep between `left` and `right`
};

// mac(i, a, j, b): MAC between sorted mode a at point i and sorted mode b at point j.
using MacFunction = std::function<double(int i, int a, int j, int b)>;

std::vector<LociEvent> detectLociEvents(const std::vector<double>& parameter,
                                        const std::vector<std::vector<double>>& omega, const MacFunction& mac);

}  // namespace strand::solvers
