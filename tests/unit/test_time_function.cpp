// Time functions (model/TimeFunction.hpp): the spin-up profile of seed 001 Eq. 57 at its known
// points, and for every kind the derivatives against central differences of the value (error
// O(h^2): checked at two steps, the error must fall by about 4).
#include <gtest/gtest.h>

#include <cmath>

#include "strand/model/HubMotion.hpp"
#include "strand/model/TimeFunction.hpp"

using strand::model::HubMotion;
using strand::model::TimeFunction;
using K = TimeFunction::Kind;

namespace {

std::vector<TimeFunction> samples() {
  std::vector<TimeFunction> out;
  TimeFunction f;
  f.kind = K::SpinUp;
  f.omega = 4.0;
  f.duration = 15.0;
  out.push_back(f);
  f = {};
  f.kind = K::Sine;
  f.amplitude = 0.3;
  f.frequency = 2.0;
  f.phase = 0.4;
  out.push_back(f);
  f = {};
  f.kind = K::Linear;
  f.rate = 1.5;
  out.push_back(f);
  return out;
}

}  // namespace

TEST(TimeFunction, SpinUpFollowsSeed001Eq57) {
  const TimeFunction f = samples()[0];
  const double W = 4.0, T = 15.0;
  EXPECT_DOUBLE_EQ(f.at(0.0).f, 0.0);
  EXPECT_DOUBLE_EQ(f.at(0.0).df, 0.0);
  EXPECT_DOUBLE_EQ(f.at(0.0).ddf, 0.0);
  // rate Omega0 (t/T - sin(2 pi t/T) / (2 pi)): at T/2 it is Omega0 / 2, with acceleration 2 Omega0 / T
  EXPECT_NEAR(f.at(T / 2).df, W / 2, 1e-14);
  EXPECT_NEAR(f.at(T / 2).ddf, 2 * W / T, 1e-14);
  // angle Omega0 T / 2 at T and continuous rate and acceleration there
  EXPECT_NEAR(f.at(T).f, W * T / 2, 1e-12);
  EXPECT_NEAR(f.at(T - 1e-9).df, W, 1e-8);
  EXPECT_NEAR(f.at(T - 1e-9).ddf, 0.0, 1e-8);
  EXPECT_NEAR(f.at(20.0).f, W * (20.0 - T / 2), 1e-12);
}

TEST(TimeFunction, DerivativesMatchCentralDifferences) {
  for (const TimeFunction& f : samples()) {
    for (double t : {0.7, 3.1, 9.4}) {
      double err[2][2];
      for (int k = 0; k < 2; ++k) {
        const double h = 1e-3 / (1 << k);
        const double d1 = (f.at(t + h).f - f.at(t - h).f) / (2 * h);
        const double d2 = (f.at(t + h).df - f.at(t - h).df) / (2 * h);
        err[k][0] = std::fabs(d1 - f.at(t).df);
        err[k][1] = std::fabs(d2 - f.at(t).ddf);
      }
      for (int j = 0; j < 2; ++j) {
        if (err[0][j] > 1e-11) {
          EXPECT_NEAR(err[0][j] / err[1][j], 4.0, 0.2) << f.name() << " t " << t << " derivative " << j + 1;
        }
      }
    }
  }
}

TEST(TimeFunction, RampAndTableArePiecewiseLinear) {
  TimeFunction r;
  r.kind = K::Ramp;
  r.start = 1.0;
  r.end = 3.0;
  r.value = 4.0;
  EXPECT_DOUBLE_EQ(r.at(0.5).f, 0.0);
  EXPECT_DOUBLE_EQ(r.at(2.0).f, 2.0);
  EXPECT_DOUBLE_EQ(r.at(2.0).df, 2.0);
  EXPECT_DOUBLE_EQ(r.at(5.0).f, 4.0);
  TimeFunction t;
  t.kind = K::Table;
  t.times = {0.0, 1.0, 2.0};
  t.values = {0.0, 1.0, -1.0};
  EXPECT_DOUBLE_EQ(t.at(1.5).f, 0.0);
  EXPECT_DOUBLE_EQ(t.at(1.5).df, -2.0);
  EXPECT_DOUBLE_EQ(t.at(-1.0).f, 0.0);
  EXPECT_DOUBLE_EQ(t.at(9.0).f, -1.0);
}

