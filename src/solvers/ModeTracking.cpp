#include "strand/solvers/ModeTracking.hpp"

#include <algorithm>
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
      LociEvent e;
      e.lower = a;
      e.point = m;
      e.parameter = parameter[m];
      e.gap = gap[m];
      e.frequency = 0.5 * (omega[m][a] + omega[m][a + 1]);
      e.exchange = std::min(mac(l, a, r, a + 1), mac(l, a + 1, r, a));
      e.mixing = std::max(mac(m, a, l, a), mac(m, a, l, a + 1));  // pure shape: ~1 with one of them
      e.modeShift = e.exchange > 0.5;
      if (!e.modeShift) continue;  // an approach without exchange of shapes
      e.kind = e.mixing < 0.9 ? "veering" : "crossing";
      events.push_back(e);
    }
  }
  std::sort(events.begin(), events.end(), [](const LociEvent& x, const LociEvent& y) { return x.parameter < y.parameter; });
  return events;
}

}  // namespace strand::solvers
