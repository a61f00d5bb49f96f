// Element-level verification of the variable-length ALE cable AleCable2d/3d (seed 000; Hong, Tang &
// Ren 2011), issue 35:
//  - the elastic tangent equals the dual-number derivative of the force (positions, slopes and the
//    material coordinates p1, p2), f = dU/du, rigid motions with unstretched spacing give no force;
//  - with p1, p2 held, the elastic force equals the Lagrangian cable's (AncfCable) to round-off;
//  - the inertial force F = rho A int S^T rddot dp (d'Alembert over the element's material, seed 000
//    Eq. 27-29) differs from Lagrange's d/dt dT/dv - dT/dq of its kinetic energy
//    T = 1/2 int_{p1}^{p2} rho A |rdot|^2 dp only by the momentum that flows through its ends
//    (Leibniz's rule on the moving limits): per coordinate k,
//      dT-terms - F_k = rho A [p2dot rdot(p2).S_k(p2) - p1dot rdot(p1).S_k(p1)]
//                       - rho A/2 [|rdot(p2)|^2 delta_{k,p2} - |rdot(p1)|^2 delta_{k,p1}],
//    with rdot(p_i) = v_ri - r_i' p_idot and S_k(p_i) the nodal position (1) or, for p_i, -r_i'.
//    Between two elements these terms cancel, so the assembled mesh obeys Lagrange's equations but
//    at its outer ends, where material enters or leaves;
//  - M = dF/da is symmetric, and the tangents dF/da, dF/dv, dF/du equal dual-number derivatives;
//  - with p1, p2 at rest, F = (the cable's consistent mass) a.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "strand/elements/AleCable.hpp"
#include "strand/math/Dual.hpp"

using namespace strand;
using namespace strand::elements;

namespace {

template <int D>
struct Fixture {
  using E = AleCable<D>;
  static constexpr int N = E::kDof;
  typename E::Body body;
  double q0[N], u[N], v[N], a[N];
  std::mt19937 rng{11};

  explicit Fixture(bool moving = true) {
    SectionValues s;
    s.numbers = {{"E", 2e7}, {"A", 1e-3}, {"I", 3e-7}, {"rho", 1000.0}};
    body = E::body(s, {0.7, 1.0, 5});
    std::uniform_real_distribution<double> r(-0.1, 0.1);
    for (int k = 0; k < N; ++k) q0[k] = u[k] = v[k] = a[k] = 0.0;
    // straight element along x at x = 3, material coordinates 5 and 5.7 (unstretched)
    q0[E::slotIndex(0)] = 3.0;
    q0[E::slotIndex(1)] = 1.0;
    q0[E::slotIndex(2)] = 3.7;
    q0[E::slotIndex(3)] = 1.0;
    q0[E::kP1] = 5.0;
    q0[E::kP2] = 5.7;
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < D; ++i) {
        const int s = E::slotIndex(k) + i;
        u[s] = r(rng) * (k % 2 == 0 ? 0.7 : 1.0);
        v[s] = 10.0 * r(rng);
        a[s] = 100.0 * r(rng);
      }
    if (moving) {
      u[E::kP1] = 0.03;
      u[E::kP2] = -0.05;
      v[E::kP1] = 1.5;
      v[E::kP2] = 2.5;
      a[E::kP1] = -3.0;
      a[E::kP2] = 7.0;
    }
  }
};

template <class T>
class AleCableTest : public ::testing::Test {};
using Dims = ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;
TYPED_TEST_SUITE(AleCableTest, Dims);

double maxAbs(const double* x, int n) {
  double m = 0.0;
  for (int k = 0; k < n; ++k) m = std::max(m, std::fabs(x[k]));
  return m;
}

}  // namespace

