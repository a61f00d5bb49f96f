// The belt-pulley contact law at a point (include/strand/contact/PulleyContact.hpp).
//
// requirement: the hand-derived tangents df/dr, df/dv equal the dual-number derivatives of the
//   force, and df/domega its central difference, in every regime (frictionless, damped, sticking
//   creep, sliding, a moving and turning pulley, the creep-rate law creeping and sliding, the
//   bristle law sticking and slipping);
// requirement: the law's kinematics: no force off the pulley; the normal force k |g| along the
//   outward normal; no friction when the belt point moves with the pulley's material point;
//   friction mu p against the slip once |s| >> v_s; the bristle law holds a sticking point with
//   f_t = -k_t z and no slip (true stick, no creep) and slides at mu p against the slip.
#include <gtest/gtest.h>

#include <cmath>

#include "strand/contact/PulleyContact.hpp"
#include "strand/math/Dual.hpp"

using namespace strand;
using contact::ContactLaw;
using contact::FrictionLaw;
using contact::PulleyState;

namespace {

struct Case {
  const char* name;
  ContactLaw law;
  PulleyState pulley;
  double r[2], v[2];
  contact::BristleHistory history = {};
};

ContactLaw law(double damping, FrictionLaw friction, double mu, double vs) {
  ContactLaw l;
  l.stiffness = 3e5;
  l.damping = damping;
  l.friction = friction;
  l.mu = mu;
  l.slipVelocity = vs;
  l.offset = 0.002;
  return l;
}

ContactLaw bristle(double damping, double mu) {
  ContactLaw l = law(damping, FrictionLaw::Bristle, mu, 1e-3);
  l.tangentialStiffness = 1e6;
  return l;
}

PulleyState pulley(double omega, double vcx = 0.0, double vcy = 0.0) {
  PulleyState p;
  p.c[0] = 0.3;
  p.c[1] = -0.1;
  p.vc[0] = vcx;
  p.vc[1] = vcy;
  p.omega = omega;
  p.radius = 0.1;
  return p;
}

std::vector<Case> cases() {
  const double a = 0.7, rho = 0.1015;  // penetration 0.5 mm below R + offset = 0.102
  const double r[2] = {0.3 + rho * std::cos(a), -0.1 + rho * std::sin(a)};
  return {
      {"frictionless", law(0.0, FrictionLaw::None, 0.0, 1e-3), pulley(0.0), {r[0], r[1]}, {0.2, -0.4}},
      {"damped", law(40.0, FrictionLaw::None, 0.0, 1e-3), pulley(0.0), {r[0], r[1]}, {0.02, -0.01}},
      {"creep", law(40.0, FrictionLaw::RegularizedCoulomb, 0.5, 1e-2), pulley(2.0), {r[0], r[1]},
       {-2.0 * rho * std::sin(a) + 0.003, 2.0 * rho * std::cos(a) - 0.002}},
      {"sliding", law(0.0, FrictionLaw::RegularizedCoulomb, 0.3, 1e-3), pulley(-5.0), {r[0], r[1]}, {0.1, 0.05}},
      {"moving pulley", law(10.0, FrictionLaw::RegularizedCoulomb, 0.4, 5e-2), pulley(1.5, 0.2, -0.3),
       {r[0], r[1]}, {0.25, -0.28}},
      {"creep-rate law creeping", law(40.0, FrictionLaw::CreepRate, 0.5, 1e-2), pulley(2.0), {r[0], r[1]},
       {-2.0 * rho * std::sin(a) + 0.003, 2.0 * rho * std::cos(a) - 0.002}},
      {"creep-rate law sliding", law(10.0, FrictionLaw::CreepRate, 0.4, 1e-2), pulley(1.5, 0.2, -0.3), {r[0], r[1]},
       {0.25, -0.28}},
      // p = 150 N/m, mu p = 75 N/m, k_t = 1e6 N/m^2: trial -k_t (z + dt s) = -30 (stick), -150 (slip)
      {"bristle stick", bristle(20.0, 0.5), pulley(2.0), {r[0], r[1]},
       {-2.0 * rho * std::sin(a) + 0.01 * -std::sin(a), 2.0 * rho * std::cos(a) + 0.01 * std::cos(a)}, {2e-5, 1e-3}},
      {"bristle slip", bristle(20.0, 0.5), pulley(-1.0, 0.1, 0.0), {r[0], r[1]}, {0.3, 0.2}, {5e-5, 1e-3}},
  };
}

}  // namespace

