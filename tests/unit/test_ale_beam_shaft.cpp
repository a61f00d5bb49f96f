// Element-level verification of the variable-length ANCF beam-shaft AleBeamShaft3d (the VLBSE of
// seed 000, sec. 2-3), issue 35:
//  - the elastic force (bending, stretching and torsion G I_p theta'^2 / 2 over the moving material)
//    is the gradient of the strain energy and its tangent the dual-number derivative, including the
//    columns of the material coordinates p1, p2 (a twisted element gets shorter or longer);
//  - the inertial force F = int (rho A S^T rddot + rho I_p S_r^T thetaddot) dp and its three tangents
//    (M, C, K) are the exact derivatives, and M is symmetric;
//  - F differs from Lagrange's d/dt dT/dv - dT/dq of T = 1/2 int (rho A |rdot|^2 + rho I_p
//    thetadot^2) dp only by the momentum (linear and angular) that flows through the element's ends
//    (Leibniz's rule on the moving limits p1(t), p2(t)), as for the ALE cable (test_ale_cable.cpp):
//    the flux of the spin adds, at each end, rho I_p pdot thetadot(p_i) S_r(p_i)
//    - rho I_p / 2 thetadot(p_i)^2 delta_{k,p_i}, with thetadot(p_i) = vtheta_i - theta' pdot_i;
//  - with p1, p2 held, the element is the Lagrangian cable plus the linear torsion element:
//    torque G I_p / L [[1, -1], [-1, 1]] theta and polar mass rho I_p L / 6 [[2, 1], [1, 2]];
//  - a torque m per unit length on the material: its generalized force is the virtual work
//    int m delta theta dp at fixed material points (differenced here, independently of the closed
//    form), its tangent the dual-number derivative, its power int m thetadot dp = v . Q_m.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "strand/elements/AleBeamShaft.hpp"
#include "strand/math/Dual.hpp"
#include "strand/math/Gauss.hpp"

using namespace strand;
using namespace strand::elements;
using E = AleBeamShaft3d;

namespace {

constexpr int N = E::kDof;
using Dl = math::Dual<N>;
constexpr double kE = 2e7, kNu = 0.3, kRho = 1000.0, kR = 0.02, kRi = 0.005;

struct Fixture {
  E::Body body;
  double q0[N], u[N], v[N], a[N];
  std::mt19937 rng{17};
  double A = M_PI * (kR * kR - kRi * kRi), Ip = M_PI * (std::pow(kR, 4) - std::pow(kRi, 4)) / 2.0;

  explicit Fixture(bool moving = true) {
    SectionValues s;
    s.numbers = {{"E", kE}, {"nu", kNu}, {"rho", kRho}, {"radius", kR}, {"inner_radius", kRi}};
    body = E::body(s, {0.7, 1.0, 5});
    std::uniform_real_distribution<double> r(-0.1, 0.1);
    for (int k = 0; k < N; ++k) q0[k] = u[k] = v[k] = a[k] = 0.0;
    q0[E::slotIndex(0)] = 3.0;
    q0[E::slotIndex(1)] = 1.0;
    q0[E::slotIndex(2)] = 3.7;
    q0[E::slotIndex(3)] = 1.0;
    q0[E::kP1] = 5.0;
    q0[E::kP2] = 5.7;
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 3; ++i) {
        const int sl = E::slotIndex(k) + i;
        u[sl] = r(rng) * (k % 2 == 0 ? 0.7 : 1.0);
        v[sl] = 10.0 * r(rng);
        a[sl] = 100.0 * r(rng);
      }
    u[E::kT1] = 0.4, u[E::kT2] = -1.1;  // a twist of 1.5 rad over the element
    v[E::kT1] = 30.0, v[E::kT2] = 27.0;
    a[E::kT1] = -200.0, a[E::kT2] = 150.0;
    if (moving) {
      u[E::kP1] = 0.03, u[E::kP2] = -0.05;
      v[E::kP1] = 1.5, v[E::kP2] = 2.5;
      a[E::kP1] = -3.0, a[E::kP2] = 7.0;
    }
  }
};

