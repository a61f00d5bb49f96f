#include "strand/solvers/ModeTracking.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace strand::solvers {

std::vector<std::vector<int>> trackModes(const std::vector<std::vector<double>>& macNext, int count) {
  std::vector<std::vector<int>> label(macNext.size() + 1, std::vector<int>(count));
  std::iota(label[0].begin(), label[0].end(), 0);
  for (size_t i = 0; i < macNext.size(); ++i) {
    std::vector<int> order(count * count);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int x, int y) { return macNext[i][x] > macNext[i][y]; });
    std::vector<char> usedA(count, 0), usedB(count, 0);
    std::vector<int> match(count, -1);
    for (int ab : order) {
      const int a = ab / count, b = ab % count;
      if (usedA[a] || usedB[b]) continue;
      usedA[a] = usedB[b] = 1;
      match[b] = a;
    }
    for (int b = 0; b < count; ++b) label[i + 1][b] = label[i][match[b]];
  }
  return label;
}

namespace {
constexpr double kExchangeGap = 5.0;

// Minimum of the gap between two samples of a close approach. In the two-mode model of a veering
// (diagonal entries linear in p, coupling c) the squared gap is exactly quadratic,
// gap^2 = g^2 + s^2 (p - p0)^2, and so is that of a crossing (g = 0). A parabola through gap^2 at
// three points around the sampled minimum gives p0 and g, which a grid of spacing h would
// otherwise overestimate by up to sqrt(g^2 + (s h / 2)^2).
void fitMinimum(const double p[3], const double g[3], double* p0, double* gmin) {
  const double y0 = g[0] * g[0], y1 = g[1] * g[1], y2 = g[2] * g[2];
  const double d01 = (y1 - y0) / (p[1] - p[0]), d12 = (y2 - y1) / (p[2] - p[1]);
  const double a = (d12 - d01) / (p[2] - p[0]);
  if (!(a > 0.0)) return;
  const double b = d01 - a * (p[0] + p[1]);  // y = a p^2 + b p + c
  const double x = -b / (2.0 * a);
  if (x < p[0] || x > p[2]) return;
  const double ymin = y1 - a * (p[1] - x) * (p[1] - x) - (2.0 * a * x + b) * (p[1] - x);
  *p0 = x;
  *gmin = std::sqrt(std::max(ymin, 0.0));
}
}  // namespace

std::vector<LociEvent> detectLociEvents(const std::vector<double>& parameter,
                                        const std::vector<std::vector<double>>& omega, const MacFunction& mac) {
  std::vector<LociEvent> events;
  const int n = static_cast<int>(omega.size());
  if (n < 3) return events;
  const int count = static_cast<int>(omega[0].size());
  for (int a = 0; a + 1 < count; ++a) {
    std::vector<double> gap(n);
    for (int i = 0; i < n; ++i) gap[i] = omega[i][a + 1] - omega[i][a];
    for (int m = 1; m + 1 < n; ++m) {
      if (!(gap[m] < gap[m - 1] && gap[m] <= gap[m + 1])) continue;
      int l = m, r = m;
      while (l > 0 && gap[l - 1] > gap[l]) --l;
      while (r + 1 < n && gap[r + 1] > gap[r]) ++r;
      // a real approach: the gap dips well below its values at both ends of the window
      if (gap[m] > 0.7 * std::min(gap[l], gap[r])) continue;
      // Shapes are compared where the gap has grown to kExchangeGap x its minimum (at least one
      // point away). For two loci alone the gap is a hyperbola and the mixing angle theta obeys
      // tan 2 theta = g_min / sqrt(gap^2 - g_min^2): at 5 g_min the shapes are 99 % pure. Going
      // further can reach a neighbouring veering when one locus passes several (multiple veering).
      const double cap = kExchangeGap * gap[m];
      l = m - 1;
      r = m + 1;
      while (l > 0 && gap[l - 1] > gap[l] && gap[l] < cap) --l;
      while (r + 1 < n && gap[r + 1] > gap[r] && gap[r] < cap) ++r;
      LociEvent e;
      e.lower = a;
      e.point = m;
      e.parameter = parameter[m];
      e.gap = gap[m];
      {
        const double ps[3] = {parameter[m - 1], parameter[m], parameter[m + 1]}, gs[3] = {gap[m - 1], gap[m], gap[m + 1]};
        fitMinimum(ps, gs, &e.parameter, &e.gap);
      }
      e.frequency = 0.5 * (omega[m][a] + omega[m][a + 1]);
      e.exchange = std::min(mac(l, a, r, a + 1), mac(l, a + 1, r, a));
      e.mixing = std::max(mac(m, a, l, a), mac(m, a, l, a + 1));  // pure shape: ~1 with one of them
      e.modeShift = e.exchange > 0.5;
      e.left = l;
      e.right = r;
      if (!e.modeShift) continue;  // an approach without exchange of shapes
      e.kind = e.mixing < 0.9 ? "veering" : "crossing";
      events.push_back(e);
    }
  }
  std::sort(events.begin(), events.end(), [](const LociEvent& x, const LociEvent& y) { return x.parameter < y.parameter; });
  return events;
}

}  // namespace strand::solvers