TEST(PulleyContact, TangentsEqualDualNumberDerivatives) {
  using Dl = math::Dual<4>;
  for (const Case& c : cases()) {
    Dl r[2] = {Dl::variable(c.r[0], 0), Dl::variable(c.r[1], 1)};
    Dl v[2] = {Dl::variable(c.v[0], 2), Dl::variable(c.v[1], 3)};
    Dl fd[2];
    ASSERT_TRUE(contact::pointForce(c.law, c.pulley, r, v, fd, &c.history)) << c.name;
    double f[2], dfdr[4], dfdv[4], dfdw[2];
    const contact::ContactPoint pt = contact::pointTangent(c.law, c.pulley, c.r, c.v, f, dfdr, dfdv, dfdw, &c.history);
    ASSERT_TRUE(pt.touching) << c.name;
    double scale = 0.0;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 4; ++j) scale = std::max(scale, std::abs(fd[i].d[j]));
    for (int i = 0; i < 2; ++i) {
      EXPECT_NEAR(f[i], fd[i].v, 1e-12 * std::abs(fd[i].v) + 1e-12) << c.name;
      for (int j = 0; j < 2; ++j) {
        EXPECT_NEAR(dfdr[i * 2 + j], fd[i].d[j], 1e-12 * scale) << c.name << " df" << i << "/dr" << j;
        EXPECT_NEAR(dfdv[i * 2 + j], fd[i].d[2 + j], 1e-12 * scale) << c.name << " df" << i << "/dv" << j;
      }
    }
    // df/domega by a central difference (omega is data of the pulley here)
    const double h = 1e-6 * std::max(1.0, std::abs(c.pulley.omega));
    PulleyState up = c.pulley, down = c.pulley;
    up.omega += h;
    down.omega -= h;
    double fu[2], fdn[2];
    contact::pointForce(c.law, up, c.r, c.v, fu, &c.history);
    contact::pointForce(c.law, down, c.r, c.v, fdn, &c.history);
    for (int i = 0; i < 2; ++i) {
      const double central = (fu[i] - fdn[i]) / (2.0 * h);
      EXPECT_NEAR(dfdw[i], central, 1e-6 * (std::abs(central) + std::abs(f[i]) * 1e-3) + 1e-9) << c.name;
    }
  }
}

TEST(PulleyContact, NormalForceIsPenaltyOnTheGapAlongTheOutwardNormal) {
  const ContactLaw l = law(0.0, FrictionLaw::RegularizedCoulomb, 0.5, 1e-3);
  const PulleyState p = pulley(0.0);
  const double a = 2.1, depth = 1e-4, rho = p.radius + l.offset - depth;
  const double r[2] = {p.c[0] + rho * std::cos(a), p.c[1] + rho * std::sin(a)}, v[2] = {0.0, 0.0};
  double f[2];
  ASSERT_TRUE(contact::pointForce(l, p, r, v, f));
  EXPECT_NEAR(f[0], l.stiffness * depth * std::cos(a), 1e-9);
  EXPECT_NEAR(f[1], l.stiffness * depth * std::sin(a), 1e-9);
  // off the pulley (a gap of 1 um): no force
  const double out[2] = {p.c[0] + (p.radius + l.offset + 1e-6) * std::cos(a),
                         p.c[1] + (p.radius + l.offset + 1e-6) * std::sin(a)};
  EXPECT_FALSE(contact::pointForce(l, p, out, v, f));
  EXPECT_EQ(f[0], 0.0);
  EXPECT_EQ(f[1], 0.0);
}

TEST(PulleyContact, FrictionFollowsTheSlipOfTheMaterialPoints) {
  const ContactLaw l = law(0.0, FrictionLaw::RegularizedCoulomb, 0.4, 1e-4);
  const PulleyState p = pulley(3.0, 0.5, -0.2);
  const double a = -0.4, rho = p.radius + l.offset - 2e-4, k = l.stiffness * 2e-4;
  const double r[2] = {p.c[0] + rho * std::cos(a), p.c[1] + rho * std::sin(a)};
  const double t[2] = {-std::sin(a), std::cos(a)};
  // the belt point moves with the pulley's material point: v = v_c + omega e_z x d
  const double withPulley[2] = {p.vc[0] - p.omega * rho * std::sin(a), p.vc[1] + p.omega * rho * std::cos(a)};
  double f[2], dr[4], dv[4], dw[2];
  contact::ContactPoint pt = contact::pointTangent(l, p, r, withPulley, f, dr, dv, dw);
  EXPECT_NEAR(pt.slip, 0.0, 1e-14);
  EXPECT_NEAR(pt.friction, 0.0, 0.4 * k * 1e-14 / 1e-4);  // mu p |s| / v_s with s at round-off
  EXPECT_NEAR(pt.pressure, k, 1e-9);
  // the belt point slides forward (along t) at 0.1 m/s relative to it: friction mu p backwards
  const double sliding[2] = {withPulley[0] + 0.1 * t[0], withPulley[1] + 0.1 * t[1]};
  pt = contact::pointTangent(l, p, r, sliding, f, dr, dv, dw);
  EXPECT_NEAR(pt.slip, 0.1, 1e-14);
  EXPECT_NEAR(pt.friction, -0.4 * k, 1e-12 * k);
  EXPECT_NEAR(f[0] * t[0] + f[1] * t[1], -0.4 * k, 1e-9 * k);
}

