// Element-level verification of AncfCable2d/AncfCable3d (docs/elements/ancf-cable.md).
// requirement: the hand-derived tangents K = df/dq and D = df/dv equal the exact derivatives
// computed with dual numbers, separately (design section 2); the Taylor remainder of f falls as h^2;
// f equals dU/dq + dR/dv (energy consistency); rigid-body motion gives zero strain energy and zero
// elastic force (Gerstmayr & Shabana, Nonlinear Dyn. 45 (2006)).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "strand/elements/AncfCable.hpp"
#include "strand/math/Dual.hpp"

using namespace strand;
using namespace strand::elements;

namespace {

template <int D>
struct Fixture {
  using E = AncfCable<D>;
  static constexpr int N = E::kDof;
  CableSection sec;
  typename E::Geometry geo;
  CableShapeTable tab;
  double q0[N], u[N], v[N];  // reference (straight) coordinates, displacement, velocity
  std::mt19937 rng{42};

  // bendingRate: with damped, also the curvature-rate damping (else the axial one alone)
  explicit Fixture(bool damped, int gaussPoints = 5, bool bendingRate = true) : tab(gaussPoints) {
    sec.EA = 3.0e4;
    sec.EI = 7.0;
    sec.rhoA = 2.0;
    sec.dampAxial = damped ? 0.03 : 0.0;
    sec.dampBending = damped && bendingRate ? 0.05 : 0.0;
    geo.length = 0.7;
    geo.slopeScale[0] = 0.7;
    geo.slopeScale[1] = 0.5;
    // A deformed, curved state: reference straight element (far from the origin) plus a random displacement.
    std::uniform_real_distribution<double> r(-0.15, 0.15);
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < D; ++i) {
        double base = 0.0;
        if (i == 0) base = (a == 0) ? 10.0 : (a == 2) ? 10.0 + geo.length : geo.slopeScale[a / 2];
        q0[a * D + i] = base;
        u[a * D + i] = r(rng) * ((a % 2) ? geo.slopeScale[a / 2] : geo.length);
        v[a * D + i] = 3.0 * r(rng);
      }
  }

  template <int M>
  void dualForce(bool seedQ, double* J) const {  // J = df/du or df/dv, row-major
    using Dl = math::Dual<M>;
    Dl ud[N], vd[N], f[N];
    for (int k = 0; k < N; ++k) {
      ud[k] = seedQ ? Dl::variable(u[k], k) : Dl(u[k]);
      vd[k] = seedQ ? Dl(v[k]) : Dl::variable(v[k], k);
    }
    E::force(sec, geo, tab, q0, ud, vd, f);
    for (int r = 0; r < N; ++r)
      for (int c = 0; c < N; ++c) J[r * N + c] = f[r].d[c];
  }
};

template <class T>
class AncfCableTest : public ::testing::Test {};
using Dims = ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;
TYPED_TEST_SUITE(AncfCableTest, Dims);

double maxAbs(const double* a, int n) {
  double m = 0.0;
  for (int k = 0; k < n; ++k) m = std::max(m, std::fabs(a[k]));
  return m;
}

}  // namespace

TYPED_TEST(AncfCableTest, StiffnessAndDampingTangentsEqualDualNumberDerivatives) {
  constexpr int D = TypeParam::value;
  for (bool damped : {false, true}) {
    Fixture<D> fx(damped);
    constexpr int N = Fixture<D>::N;
    double K[N * N], Dm[N * N], f[N], fRef[N], Kad[N * N], Dad[N * N];
    AncfCable<D>::tangent(fx.sec, fx.geo, fx.tab, fx.q0, fx.u, fx.v, f, K, Dm);
    AncfCable<D>::force(fx.sec, fx.geo, fx.tab, fx.q0, fx.u, fx.v, fRef);
    fx.template dualForce<N>(true, Kad);
    fx.template dualForce<N>(false, Dad);
    const double scaleK = maxAbs(Kad, N * N), scaleF = maxAbs(fRef, N);
    for (int k = 0; k < N; ++k) EXPECT_NEAR(f[k], fRef[k], 1e-13 * scaleF);
    for (int k = 0; k < N * N; ++k) EXPECT_NEAR(K[k], Kad[k], 1e-12 * scaleK) << "K entry " << k;
    const double scaleD = std::max(maxAbs(Dad, N * N), 1e-300);
    for (int k = 0; k < N * N; ++k) EXPECT_NEAR(damped ? Dm[k] : 0.0, Dad[k], 1e-12 * scaleD) << "D entry " << k;
  }
}

