// The shear-deformable 2D beams (AncfBeam2dShear, AncfBeam2dLinear) in every integrator (issue 33):
// a soft pendulum of 4 elements (1 m, 0.1 x 0.02 m, E = 1e6 Pa, nu = 0.3, Kelvin-Voigt 3e-4 s),
// pinned at node 0 and released horizontally under gravity, to t = 0.5 s. The tip position changes
// per halving of h at the rate of each scheme (generalized-alpha 2, Newmark 2, HHT 2, BDF2 2,
// RK4 4), and every scheme's finest tip agrees with RK4's finest within twice their Richardson
// error estimates: one answer, reached by every integrator, with the element's mass, damping and
// tangents. (The cable's own study: test_integrators.cpp.) The section's thickness-stretch mode,
// omega ~ sqrt(12 E / rho) / h = 2e3 rad/s, bounds the explicit steps: ABM4 is stable only below
// h = 1.9e-4 s here (it says so and stops at 5e-4 s), where its tip error is at round-off, so it
// runs once at 1.25e-4 s and must agree with RK4's finest to 1e-9 m.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/Pendulum.hpp"
#include "support/ShearBeams.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

model::SceneDescription shearPendulum(const std::string& kind) {
  RectangleSection s;
  s.E = 1e6;
  s.height = 0.02;
  auto sc = shearCantilever(kind, 4, 1.0, s);
  sc.bodies[0].section.set("damping", 3e-4);
  sc.supports[0].type = model::SupportType::Pinned;
  sc.loads.gravity = {0, -9.81, 0};
  sc.analysis = model::Analysis::Dynamic;
  return sc;
}

struct Study {
  double tip[4][2];
  double change[3];
};

Study halvings(const std::string& kind, model::DynamicsDesc d, double h0, const char* name) {
  Study s{};
  for (int k = 0; k < 4; ++k) {
    d.dt = h0 / (1 << k);
    d.tEnd = 0.5;
    const PendulumRun r = runPendulum(shearPendulum(kind), d, false);
    s.tip[k][0] = r.tipX;
    s.tip[k][1] = r.tipY;
  }
  for (int k = 0; k < 3; ++k) s.change[k] = std::hypot(s.tip[k][0] - s.tip[k + 1][0], s.tip[k][1] - s.tip[k + 1][1]);
  std::printf("%s %-7s changes %.3e %.3e %.3e  rates %.2f %.2f; finest tip (%.10f, %.10f)\n", kind.c_str(), name,
              s.change[0], s.change[1], s.change[2], std::log2(s.change[0] / s.change[1]),
              std::log2(s.change[1] / s.change[2]), s.tip[3][0], s.tip[3][1]);
  return s;
}

}  // namespace

TEST(ShearBeamDynamics, EveryIntegratorConvergesAtItsOrderToTheSameTip) {
  for (const char* kind : {"AncfBeam2dShear", "AncfBeam2dLinear"}) {
    model::DynamicsDesc bdf2 = scheme(model::Integrator::Bdf, 1.0, 0, 0);
    bdf2.bdfOrder = 2;
    struct Case {
      const char* name;
      model::DynamicsDesc d;
      double h0;
      int order;
    } cases[] = {{"alpha", scheme(model::Integrator::GeneralizedAlpha, 0.9, 0, 0), 2e-3, 2},
                 {"newmark", scheme(model::Integrator::Newmark, 1.0, 0, 0), 2e-3, 2},
                 {"hht", scheme(model::Integrator::Hht, 1.0, 0, 0), 2e-3, 2},
                 {"bdf2", bdf2, 2e-3, 2}};
    const Study ref = halvings(kind, scheme(model::Integrator::Rk4, 1.0, 0, 0), 1e-3, "rk4");
    for (int k = 0; k < 2; ++k) EXPECT_NEAR(std::log2(ref.change[k] / ref.change[k + 1]), 4.0, 0.3) << kind << " rk4";
    for (const Case& c : cases) {
      const Study s = halvings(kind, c.d, c.h0, c.name);
      EXPECT_NEAR(std::log2(s.change[1] / s.change[2]), c.order, c.order == 4 ? 0.3 : 0.15) << kind << " " << c.name;
      const double richardson = s.change[2] / ((1 << c.order) - 1), refError = ref.change[2] / 15.0;
      const double distance = std::hypot(s.tip[3][0] - ref.tip[3][0], s.tip[3][1] - ref.tip[3][1]);
      EXPECT_LT(distance, 2.0 * (richardson + refError)) << kind << " " << c.name;
    }
    model::DynamicsDesc abm4 = scheme(model::Integrator::Abm4, 1.0, 1.25e-4, 0.5);
    const PendulumRun r = runPendulum(shearPendulum(kind), abm4, false);
    EXPECT_LT(std::hypot(r.tipX - ref.tip[3][0], r.tipY - ref.tip[3][1]), 1e-9) << kind << " abm4";
  }
}