// The creep-rate law (Leamy & Wasfy 2002): friction mu p s / v_s against the slip up to v_s, mu p
// beyond, continuous at v_s.
TEST(PulleyContact, CreepRateLawIsLinearInTheCreepAndCoulombBeyond) {
  const ContactLaw l = law(0.0, FrictionLaw::CreepRate, 0.4, 0.02);
  const PulleyState p = pulley(0.0);
  const double a = 1.1, rho = 0.1015;  // p = k 0.5e-3 = 150 N/m
  const double r[2] = {0.3 + rho * std::cos(a), -0.1 + rho * std::sin(a)};
  const double t[2] = {-std::sin(a), std::cos(a)};
  double f[2], dr[4], dv[4], dw[2];
  for (double s : {-0.05, -0.02, -0.005, 0.0, 0.01, 0.02 * (1.0 - 1e-12), 0.02, 0.3}) {
    const double v[2] = {s * t[0], s * t[1]};
    const contact::ContactPoint pt = contact::pointTangent(l, p, r, v, f, dr, dv, dw);
    const double expected = -0.4 * 150.0 * std::max(-1.0, std::min(1.0, s / 0.02));
    EXPECT_NEAR(pt.pressure, 150.0, 1e-9);
    EXPECT_NEAR(pt.friction, expected, 1e-9) << "s " << s;
    EXPECT_EQ(pt.sticking, std::abs(s) <= 0.02) << "s " << s;
  }
}

TEST(PulleyContact, BristleSticksWithoutCreepAndSlidesAtMuP) {
  ContactLaw l = law(0.0, FrictionLaw::Bristle, 0.5, 1e-3);
  l.tangentialStiffness = 1e6;
  const PulleyState p = pulley(2.0);
  const double a = 0.3, rho = 0.1015;  // p = k 0.5e-3 = 150 N/m, mu p = 75 N/m
  const double r[2] = {0.3 + rho * std::cos(a), -0.1 + rho * std::sin(a)};
  const double t[2] = {-std::sin(a), std::cos(a)};
  double withPulley[2], f[2], dr[4], dv[4], dw[2];
  for (int i = 0; i < 2; ++i) withPulley[i] = 2.0 * rho * t[i];  // s = 0
  // stuck with a deflection inside the cone: the force holds it, whatever the time since (no creep)
  for (double dt : {0.0, 1e-3, 1.0}) {
    const contact::BristleHistory h{-4e-5, dt};
    const contact::ContactPoint pt = contact::pointTangent(l, p, r, withPulley, f, dr, dv, dw, &h);
    EXPECT_TRUE(pt.sticking);
    EXPECT_NEAR(pt.pressure, 150.0, 1e-9);
    EXPECT_NEAR(pt.friction, 40.0, 1e-9);  // -k_t z
  }
  // slipping along +t: the deflection grows to the cone's edge and the force stays -mu p
  double sliding[2];
  for (int i = 0; i < 2; ++i) sliding[i] = withPulley[i] + 0.05 * t[i];
  const contact::BristleHistory h{0.0, 1e-2};  // trial -k_t dt s = -500 beyond mu p = 75
  const contact::ContactPoint pt = contact::pointTangent(l, p, r, sliding, f, dr, dv, dw, &h);
  EXPECT_FALSE(pt.sticking);
  EXPECT_NEAR(pt.slip, 0.05, 1e-12);
  EXPECT_NEAR(pt.friction, -75.0, 1e-9);
  EXPECT_NEAR(f[0] * t[0] + f[1] * t[1], -75.0, 1e-9);
  // off the pulley: no force, whatever the history
  const double off[2] = {0.3 + 0.2 * std::cos(a), -0.1 + 0.2 * std::sin(a)};
  EXPECT_FALSE(contact::pointTangent(l, p, off, sliding, f, dr, dv, dw, &h).touching);
}
