// Scalar functions of time for prescribed motions and loads, with exact first and second
// derivatives (the integrator needs the prescribed velocity and acceleration at t = 0).
//
//   constant  f = value
//   linear    f = rate t
//   ramp      f = 0 before start, linear to `value` at end, `value` after
//   cosine_ramp  f = 0 before start, value (1 - cos(pi (t - start) / (end - start))) / 2 to end,
//             `value` after (continuous rate: e.g. the load torque of Pechstein & Gerstmayr's drive)
//   sine      f = amplitude sin(2 pi frequency t + phase)
//   spin_up   hub angle of seed 001 Eq. 57 (Omega0 = omega, T = duration):
//               dpsi/dt = Omega0 (t/T - sin(2 pi t/T) / (2 pi))  for t <= T,  Omega0 after;
//               psi = Omega0 (t^2/(2T) + T/(4 pi^2) (cos(2 pi t/T) - 1)) for t <= T,
//               psi = Omega0 (t - T/2) after (continuous angle, rate and acceleration)
//   table     piecewise linear through (time[i], value[i]), constant outside
#pragma once
#include <string>
#include <vector>

namespace strand::model {

struct TimeValue {
  double f = 0.0, df = 0.0, ddf = 0.0;  // value and its first two time derivatives
};

struct TimeFunction {
  enum class Kind { Constant, Linear, Ramp, CosineRamp, Sine, SpinUp, Table };
  Kind kind = Kind::Constant;
  double value = 0.0;                      // constant, ramp, cosine_ramp
  double rate = 0.0;                       // linear
  double start = 0.0, end = 0.0;           // ramp [s]
  double amplitude = 0.0, frequency = 0.0, phase = 0.0;  // sine [Hz, rad]
  double omega = 0.0, duration = 0.0;      // spin_up [rad/s, s]
  std::vector<double> times, values;       // table

  TimeValue at(double t) const;
  std::string name() const;
  // the same function (every field above: a field added there belongs here too)
  bool operator==(const TimeFunction& o) const {
    return kind == o.kind && value == o.value && rate == o.rate && start == o.start && end == o.end &&
           amplitude == o.amplitude && frequency == o.frequency && phase == o.phase && omega == o.omega &&
           duration == o.duration && times == o.times && values == o.values;
  }
};

}  // namespace strand::model