// The hand-derived tangent's f and K against the dual-number derivatives of force() and
// strainEnergy() for `body` at the fixture's state (label: what the failure messages name).
template <int D>
void checkElasticDerivatives(const typename AleCable<D>::Body& body, const Fixture<D>& fx, const std::string& label) {
  using E = AleCable<D>;
  constexpr int N = E::kDof;
  using Dl = math::Dual<N>;
  const typename E::Element el = E::element(body, nullptr);
  double f[N], K[N * N];
  E::tangent(body, el, fx.q0, fx.u, nullptr, f, K, nullptr);
  Dl ud[N], fd[N];
  for (int k = 0; k < N; ++k) ud[k] = Dl::variable(fx.u[k], k);
  E::force(body, el, fx.q0, ud, static_cast<const Dl*>(nullptr), fd);
  const Dl U = E::strainEnergy(body, el, fx.q0, ud);
  double Kad[N * N], fv[N];
  for (int r = 0; r < N; ++r) {
    fv[r] = fd[r].v;
    for (int c = 0; c < N; ++c) Kad[r * N + c] = fd[r].d[c];
  }
  const double sK = maxAbs(Kad, N * N), sF = maxAbs(f, N);
  for (int k = 0; k < N; ++k) {
    EXPECT_NEAR(f[k], U.d[k], 1e-11 * sF) << label << "f = dU/du, entry " << k;
    EXPECT_NEAR(fv[k], U.d[k], 1e-11 * sF) << label << "force() = dU/du, entry " << k;
    EXPECT_NEAR(f[k], fv[k], 1e-12 * sF) << label << "the tangent's f, entry " << k;
  }
  for (int k = 0; k < N * N; ++k) EXPECT_NEAR(K[k], Kad[k], 1e-11 * sK) << label << "K entry " << k;
}

TYPED_TEST(AleCableTest, ElasticTangentIsTheExactDerivativeAndTheForceTheEnergyGradient) {
  constexpr int D = TypeParam::value;
  Fixture<D> fx;
  checkElasticDerivatives<D>(fx.body, fx, "");
}

// The force evaluates its points as arrays padded to an even count (AleCableKernels.hpp): every
// elastic rule of 2 to 8 points (odd counts padded) gives the energy's gradient, and the pointwise
// hand-derived tangent is its derivative.
TYPED_TEST(AleCableTest, EveryPointCountGivesTheEnergyGradientAndItsTangent) {
  constexpr int D = TypeParam::value;
  Fixture<D> fx;
  for (int points = 2; points <= 8; ++points) {
    SectionValues s;
    s.numbers = {{"E", 2e7}, {"A", 1e-3}, {"I", 3e-7}, {"rho", 1000.0}};
    checkElasticDerivatives<D>(AleCable<D>::body(s, {0.7, 1.0, points}), fx, std::to_string(points) + " points, ");
  }
}

// The dynamic residual's one pass over the inertia's points: inertiaLessLoad = inertia - Q_f.
TYPED_TEST(AleCableTest, InertiaLessLoadIsTheInertiaLessTheDistributedLoad) {
  constexpr int D = TypeParam::value;
  using E = AleCable<D>;
  constexpr int N = E::kDof;
  Fixture<D> fx;
  const typename E::Element el = E::element(fx.body, nullptr);
  const double load[3] = {0.3, -9.81, D == 3 ? 1.7 : 0.0};
  double F[N], Q[N], both[N];
  E::inertia(fx.body, el, fx.q0, fx.u, fx.v, fx.a, F);
  E::distributedLoad(fx.body, fx.q0, fx.u, load, Q);
  E::inertiaLessLoad(fx.body, el, fx.q0, fx.u, fx.v, fx.a, load, both);
  const double s = std::max(maxAbs(F, N), maxAbs(Q, N));
  for (int k = 0; k < N; ++k) EXPECT_NEAR(both[k], F[k] - Q[k], 1e-14 * s) << "entry " << k;
}

// The energy monitor's load power from the material velocity: loadPower = v . Q_f.
TYPED_TEST(AleCableTest, LoadPowerIsTheVelocitiesDotTheDistributedLoad) {
  constexpr int D = TypeParam::value;
  using E = AleCable<D>;
  constexpr int N = E::kDof;
  Fixture<D> fx;
  const double load[3] = {0.3, -9.81, D == 3 ? 1.7 : 0.0};
  double Q[N], vQ = 0.0;
  E::distributedLoad(fx.body, fx.q0, fx.u, load, Q);
  for (int k = 0; k < N; ++k) vQ += fx.v[k] * Q[k];
  EXPECT_NEAR(E::loadPower(fx.body, fx.q0, fx.u, fx.v, load), vQ, 1e-13 * maxAbs(Q, N) * maxAbs(fx.v, N));
}