double maxAbs(const double* x, int n) {
  double m = 0.0;
  for (int k = 0; k < n; ++k) m = std::max(m, std::fabs(x[k]));
  return m;
}

}  // namespace

TEST(AleBeamShaft, ElasticTangentIsTheExactDerivativeAndTheForceTheEnergyGradient) {
  Fixture fx;
  const E::Element el = E::element(fx.body, nullptr);
  double f[N], K[N * N];
  E::tangent(fx.body, el, fx.q0, fx.u, nullptr, f, K, nullptr);
  Dl ud[N], fd[N];
  for (int k = 0; k < N; ++k) ud[k] = Dl::variable(fx.u[k], k);
  E::force(fx.body, el, fx.q0, ud, static_cast<const Dl*>(nullptr), fd);
  const Dl U = E::strainEnergy(fx.body, el, fx.q0, ud);
  double Kad[N * N];
  for (int r = 0; r < N; ++r)
    for (int c = 0; c < N; ++c) Kad[r * N + c] = fd[r].d[c];
  const double sK = maxAbs(Kad, N * N), sF = maxAbs(f, N);
  EXPECT_GT(std::fabs(f[E::kT1]), 1e-4 * sF) << "the fixture twists the element";
  for (int k = 0; k < N; ++k) EXPECT_NEAR(f[k], U.d[k], 1e-11 * sF) << "f = dU/du, entry " << k;
  for (int k = 0; k < N * N; ++k) EXPECT_NEAR(K[k], Kad[k], 1e-11 * sK) << "K entry " << k;
}

TEST(AleBeamShaft, InertiaTangentsAreTheExactDerivatives) {
  Fixture fx;
  const E::Element el = E::element(fx.body, nullptr);
  double F[N], M[N * N], C[N * N], K[N * N];
  for (double* X : {M, C, K})
    for (int k = 0; k < N * N; ++k) X[k] = 0.0;
  E::inertiaTangent(fx.body, el, fx.q0, fx.u, fx.v, fx.a, F, M, C, K);
  for (int which = 0; which < 3; ++which) {  // d/da, d/dv, d/du
    Dl ud[N], vd[N], ad[N], Fd[N];
    for (int k = 0; k < N; ++k) {
      ud[k] = which == 2 ? Dl::variable(fx.u[k], k) : Dl(fx.u[k]);
      vd[k] = which == 1 ? Dl::variable(fx.v[k], k) : Dl(fx.v[k]);
      ad[k] = which == 0 ? Dl::variable(fx.a[k], k) : Dl(fx.a[k]);
    }
    E::inertia(fx.body, el, fx.q0, ud, vd, ad, Fd);
    const double* mine = which == 0 ? M : which == 1 ? C : K;
    double ref[N * N];
    for (int r = 0; r < N; ++r)
      for (int c = 0; c < N; ++c) ref[r * N + c] = Fd[r].d[c];
    const double s = maxAbs(ref, N * N);
    for (int k = 0; k < N * N; ++k) EXPECT_NEAR(mine[k], ref[k], 1e-11 * s) << "matrix " << which << " entry " << k;
    for (int k = 0; k < N; ++k) EXPECT_NEAR(F[k], Fd[k].v, 1e-13 * maxAbs(F, N));
  }
  for (int r = 0; r < N; ++r)
    for (int c = 0; c < N; ++c) EXPECT_NEAR(M[r * N + c], M[c * N + r], 1e-12 * maxAbs(M, N * N));
}

