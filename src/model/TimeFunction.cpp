#include "strand/model/TimeFunction.hpp"

#include <algorithm>
#include <cmath>

namespace strand::model {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

TimeValue TimeFunction::at(double t) const {
  switch (kind) {
    case Kind::Constant: return {value, 0.0, 0.0};
    case Kind::Linear: return {rate * t, rate, 0.0};
    case Kind::Ramp: {
      if (t <= start) return {0.0, 0.0, 0.0};
      if (t >= end) return {value, 0.0, 0.0};
      const double slope = value / (end - start);
      return {slope * (t - start), slope, 0.0};
    }
    case Kind::CosineRamp: {
      if (t <= start) return {0.0, 0.0, 0.0};
      if (t >= end) return {value, 0.0, 0.0};
      const double k = kPi / (end - start), x = k * (t - start);
      return {0.5 * value * (1.0 - std::cos(x)), 0.5 * value * k * std::sin(x), 0.5 * value * k * k * std::cos(x)};
    }
    case Kind::Sine: {
      const double w = 2.0 * kPi * frequency, s = std::sin(w * t + phase), c = std::cos(w * t + phase);
      return {amplitude * s, amplitude * w * c, -amplitude * w * w * s};
    }
    case Kind::SpinUp: {  // seed 001 Eq. 57
      const double T = duration, W = omega;
      if (t >= T) return {W * (t - 0.5 * T), W, 0.0};
      const double k = 2.0 * kPi / T;
      return {W * (t * t / (2.0 * T) + (std::cos(k * t) - 1.0) / (k * k * T)), W * (t / T - std::sin(k * t) / (k * T)),
              W / T * (1.0 - std::cos(k * t))};
    }
    case Kind::Table: {
      if (t <= times.front()) return {values.front(), 0.0, 0.0};
      if (t >= times.back()) return {values.back(), 0.0, 0.0};
      const size_t i = static_cast<size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
      const double slope = (values[i + 1] - values[i]) / (times[i + 1] - times[i]);
      return {values[i] + slope * (t - times[i]), slope, 0.0};
    }
  }
  return {};
}

std::string TimeFunction::name() const {
  switch (kind) {
    case Kind::Constant: return "constant";
    case Kind::Linear: return "linear";
    case Kind::Ramp: return "ramp";
    case Kind::CosineRamp: return "cosine_ramp";
    case Kind::Sine: return "sine";
    case Kind::SpinUp: return "spin_up";
    case Kind::Table: return "table";
  }
  return "";
}

}  // namespace strand::model