TYPED_TEST(AleCableTest, WithTheMaterialCoordinatesHeldItIsTheLagrangianCable) {
  constexpr int D = TypeParam::value;
  using E = AleCable<D>;
  using C = AncfCable<D>;
  Fixture<D> fx(false);
  double f[E::kDof];
  E::force(fx.body, E::element(fx.body, nullptr), fx.q0, fx.u, static_cast<const double*>(nullptr), f);
  CableSection sec{2e7 * 1e-3, 2e7 * 3e-7, 1000.0 * 1e-3, 0.0, 0.0};
  typename C::Geometry geo;
  geo.length = 0.7;
  const CableShapeTable tab(5);
  double q0c[C::kDof], uc[C::kDof], fc[C::kDof];
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < D; ++i) {
      q0c[k * D + i] = fx.q0[E::slotIndex(k) + i];
      uc[k * D + i] = fx.u[E::slotIndex(k) + i];
    }
  C::force(sec, geo, tab, q0c, uc, static_cast<const double*>(nullptr), fc);
  const double s = maxAbs(fc, C::kDof);
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < D; ++i) EXPECT_NEAR(f[E::slotIndex(k) + i], fc[k * D + i], 1e-12 * s);
}

TYPED_TEST(AleCableTest, InertiaIsLagrangesEquationPlusTheMomentumFluxThroughTheEnds) {
  constexpr int D = TypeParam::value;
  using E = AleCable<D>;
  constexpr int N = E::kDof;
  using Dl = math::Dual<N>;
  Fixture<D> fx;
  const typename E::Element el = E::element(fx.body, nullptr);
  // dT/dv and dT/du exactly (dual numbers), as functions of (u, v)
  auto gradients = [&](const double* u, const double* v, double* Tv, double* Tu) {
    Dl ud[N], vd[N];
    for (int k = 0; k < N; ++k) ud[k] = Dl(u[k]), vd[k] = Dl::variable(v[k], k);
    const Dl T1 = E::kineticEnergy(fx.body, fx.q0, ud, vd);
    for (int k = 0; k < N; ++k) Tv[k] = T1.d[k], ud[k] = Dl::variable(u[k], k), vd[k] = Dl(v[k]);
    const Dl T2 = E::kineticEnergy(fx.body, fx.q0, ud, vd);
    for (int k = 0; k < N; ++k) Tu[k] = T2.d[k];
  };
  // d/dt dT/dv along (u + v t, v + a t) by a central difference of the exact gradient
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
  // the momentum flux through the element's ends
  double flux[N] = {}, q[N];
  for (int k = 0; k < N; ++k) q[k] = fx.q0[k] + fx.u[k];
  const double rhoA = 1.0;  // rho A of the fixture: 1000 * 1e-3
  for (int node = 0; node < 2; ++node) {
    const int pos = E::slotIndex(2 * node), slope = E::slotIndex(2 * node + 1), p = node == 0 ? E::kP1 : E::kP2;
    const double sign = node == 0 ? -1.0 : 1.0, pdot = fx.v[p];
    double rd[D], rd2 = 0.0;
    for (int i = 0; i < D; ++i) {
      rd[i] = fx.v[pos + i] - q[slope + i] * pdot;
      rd2 += rd[i] * rd[i];
    }
    for (int i = 0; i < D; ++i) {
      flux[pos + i] += sign * rhoA * pdot * rd[i];
      flux[p] += sign * rhoA * pdot * rd[i] * (-q[slope + i]);
    }
    flux[p] -= sign * 0.5 * rhoA * rd2;
  }
  const double s = maxAbs(F, N);
  for (int k = 0; k < N; ++k)
    EXPECT_NEAR(F[k] + flux[k], (Tvp[k] - Tvm[k]) / (2.0 * h) - Tu[k], 1e-7 * s) << "entry " << k;
}

TYPED_TEST(AleCableTest, InertiaTangentsAreTheExactDerivatives) {
  constexpr int D = TypeParam::value;
  using E = AleCable<D>;
  constexpr int N = E::kDof;
  using Dl = math::Dual<N>;
  Fixture<D> fx;
  const typename E::Element el = E::element(fx.body, nullptr);
  double F[N], M[N * N], C[N * N], K[N * N];
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
    const double s = std::max(maxAbs(ref, N * N), 1e-300);
    for (int k = 0; k < N * N; ++k) EXPECT_NEAR(mine[k], ref[k], 1e-11 * s) << "matrix " << which << " entry " << k;
  }
  for (int r = 0; r < N; ++r)
    for (int c = 0; c < N; ++c) EXPECT_NEAR(M[r * N + c], M[c * N + r], 1e-12 * maxAbs(M, N * N));
}