// The dynamic residual's one pass (KernelFamily::residualWithInertia): inertiaLessLoad = inertia -
// Q_f, the spin's inertia included.
TEST(AleBeamShaft, InertiaLessLoadIsTheInertiaLessTheDistributedLoad) {
  Fixture fx;
  const E::Element el = E::element(fx.body, nullptr);
  const double load[4] = {0.3, -9.81, 1.7, 45.0};  // a force and a torque per unit length
  double F[N], Q[N], both[N];
  E::inertia(fx.body, el, fx.q0, fx.u, fx.v, fx.a, F);
  E::distributedLoad(fx.body, fx.q0, fx.u, load, Q);
  E::inertiaLessLoad(fx.body, el, fx.q0, fx.u, fx.v, fx.a, load, both);
  const double s = std::max(maxAbs(F, N), maxAbs(Q, N));
  EXPECT_NE(F[E::kT1], 0.0);  // the spin's inertia is there (the cable part has none on theta)
  for (int k = 0; k < N; ++k) EXPECT_NEAR(both[k], F[k] - Q[k], 1e-14 * s) << "entry " << k;
}

TEST(AleBeamShaft, InertiaIsLagrangesEquationPlusTheMomentumFluxThroughTheEnds) {
  Fixture fx;
  const E::Element el = E::element(fx.body, nullptr);
  auto gradients = [&](const double* u, const double* v, double* Tv, double* Tu) {
    Dl ud[N], vd[N];
    for (int k = 0; k < N; ++k) ud[k] = Dl(u[k]), vd[k] = Dl::variable(v[k], k);
    const Dl T1 = E::kineticEnergy(fx.body, fx.q0, ud, vd);
    for (int k = 0; k < N; ++k) Tv[k] = T1.d[k], ud[k] = Dl::variable(u[k], k), vd[k] = Dl(v[k]);
    const Dl T2 = E::kineticEnergy(fx.body, fx.q0, ud, vd);
    for (int k = 0; k < N; ++k) Tu[k] = T2.d[k];
  };
  const double h = 1e-6;
  double up[N], vp[N], um[N], vm[N], Tvp[N], Tvm[N], Tu[N], Tv[N], tmp[N];
  for (int k = 0; k < N; ++k) {
    up[k] = fx.u[k] + h * fx.v[k], vp[k] = fx.v[k] + h * fx.a[k];
    um[k] = fx.u[k] - h * fx.v[k], vm[k] = fx.v[k] - h * fx.a[k];
  }
  gradients(up, vp, Tvp, tmp);
  gradients(um, vm, Tvm, tmp);
  gradients(fx.u, fx.v, Tv, Tu);
  double F[N];
  E::inertia(fx.body, el, fx.q0, fx.u, fx.v, fx.a, F);
  double flux[N] = {}, q[N];
  for (int k = 0; k < N; ++k) q[k] = fx.q0[k] + fx.u[k];
  const double rhoA = kRho * fx.A, rhoIp = kRho * fx.Ip;
  const double thetaPrime = (q[E::kT2] - q[E::kT1]) / (q[E::kP2] - q[E::kP1]);
  for (int node = 0; node < 2; ++node) {
    const int pos = E::slotIndex(2 * node), slope = E::slotIndex(2 * node + 1);
    const int p = node == 0 ? E::kP1 : E::kP2, th = node == 0 ? E::kT1 : E::kT2;
    const double sign = node == 0 ? -1.0 : 1.0, pdot = fx.v[p];
    double rd[3], rd2 = 0.0;
    for (int i = 0; i < 3; ++i) {
      rd[i] = fx.v[pos + i] - q[slope + i] * pdot;
      rd2 += rd[i] * rd[i];
    }
    for (int i = 0; i < 3; ++i) {
      flux[pos + i] += sign * rhoA * pdot * rd[i];
      flux[p] += sign * rhoA * pdot * rd[i] * (-q[slope + i]);
    }
    flux[p] -= sign * 0.5 * rhoA * rd2;
    const double thd = fx.v[th] - thetaPrime * pdot;  // the spin rate of the material at the end
    flux[th] += sign * rhoIp * pdot * thd;
    flux[p] += sign * rhoIp * pdot * thd * (-thetaPrime);
    flux[p] -= sign * 0.5 * rhoIp * thd * thd;
  }
  const double s = maxAbs(F, N);
  for (int k = 0; k < N; ++k)
    EXPECT_NEAR(F[k] + flux[k], (Tvp[k] - Tvm[k]) / (2.0 * h) - Tu[k], 1e-7 * s) << "entry " << k;
}