// The kernels evaluate the Gauss points of an element as one padded array (SlotIntegration.hpp;
// 2..8 points are padded to 2, 4, 6, 8), and the 3D tangent without curvature-rate damping has its
// own closed form (pointTangents3d). Every point count, undamped / axial damping alone / both, with
// and without the precomputed table: tangents equal the dual-number derivatives of the force, and
// the table changes no bit.
TYPED_TEST(AncfCableTest, EveryGaussCountAndDampingGivesExactTangents) {
  constexpr int D = TypeParam::value;
  using E = AncfCable<D>;
  constexpr int N = Fixture<D>::N;
  for (int gauss = 2; gauss <= 8; ++gauss)
    for (int mode = 0; mode < 3; ++mode) {
      Fixture<D> fx(mode > 0, gauss, mode == 2);
      double K[N * N], Dm[N * N], f[N], Kad[N * N], Dad[N * N];
      E::tangent(fx.sec, fx.geo, fx.tab, fx.q0, fx.u, fx.v, f, K, Dm);
      fx.template dualForce<N>(true, Kad);
      fx.template dualForce<N>(false, Dad);
      const double scaleK = maxAbs(Kad, N * N), scaleD = std::max(maxAbs(Dad, N * N), 1e-300);
      for (int k = 0; k < N * N; ++k) {
        EXPECT_NEAR(K[k], Kad[k], 1e-12 * scaleK) << gauss << " points, mode " << mode << ", K entry " << k;
        EXPECT_NEAR(Dm[k], Dad[k], 1e-12 * scaleD) << gauss << " points, mode " << mode << ", D entry " << k;
      }
      const CablePointTable table = E::pointTable(fx.geo, fx.tab);
      EXPECT_EQ(table.padded, gauss + gauss % 2);
      typename E::Geometry tabulated = fx.geo;
      tabulated.points = &table;
      tabulated.pointsOf = &fx.tab;
      double Kt[N * N], Dt[N * N], ft[N], fForce[N];
      E::tangent(fx.sec, tabulated, fx.tab, fx.q0, fx.u, fx.v, ft, Kt, Dt);
      E::force(fx.sec, tabulated, fx.tab, fx.q0, fx.u, fx.v, fForce);
      for (int k = 0; k < N; ++k) {
        EXPECT_EQ(ft[k], f[k]);
        EXPECT_NEAR(fForce[k], f[k], 1e-13 * maxAbs(f, N));
      }
      for (int k = 0; k < N * N; ++k) {
        EXPECT_EQ(Kt[k], K[k]);
        EXPECT_EQ(Dt[k], Dm[k]);
      }
      EXPECT_EQ(E::strainEnergy(fx.sec, tabulated, fx.tab, fx.q0, fx.u), E::strainEnergy(fx.sec, fx.geo, fx.tab, fx.q0, fx.u));
      if (mode == 0) {  // and the force is the gradient of the strain energy
        using Dl = math::Dual<N>;
        Dl ud[N];
        for (int k = 0; k < N; ++k) ud[k] = Dl::variable(fx.u[k], k);
        const Dl U = E::strainEnergy(fx.sec, tabulated, fx.tab, fx.q0, ud);
        for (int k = 0; k < N; ++k) EXPECT_NEAR(f[k], U.d[k], 1e-12 * maxAbs(f, N)) << gauss << " points";
      }
    }
}

TYPED_TEST(AncfCableTest, TaylorRemainderFallsAsHSquared) {
  constexpr int D = TypeParam::value;
  Fixture<D> fx(true);
  constexpr int N = Fixture<D>::N;
  double K[N * N], Dm[N * N], f0[N], dir[N], dirV[N];
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < N; ++k) { dir[k] = 0.1 * u(fx.rng); dirV[k] = u(fx.rng); }
  AncfCable<D>::tangent(fx.sec, fx.geo, fx.tab, fx.q0, fx.u, fx.v, f0, K, Dm);
  // Perturb q and v together: f(q + h dq, v + h dv) - f - h (K dq + D dv) = O(h^2).
  double prev = 0.0;
  for (int level = 0; level < 4; ++level) {
    const double h = 1e-2 / std::pow(2.0, level);
    double up[N], vp[N], fp[N];
    for (int k = 0; k < N; ++k) { up[k] = fx.u[k] + h * dir[k]; vp[k] = fx.v[k] + h * dirV[k]; }
    AncfCable<D>::force(fx.sec, fx.geo, fx.tab, fx.q0, up, vp, fp);
    double err = 0.0;
    for (int r = 0; r < N; ++r) {
      double lin = f0[r];
      for (int c = 0; c < N; ++c) lin += h * (K[r * N + c] * dir[c] + Dm[r * N + c] * dirV[c]);
      err = std::max(err, std::fabs(fp[r] - lin));
    }
    if (level > 0) {
      EXPECT_NEAR(std::log2(prev / err), 2.0, 0.1) << "h=" << h;
    }
    prev = err;
  }
}