TYPED_TEST(AleCableTest, MaterialAtRestHasTheCablesConsistentMass) {
  constexpr int D = TypeParam::value;
  using E = AleCable<D>;
  using C = AncfCable<D>;
  Fixture<D> fx(false);
  double F[E::kDof];
  E::inertia(fx.body, E::element(fx.body, nullptr), fx.q0, fx.u, fx.v, fx.a, F);
  CableSection sec{0, 0, 1.0, 0, 0};
  typename C::Geometry geo;
  geo.length = 0.7;
  double Mc[C::kDof * C::kDof];
  C::mass(sec, geo, CableShapeTable(4), Mc);
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < D; ++i) {
      double ref = 0.0;
      for (int l = 0; l < 4; ++l)
        for (int j = 0; j < D; ++j) ref += Mc[(k * D + i) * C::kDof + l * D + j] * fx.a[E::slotIndex(l) + j];
      EXPECT_NEAR(F[E::slotIndex(k) + i], ref, 1e-12 * (1.0 + std::fabs(ref)));
    }
}

// requirement: a force per unit length f on the moving material gives Q_f = int S^T f dp, the
// virtual work of f on the element's material (Eq. 43-44, with the p columns of S); it depends on
// the coordinates, and its tangent is the dual-number derivative.
TYPED_TEST(AleCableTest, DistributedLoadIsThePotentialsGradientWithAnExactTangent) {
  constexpr int D = TypeParam::value;
  using E = AleCable<D>;
  constexpr int N = E::kDof;
  using Dl = math::Dual<N>;
  Fixture<D> fx;
  const double f[3] = {0.3, -9.81, D == 3 ? 1.7 : 0.0};
  double Q[N], K[N * N];
  E::distributedLoad(fx.body, fx.q0, fx.u, f, Q);
  E::distributedLoadTangent(fx.body, fx.q0, fx.u, f, K);
  Dl ud[N], Qd[N];
  for (int k = 0; k < N; ++k) ud[k] = Dl::variable(fx.u[k], k);
  E::distributedLoad(fx.body, fx.q0, ud, f, Qd);
  double ref[N * N];
  for (int r = 0; r < N; ++r)
    for (int c = 0; c < N; ++c) ref[r * N + c] = Qd[r].d[c];
  const double s = maxAbs(ref, N * N);
  for (int k = 0; k < N * N; ++k) EXPECT_NEAR(K[k], ref[k], 1e-12 * s) << "entry " << k;
  for (int k = 0; k < N; ++k) EXPECT_NEAR(Q[k], Qd[k].v, 1e-14 * maxAbs(Q, N));
}