TEST(AleBeamShaft, WithTheMaterialHeldItIsTheCablePlusTheLinearTorsionElement) {
  Fixture fx(false);
  const E::Element el = E::element(fx.body, nullptr);
  using Cable = AleCable<3>;
  SectionValues cs;
  cs.numbers = {{"E", kE}, {"A", fx.A}, {"I", fx.Ip / 2.0}, {"rho", kRho}};
  const Cable::Body cb = Cable::body(cs, {0.7, 1.0, 5});
  double f[N], fc[N], F[N], Fc[N];
  double uc[N], vc[N], ac[N];  // the cable's coordinates: no spin
  for (int k = 0; k < N; ++k) uc[k] = fx.u[k], vc[k] = fx.v[k], ac[k] = fx.a[k];
  uc[E::kT1] = uc[E::kT2] = vc[E::kT1] = vc[E::kT2] = ac[E::kT1] = ac[E::kT2] = 0.0;
  E::force(fx.body, el, fx.q0, fx.u, static_cast<const double*>(nullptr), f);
  Cable::force(cb, Cable::element(cb, nullptr), fx.q0, uc, static_cast<const double*>(nullptr), fc);
  E::inertia(fx.body, el, fx.q0, fx.u, fx.v, fx.a, F);
  Cable::inertia(cb, Cable::element(cb, nullptr), fx.q0, uc, vc, ac, Fc);
  const double L = 0.7, G = kE / (2.0 * (1.0 + kNu));
  const double k = G * fx.Ip / L, m = kRho * fx.Ip * L / 6.0;
  const double t1 = fx.u[E::kT1], t2 = fx.u[E::kT2], a1 = fx.a[E::kT1], a2 = fx.a[E::kT2];
  fc[E::kT1] = k * (t1 - t2), fc[E::kT2] = k * (t2 - t1);
  Fc[E::kT1] = m * (2.0 * a1 + a2), Fc[E::kT2] = m * (a1 + 2.0 * a2);
  const double sf = maxAbs(fc, N), sF = maxAbs(Fc, N);
  for (int i = 0; i < N; ++i) {
    if (i == E::kP1 || i == E::kP2) continue;  // the reaction on the held material coordinates
    EXPECT_NEAR(f[i], fc[i], 1e-12 * sf) << "force entry " << i;
    EXPECT_NEAR(F[i], Fc[i], 1e-12 * sF) << "inertia entry " << i;
  }
}

// requirement (Eq. 38): the twist damping G I_p c_t thetadot' acts on the material's twist rate;
// with the material held it adds the linear torsion element's damping torque
// G I_p c_t (vtheta2 - vtheta1) / L to theta2 (and its negative to theta1).
TEST(AleBeamShaft, TwistDampingOnTheHeldMaterialIsTheLinearElements) {
  Fixture fx(false);
  SectionValues s;
  s.numbers = {{"E", kE}, {"nu", kNu}, {"rho", kRho}, {"radius", kR}, {"inner_radius", kRi}, {"damping_torsion", 0.02}};
  const E::Body damped = E::body(s, {0.7, 1.0, 5});
  ASSERT_TRUE(E::velocityDependent(damped));
  double fd[N], f0[N];
  E::force(damped, E::element(damped, nullptr), fx.q0, fx.u, fx.v, fd);
  E::force(damped, E::element(damped, nullptr), fx.q0, fx.u, static_cast<const double*>(nullptr), f0);
  const double G = kE / (2.0 * (1.0 + kNu)), torque = G * fx.Ip * 0.02 * (fx.v[E::kT2] - fx.v[E::kT1]) / 0.7;
  EXPECT_NEAR(fd[E::kT2] - f0[E::kT2], torque, 1e-12 * std::fabs(torque));
  EXPECT_NEAR(fd[E::kT1] - f0[E::kT1], -torque, 1e-12 * std::fabs(torque));
  for (int k = 0; k < N; ++k) {
    if (k != E::kT1 && k != E::kT2 && k != E::kP1 && k != E::kP2) {
      EXPECT_EQ(fd[k], f0[k]) << "entry " << k;
    }
  }
}