// A hub point follows the circle: position, velocity psi' e x w and acceleration psi'' e x w +
// psi'^2 e x (e x w), here against the closed form for rotation about z in 2D and about x in 3D.
TEST(HubMotion, PointOnTheHubMovesOnItsCircle) {
  HubMotion h;
  h.center = {1.0, 0.0, 0.0};
  h.angle = samples()[0];
  h.blocks = {0, 1};
  h.slope = {0, 1};
  const double q0[2] = {3.0, 0.0}, t = 6.0;
  const auto psi = h.angle.at(t);
  double u[2], v[2], a[2];
  h.state(0, q0, 2, t, u, v, a);
  EXPECT_NEAR(u[0], 1.0 + 2.0 * std::cos(psi.f) - 3.0, 1e-14);
  EXPECT_NEAR(u[1], 2.0 * std::sin(psi.f), 1e-14);
  EXPECT_NEAR(v[0], -2.0 * psi.df * std::sin(psi.f), 1e-13);
  EXPECT_NEAR(v[1], 2.0 * psi.df * std::cos(psi.f), 1e-13);
  EXPECT_NEAR(a[0], -2.0 * (psi.ddf * std::sin(psi.f) + psi.df * psi.df * std::cos(psi.f)), 1e-13);
  EXPECT_NEAR(a[1], 2.0 * (psi.ddf * std::cos(psi.f) - psi.df * psi.df * std::sin(psi.f)), 1e-13);
  // slope block: rotates about no center
  const double s0[2] = {1.0, 0.0};
  h.state(1, s0, 2, t, u, v, a);
  EXPECT_NEAR(u[0], std::cos(psi.f) - 1.0, 1e-14);
  // 3D, axis x: the point (0, 2, 0) turns towards z
  HubMotion h3 = h;
  h3.center = {0.0, 0.0, 0.0};
  h3.axis = {1.0, 0.0, 0.0};
  const double p0[3] = {0.0, 2.0, 0.0};
  double u3[3], v3[3], a3[3];
  h3.state(0, p0, 3, t, u3, v3, a3);
  EXPECT_NEAR(u3[0], 0.0, 1e-14);
  EXPECT_NEAR(u3[1], 2.0 * std::cos(psi.f) - 2.0, 1e-14);
  EXPECT_NEAR(u3[2], 2.0 * std::sin(psi.f), 1e-14);
}

// The scene's geometry is the one at t = 0: a drive with psi(0) != 0 (a sine with a phase) turns it
// by psi(t) - psi(0), so the supported point starts where it is drawn, with the drive's own rate.
TEST(HubMotion, DriveWithAPhaseTurnsTheSceneFromWhereItIsDrawn) {
  HubMotion h;
  h.angle.kind = strand::model::TimeFunction::Kind::Sine;
  h.angle.amplitude = 0.5;
  h.angle.frequency = 0.5;
  h.angle.phase = M_PI / 4.0;
  h.blocks = {0};
  h.slope = {0};
  const double q0[2] = {2.0, 0.0};
  double u[2], v[2], a[2];
  h.state(0, q0, 2, 0.0, u, v, a);
  const auto psi0 = h.angle.at(0.0);
  EXPECT_EQ(u[0], 0.0);
  EXPECT_EQ(u[1], 0.0);
  EXPECT_NEAR(v[1], 2.0 * psi0.df, 1e-15);  // psi'(0) e_z x (2, 0)
  EXPECT_NEAR(a[0], -2.0 * psi0.df * psi0.df, 1e-14);
  EXPECT_NEAR(a[1], 2.0 * psi0.ddf, 1e-14);
  const double t = 0.7, turned = h.angle.at(t).f - psi0.f;
  h.state(0, q0, 2, t, u, v, a);
  EXPECT_NEAR(u[0], 2.0 * std::cos(turned) - 2.0, 1e-15);
  EXPECT_NEAR(u[1], 2.0 * std::sin(turned), 1e-15);
}