TYPED_TEST(AncfCableTest, ForceIsGradientOfEnergyPlusDissipation) {
  constexpr int D = TypeParam::value;
  Fixture<D> fx(true);
  constexpr int N = Fixture<D>::N;
  using Dl = math::Dual<N>;
  Dl ud[N], vd[N], uc[N];
  for (int k = 0; k < N; ++k) {
    ud[k] = Dl::variable(fx.u[k], k);
    vd[k] = Dl::variable(fx.v[k], k);
    uc[k] = Dl(fx.u[k]);
  }
  const Dl U = AncfCable<D>::strainEnergy(fx.sec, fx.geo, fx.tab, fx.q0, ud);
  const Dl R = AncfCable<D>::dissipation(fx.sec, fx.geo, fx.tab, fx.q0, uc, vd);
  double f[N];
  AncfCable<D>::force(fx.sec, fx.geo, fx.tab, fx.q0, fx.u, fx.v, f);
  const double scale = maxAbs(f, N);
  for (int k = 0; k < N; ++k) EXPECT_NEAR(f[k], U.d[k] + R.d[k], 1e-12 * scale);
}

TYPED_TEST(AncfCableTest, RigidBodyMotionIsStressFree) {
  constexpr int D = TypeParam::value;
  using E = AncfCable<D>;
  constexpr int N = E::kDof;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  CableSection sec{2.0e7, 30.0, 1.0, 0.01, 0.02};
  CableShapeTable tab(5);
  for (int trial = 0; trial < 20; ++trial) {
    typename E::Geometry geo;
    geo.length = 0.5 + 0.4 * std::fabs(u(rng));
    geo.slopeScale[0] = geo.slopeScale[1] = (trial % 2) ? geo.length : 1.0;
    // Random rotation (2D: angle; 3D: unit quaternion), large translation, rigid velocity.
    double R[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    if (D == 2) {
      const double a = M_PI * u(rng);
      R[0][0] = std::cos(a); R[0][1] = -std::sin(a); R[1][0] = std::sin(a); R[1][1] = std::cos(a);
    } else {
      double e[4] = {u(rng), u(rng), u(rng), u(rng)};
      const double n = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + e[3] * e[3]);
      for (double& x : e) x /= n;
      const double w = e[0], x = e[1], y = e[2], z = e[3];
      const double Q[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                              {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                              {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) R[i][j] = Q[i][j];
    }
    double t[3] = {100 * u(rng), 100 * u(rng), 100 * u(rng)}, omega[3] = {u(rng), u(rng), u(rng)};
    double q[N], q0[N], u[N], v[N];
    for (int a = 0; a < 4; ++a) {
      const bool slope = a % 2;
      const double x = (a < 2) ? 0.0 : geo.length;
      for (int i = 0; i < D; ++i) {
        // straight reference along x: r = (x, 0, 0), sigma r' = (sigma, 0, 0)
        q0[a * D + i] = (i == 0) ? (slope ? geo.slopeScale[a / 2] : x) : 0.0;
        q[a * D + i] = slope ? R[i][0] * geo.slopeScale[a / 2] : R[i][0] * x + t[i];
        u[a * D + i] = q[a * D + i] - q0[a * D + i];
      }
      // rigid velocity: v = w x (r - t) (2D: w_z only), same formula for slope vectors
      double rr[3] = {0, 0, 0};
      for (int i = 0; i < D; ++i) rr[i] = q[a * D + i] - (slope ? 0.0 : t[i]);
      if (D == 2) {
        v[a * D + 0] = -omega[2] * rr[1];
        v[a * D + 1] = omega[2] * rr[0];
      } else {
        v[a * D + 0] = omega[1] * rr[2] - omega[2] * rr[1];
        v[a * D + 1] = omega[2] * rr[0] - omega[0] * rr[2];
        v[a * D + 2] = omega[0] * rr[1] - omega[1] * rr[0];
      }
    }
    double f[N];
    E::force(sec, geo, tab, q0, u, v, f);
    EXPECT_NEAR(E::strainEnergy(sec, geo, tab, q0, u), 0.0, 1e-18 * sec.EA);
    EXPECT_NEAR(E::dissipation(sec, geo, tab, q0, u, v), 0.0, 1e-20 * sec.EA);
    for (int k = 0; k < N; ++k) EXPECT_NEAR(f[k], 0.0, 1e-13 * sec.EA) << "trial " << trial;
  }
}