namespace {

// theta at the material point p of an element with coordinates q (linear in xi = (p - p1) / L).
double thetaAt(const double* q, double p) {
  const double xi = (p - q[E::kP1]) / (q[E::kP2] - q[E::kP1]);
  return (1.0 - xi) * q[E::kT1] + xi * q[E::kT2];
}

}  // namespace

// requirement (seed 000 Eq. 43-44 for a torque on the spin angle): Q_m,k = int m d theta(p)/d q_k dp
// over the element's material at fixed p, differenced (central, h = 1e-6) and integrated by a
// 5-point rule; the force part of the load is zero, so every other entry of Q vanishes.
TEST(AleBeamShaft, DistributedTorqueIsTheVirtualWorkAtFixedMaterialPoints) {
  Fixture fx;
  const double m = 45.0, load[4] = {0.0, 0.0, 0.0, m};
  double Q[N];
  E::distributedLoad(fx.body, fx.q0, fx.u, load, Q);
  double q[N];
  for (int k = 0; k < N; ++k) q[k] = fx.q0[k] + fx.u[k];
  const double p1 = q[E::kP1], L = q[E::kP2] - q[E::kP1], h = 1e-6;
  const math::QuadratureRule rule = math::gaussLegendre(5);
  for (int k = 0; k < N; ++k) {
    double plus[N], minus[N];
    for (int j = 0; j < N; ++j) plus[j] = minus[j] = q[j];
    plus[k] += h, minus[k] -= h;
    double ref = 0.0;
    for (int g = 0; g < rule.size(); ++g) {
      const double p = p1 + rule.x[g] * L;
      ref += rule.w[g] * L * m * (thetaAt(plus, p) - thetaAt(minus, p)) / (2.0 * h);
    }
    EXPECT_NEAR(Q[k], ref, 1e-8 * m * L) << "entry " << k;
  }
  EXPECT_NEAR(Q[E::kT1], 0.5 * m * L, 1e-14 * m * L);
}

// The torque's tangent (not symmetric: Q_m is no gradient) is the dual-number derivative, with the
// force's; and v . Q = loadPower (int (rdot . f + thetadot m) dp).
TEST(AleBeamShaft, DistributedTorqueHasAnExactTangentAndItsPower) {
  Fixture fx;
  const double load[4] = {0.3, -9.81, 1.7, 45.0};
  double Q[N], K[N * N];
  E::distributedLoad(fx.body, fx.q0, fx.u, load, Q);
  E::distributedLoadTangent(fx.body, fx.q0, fx.u, load, K);
  Dl ud[N], Qd[N];
  for (int k = 0; k < N; ++k) ud[k] = Dl::variable(fx.u[k], k);
  E::distributedLoad(fx.body, fx.q0, ud, load, Qd);
  double ref[N * N];
  for (int r = 0; r < N; ++r)
    for (int c = 0; c < N; ++c) ref[r * N + c] = Qd[r].d[c];
  const double s = maxAbs(ref, N * N);
  EXPECT_NE(K[E::kT1 * N + E::kP2], 0.0);
  for (int k = 0; k < N * N; ++k) EXPECT_NEAR(K[k], ref[k], 1e-12 * s) << "entry " << k;
  double vQ = 0.0;
  for (int k = 0; k < N; ++k) vQ += fx.v[k] * Q[k];
  EXPECT_NEAR(E::loadPower(fx.body, fx.q0, fx.u, fx.v, load), vQ, 1e-13 * maxAbs(Q, N) * maxAbs(fx.v, N));
}