// requirement (seed 000 Eq. 31-37): the Kelvin-Voigt damping acts on the material's strain rates.
// (1) With the material held (p1, p2 at rest) it is the Lagrangian cable's damping force.
// (2) A rigid rotation of the material, whatever the nodes do: the element's field (a cubic in p)
//     turns rigidly at omega while the nodes slide through the material at p1dot != p2dot (node
//     velocities omega x r_i + r_i' p_idot, slope velocities omega x r_i' + r_i'' p_idot; the turned
//     cubic restricted to the moving interval is again the Hermite cubic of the moving nodes). No
//     material strain rate: the damped force equals the undamped one to round-off. This checks the
//     material derivative's xidot and Ldot terms, r''' included.
TYPED_TEST(AleCableTest, DampingActsOnTheMaterialStrainRates) {
  constexpr int D = TypeParam::value;
  using E = AleCable<D>;
  using C = AncfCable<D>;
  constexpr int N = E::kDof;
  SectionValues s;
  s.numbers = {{"E", 2e7}, {"A", 1e-3}, {"I", 3e-7}, {"rho", 1000.0}, {"damping_axial", 0.03}, {"damping_bending", 0.05}};
  {  // (1)
    Fixture<D> fx(false);
    fx.body = E::body(s, {0.7, 1.0, 5});
    ASSERT_TRUE(E::velocityDependent(fx.body));
    double f[N];
    E::force(fx.body, E::element(fx.body, nullptr), fx.q0, fx.u, fx.v, f);
    CableSection sec{2e7 * 1e-3, 2e7 * 3e-7, 1.0, 0.03, 0.05};
    typename C::Geometry geo;
    geo.length = 0.7;
    const CableShapeTable tab(5);
    double q0c[C::kDof], uc[C::kDof], vc[C::kDof], fc[C::kDof];
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < D; ++i) {
        q0c[k * D + i] = fx.q0[E::slotIndex(k) + i];
        uc[k * D + i] = fx.u[E::slotIndex(k) + i];
        vc[k * D + i] = fx.v[E::slotIndex(k) + i];
      }
    C::force(sec, geo, tab, q0c, uc, vc, fc);
    const double sc = maxAbs(fc, C::kDof);
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < D; ++i) EXPECT_NEAR(f[E::slotIndex(k) + i], fc[k * D + i], 1e-12 * sc);
  }
  {  // (2)
    Fixture<D> fx(true);
    // 3D: the cable's bending damping acts on the rate of the curvature vector c = r' x r'', which a
    // rigid rotation turns (dc = omega x c), so only the axial damping is frame-indifferent there
    if (D == 3) s.set("damping_bending", 0.0);
    fx.body = E::body(s, {0.7, 1.0, 5});
    double q[N], v[N] = {};
    for (int k = 0; k < N; ++k) q[k] = fx.q0[k] + fx.u[k];
    const double w[3] = {D == 3 ? 0.7 : 0.0, D == 3 ? -0.4 : 0.0, 1.3};  // omega
    auto cross = [&](const double* r, double* out) {
      double r3[3] = {r[0], r[1], D == 3 ? r[2] : 0.0}, o[3];
      o[0] = w[1] * r3[2] - w[2] * r3[1];
      o[1] = w[2] * r3[0] - w[0] * r3[2];
      o[2] = w[0] * r3[1] - w[1] * r3[0];
      for (int i = 0; i < D; ++i) out[i] = o[i];
    };
    const double L = q[E::kP2] - q[E::kP1], pdot[2] = {1.5, -0.8};
    const double h2[2][4] = {{-6, -4, 6, -2}, {6, 2, -6, 4}};  // h_k'' at xi = 0 and 1
    for (int node = 0; node < 2; ++node) {
      const int pos = E::slotIndex(2 * node), slope = E::slotIndex(2 * node + 1);
      double r2[D];  // r'' at the node
      for (int i = 0; i < D; ++i)
        r2[i] = (h2[node][0] * q[E::slotIndex(0) + i] + h2[node][2] * q[E::slotIndex(2) + i]) / (L * L) +
                (h2[node][1] * q[E::slotIndex(1) + i] + h2[node][3] * q[E::slotIndex(3) + i]) / L;
      double wr[D], wt[D];
      cross(&q[pos], wr);
      cross(&q[slope], wt);
      for (int i = 0; i < D; ++i) {
        v[pos + i] = wr[i] + q[slope + i] * pdot[node];
        v[slope + i] = wt[i] + r2[i] * pdot[node];
      }
      v[node == 0 ? E::kP1 : E::kP2] = pdot[node];
    }
    double fd[N], f0[N];
    const typename E::Element el = E::element(fx.body, nullptr);
    E::force(fx.body, el, fx.q0, fx.u, v, fd);
    E::force(fx.body, el, fx.q0, fx.u, static_cast<const double*>(nullptr), f0);
    // the damping force's scale: the same velocities with the rotation left out (pure sliding, which strains)
    double vs[N], fs[N];
    for (int k = 0; k < N; ++k) vs[k] = 0.0;
    vs[E::kP1] = 1.0;
    E::force(fx.body, el, fx.q0, fx.u, vs, fs);
    double scale = 0.0;
    for (int k = 0; k < N; ++k) scale = std::max(scale, std::fabs(fs[k] - f0[k]));
    EXPECT_GT(scale, 1e-3 * maxAbs(f0, N)) << "sliding the material through a bent element strains it";
    for (int k = 0; k < N; ++k) EXPECT_NEAR(fd[k], f0[k], 1e-10 * maxAbs(f0, N)) << "entry " << k;
  }
}

// The point arrays hold at most 8 points (the scene reader allows 2-8): more is an error, not an
// overrun.
TEST(AlePointArrays, RefuseMoreThanEightPoints) {
  EXPECT_NO_THROW(AlePointArrays::of(math::gaussLegendre(8)));
  math::QuadratureRule nine;  // (gaussLegendre stops at 8 itself)
  nine.x.assign(9, 0.5);
  nine.w.assign(9, 1.0 / 9.0);
  EXPECT_THROW(AlePointArrays::of(nine), std::invalid_argument);
}
