// Every element kind of the registry (elements::AllKinds), through the kind contract only
// (ElementKind.hpp; docs/architecture.md, "Element kinds"), with every formulation option:
//  - the hand-derived tangents K = df/du and D = df/dv equal the exact derivatives computed with
//    dual numbers (design section 2), and the Taylor remainder of f falls as h^2;
//  - the elastic force is the gradient of the strain energy;
//  - rigid motions (any rotation and translation of the straight initial element) give zero strain
//    energy and zero force (Gerstmayr & Shabana, Nonlinear Dyn. 45 (2006));
//  - the slot mass gives the exact kinetic energy of every rigid velocity field: the mass rho A l,
//    the centre of mass and the moment of inertia rho A (l^3/12 + l x_c^2) + rho I l (the section's
//    rotary inertia, for the shear-deformable kinds whose cross-section vector carries it).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "strand/elements/ElementKinds.hpp"
#include "strand/math/Dual.hpp"

using namespace strand;
using namespace strand::elements;

namespace {

// The section of each kind's test, with damping when asked, and its rotary inertia rho I.
template <class K>
constexpr bool isAle() {
  return std::is_same_v<K, AleCable2d> || std::is_same_v<K, AleCable3d> || std::is_same_v<K, AleBeamShaft3d>;
}

// Whether the kind has Kelvin-Voigt damping to test.
template <class K>
constexpr bool hasDamping() {
  return true;
}

template <class K>
SectionValues sectionOf(bool damped, double* rotary) {
  SectionValues v;
  if constexpr (std::is_same_v<K, AleBeamShaft3d>) {
    v.numbers = {{"E", 2e7}, {"nu", 0.3}, {"rho", 1000.0}, {"radius", 0.02}};
    v.set("damping_axial", damped ? 0.03 : 0.0);
    v.set("damping_bending", damped ? 0.05 : 0.0);
    v.set("damping_torsion", damped ? 0.02 : 0.0);
    *rotary = 0.0;
  } else if constexpr (isAle<K>()) {
    v.numbers = {{"E", 2e7}, {"A", 1e-3}, {"I", 3e-7}, {"rho", 1000.0}};
    v.set("damping_axial", damped ? 0.03 : 0.0);
    v.set("damping_bending", damped ? 0.05 : 0.0);
    *rotary = 0.0;
  } else if constexpr (std::is_same_v<K, AncfCable2d> || std::is_same_v<K, AncfCable3d>) {
    v.numbers = {{"E", 2e7}, {"A", 1e-3}, {"I", 3e-7}, {"rho", 1000.0}};
    v.set("damping_axial", damped ? 0.03 : 0.0);
    v.set("damping_bending", damped ? 0.05 : 0.0);
    *rotary = 0.0;
  } else {
    v.numbers = {{"E", 2e7}, {"nu", 0.3}, {"rho", 1000.0}, {"width", 0.05}, {"height", 0.02}};
    v.set("damping", damped ? 0.01 : 0.0);
    *rotary = 1000.0 * 0.05 * std::pow(0.02, 3) / 12.0;
  }
  return v;
}

// Every combination of the kind's formulation options (one empty set for a kind without options).
template <class K>
std::vector<std::map<std::string, std::string>> optionSets() {
  std::vector<std::map<std::string, std::string>> sets{{}};
  for (int k = 0; k < K::kOptionCount; ++k) {
    std::vector<std::map<std::string, std::string>> next;
    for (const auto& s : sets)
      for (int v = 0; v < OptionKey::kMaxValues && K::kOptions[k].values[v]; ++v) {
        auto t = s;
        t[K::kOptions[k].name] = K::kOptions[k].values[v];
        next.push_back(t);
      }
    sets = next;
  }
  return sets;
}

std::string describe(const std::map<std::string, std::string>& options) {
  std::string s;
  for (const auto& [k, v] : options) s += k + "=" + v + " ";
  return s;
}

double maxAbs(const double* a, int n) {
  double m = 0.0;
  for (int k = 0; k < n; ++k) m = std::max(m, std::fabs(a[k]));
  return m;
}

template <class K>
struct Fixture {
  static constexpr int D = K::kDim, B = K::kBlocks, N = K::kDof;
  SectionValues section;
  BodyDiscretization disc;
  typename K::Body body;
  double rotary = 0.0;
  double q0[N], u[N], v[N];  // straight initial element far from the origin, displacement, velocity
  std::mt19937 rng{7};

  Fixture(bool damped, const std::map<std::string, std::string>& options, double gradientScale = 1.0) {
    section = sectionOf<K>(damped, &rotary);
    section.options = options;
    disc = {0.7, gradientScale, 5};
    body = K::body(section, disc);
    std::uniform_real_distribution<double> r(-0.1, 0.1);
    for (int a = 0; a < B; ++a) {
      const BlockRole role = K::kNodeLayout[a % K::kBlocksPerNode];
      const int node = a / K::kBlocksPerNode;
      for (int i = 0; i < D; ++i) {
        double base = 0.0;
        if (role == BlockRole::Position) base = i == 0 ? 10.0 + node * disc.elementLength : (i == 1 ? -3.0 : 0.0);
        if (role == BlockRole::AxialGradient && i == 0) base = disc.gradientScale;
        if (role == BlockRole::TransverseGradient && i == 1) base = 1.0;
        if (isMaterialBlock(role) && i == 0) base = 2.0 + node * disc.elementLength;
        const bool padding = i >= usedComponents(role, D);  // held at zero
        q0[a * D + i] = base;
        u[a * D + i] = padding ? 0.0 : r(rng) * (role == BlockRole::Position ? disc.elementLength : 0.1);
        v[a * D + i] = padding ? 0.0 : 3.0 * r(rng);
      }
    }
  }

  typename K::Element element() const { return K::element(body, nullptr); }

  template <int M>
  void dualForce(bool seedU, double* J) const {  // J = df/du or df/dv, row-major
    using Dl = math::Dual<M>;
    Dl ud[N], vd[N], f[N];
    for (int k = 0; k < N; ++k) {
      ud[k] = seedU ? Dl::variable(u[k], k) : Dl(u[k]);
      vd[k] = seedU ? Dl(v[k]) : Dl::variable(v[k], k);
    }
    K::force(body, element(), q0, ud, vd, f);
    for (int r = 0; r < N; ++r)
      for (int c = 0; c < N; ++c) J[r * N + c] = f[r].d[c];
  }
};

template <class K>
class ElementKindTest : public ::testing::Test {};
using Kinds = ::testing::Types<AncfCable2d, AncfCable3d, AncfBeam2dShear, AncfBeam2dLinear, AleCable2d, AleCable3d,
                               AleBeamShaft3d>;
TYPED_TEST_SUITE(ElementKindTest, Kinds);

}  // namespace

TEST(ElementKinds, TheTestCoversEveryRegisteredKind) { EXPECT_EQ(AllKinds::size, 7); }

TYPED_TEST(ElementKindTest, TangentsEqualDualNumberDerivatives) {
  using K = TypeParam;
  constexpr int N = K::kDof;
  for (const auto& options : optionSets<K>())
    for (bool damped : {false, true})
      for (double sigma : {1.0, 0.7}) {
        if ((damped && !hasDamping<K>()) || (sigma != 1.0 && isAle<K>())) continue;  // ALE: slopes are dr/dp
        Fixture<K> fx(damped, options, sigma);
        double Kt[N * N], Dt[N * N], f[N], fRef[N], Kad[N * N], Dad[N * N];
        K::tangent(fx.body, fx.element(), fx.q0, fx.u, fx.v, f, Kt, Dt);
        K::force(fx.body, fx.element(), fx.q0, fx.u, fx.v, fRef);
        fx.template dualForce<N>(true, Kad);
        fx.template dualForce<N>(false, Dad);
        const double scaleK = maxAbs(Kad, N * N), scaleF = maxAbs(fRef, N);
        const double scaleD = std::max(maxAbs(Dad, N * N), 1e-300);
        const std::string where = describe(options) + (damped ? "damped" : "undamped") + " sigma " + std::to_string(sigma);
        EXPECT_EQ(K::velocityDependent(fx.body), damped) << where;
        for (int k = 0; k < N; ++k) EXPECT_NEAR(f[k], fRef[k], 1e-13 * scaleF) << where;
        for (int k = 0; k < N * N; ++k) EXPECT_NEAR(Kt[k], Kad[k], 1e-12 * scaleK) << where << " K entry " << k;
        for (int k = 0; k < N * N; ++k) EXPECT_NEAR(damped ? Dt[k] : 0.0, Dad[k], 1e-12 * scaleD) << where << " D entry " << k;
      }
}

// |f(u + h w) - f(u) - h K w| falls as h^2 (rate 2) until round-off.
TYPED_TEST(ElementKindTest, TaylorRemainderOfTheForceFallsAsTheSquare) {
  using K = TypeParam;
  constexpr int N = K::kDof;
  for (const auto& options : optionSets<K>()) {
    Fixture<K> fx(false, options);
    double w[N], Kt[N * N], f0[N], Kw[N] = {};
    std::uniform_real_distribution<double> r(-1.0, 1.0);
    for (double& x : w) x = r(fx.rng) * 0.1;
    K::tangent(fx.body, fx.element(), fx.q0, fx.u, nullptr, f0, Kt, nullptr);
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) Kw[i] += Kt[i * N + j] * w[j];
    std::vector<double> remainder;
    for (double h = 1e-1; h > 1e-4; h /= 2.0) {
      double uh[N], fh[N], rem = 0.0;
      for (int k = 0; k < N; ++k) uh[k] = fx.u[k] + h * w[k];
      K::force(fx.body, fx.element(), fx.q0, uh, static_cast<const double*>(nullptr), fh);
      for (int k = 0; k < N; ++k) rem = std::max(rem, std::fabs(fh[k] - f0[k] - h * Kw[k]));
      remainder.push_back(rem);
    }
    for (size_t k = 1; k + 1 < remainder.size() && k < 5; ++k) {
      const double rate = std::log2(remainder[k - 1] / remainder[k]);
      EXPECT_NEAR(rate, 2.0, 0.15) << describe(options) << " step " << k;
    }
  }
}

TYPED_TEST(ElementKindTest, ElasticForceIsTheGradientOfTheStrainEnergy) {
  using K = TypeParam;
  constexpr int N = K::kDof;
  using Dl = math::Dual<N>;
  for (const auto& options : optionSets<K>()) {
    Fixture<K> fx(false, options);
    Dl ud[N];
    for (int k = 0; k < N; ++k) ud[k] = Dl::variable(fx.u[k], k);
    const Dl U = K::strainEnergy(fx.body, fx.element(), fx.q0, ud);
    double f[N];
    K::force(fx.body, fx.element(), fx.q0, fx.u, static_cast<const double*>(nullptr), f);
    const double scale = maxAbs(f, N);
    for (int k = 0; k < N; ++k) EXPECT_NEAR(f[k], U.d[k], 1e-12 * scale) << describe(options) << " entry " << k;
  }
}

TYPED_TEST(ElementKindTest, RigidMotionsStoreNoEnergyAndGiveNoForce) {
  using K = TypeParam;
  constexpr int D = K::kDim, B = K::kBlocks, N = K::kDof;
  for (const auto& options : optionSets<K>()) {
    Fixture<K> fx(false, options);
    std::uniform_real_distribution<double> r(-1.0, 1.0);
    for (int trial = 0; trial < 5; ++trial) {
      // a random rotation (2D: about z; 3D: axis-angle) and translation
      double R[3][3] = {}, t[3];
      const double angle = 3.0 * r(fx.rng);
      double axis[3] = {0.0, 0.0, 1.0};
      if (D == 3) {
        for (double& a : axis) a = r(fx.rng);
        const double n = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
        for (double& a : axis) a /= n;
      }
      const double c = std::cos(angle), s = std::sin(angle);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) R[i][j] = (i == j ? c : 0.0) + (1.0 - c) * axis[i] * axis[j];
      R[0][1] -= s * axis[2], R[0][2] += s * axis[1], R[1][0] += s * axis[2];
      R[1][2] -= s * axis[0], R[2][0] -= s * axis[1], R[2][1] += s * axis[0];
      for (double& x : t) x = 5.0 * r(fx.rng);
      double u[N];
      for (int a = 0; a < B; ++a) {
        const BlockRole role = K::kNodeLayout[a % K::kBlocksPerNode];
        const bool position = role == BlockRole::Position;
        for (int i = 0; i < D; ++i) {
          double q = position ? t[i] : 0.0;
          for (int j = 0; j < D; ++j) q += R[i][j] * fx.q0[a * D + j];
          u[a * D + i] = isMaterialBlock(role) ? 0.0 : q - fx.q0[a * D + i];  // the material and its spin stay
        }
      }
      double f[N];
      K::force(fx.body, fx.element(), fx.q0, u, static_cast<const double*>(nullptr), f);
      const BeamProperties p = K::properties(fx.section);
      EXPECT_LT(std::fabs(K::strainEnergy(fx.body, fx.element(), fx.q0, u)), 1e-24 * p.EA) << describe(options);
      EXPECT_LT(maxAbs(f, N), 1e-12 * p.EA) << describe(options);
    }
  }
}

// 1/2 v^T M v of v = V + w x r (positions) and w x g (gradients) against the rigid body's
// 1/2 m |V|^2 + m V . (w x r_c) + 1/2 w . J w, for the straight element along x.
TYPED_TEST(ElementKindTest, SlotMassGivesTheExactRigidKineticEnergy) {
  using K = TypeParam;
  constexpr int D = K::kDim, B = K::kBlocks;
  for (const auto& options : optionSets<K>()) {
    Fixture<K> fx(false, options);
    double m[B * B];
    K::slotMass(fx.body, m);
    if constexpr (isAle<K>()) {  // M(q): the element's inertia at rest is checked in test_ale_cable.cpp
      for (int k = 0; k < B * B; ++k) EXPECT_EQ(m[k], 0.0);
      continue;
    }
    const BeamProperties p = K::properties(fx.section);
    const double l = fx.disc.elementLength, mass = p.rhoA * l;
    const double rc[3] = {10.0 + 0.5 * l, -3.0, 0.0};
    std::uniform_real_distribution<double> r(-1.0, 1.0);
    for (int trial = 0; trial < 4; ++trial) {
      double V[3] = {r(fx.rng), r(fx.rng), D == 3 ? r(fx.rng) : 0.0};
      double w[3] = {D == 3 ? r(fx.rng) : 0.0, D == 3 ? r(fx.rng) : 0.0, r(fx.rng)};
      double v[B][3] = {};
      for (int a = 0; a < B; ++a) {
        const double* q = &fx.q0[a * D];
        const double x[3] = {q[0], q[1], D == 3 ? q[2] : 0.0};
        const bool position = K::kNodeLayout[a % K::kBlocksPerNode] == BlockRole::Position;
        const double wx[3] = {w[1] * x[2] - w[2] * x[1], w[2] * x[0] - w[0] * x[2], w[0] * x[1] - w[1] * x[0]};
        for (int i = 0; i < 3; ++i) v[a][i] = (position ? V[i] : 0.0) + wx[i];
      }
      double T = 0.0;
      for (int a = 0; a < B; ++a)
        for (int b = 0; b < B; ++b)
          for (int i = 0; i < 3; ++i) T += 0.5 * m[a * B + b] * v[a][i] * v[b][i];
      // about the centre of mass: the element along x has J = diag(Jx, Jy, Jz) with the rod's
      // m l^2/12 about y and z, and the section's rotary inertia rho I l about z (in-plane bending)
      // and x (no torsion in these kinds: their cross-section vector carries only rotation about z)
      const double rod = mass * l * l / 12.0, sec = fx.rotary * l;
      const double J[3] = {D == 3 ? 0.0 : sec, rod, rod + sec};
      double vc[3] = {V[0], V[1], V[2]};
      const double wrc[3] = {w[1] * rc[2] - w[2] * rc[1], w[2] * rc[0] - w[0] * rc[2], w[0] * rc[1] - w[1] * rc[0]};
      for (int i = 0; i < 3; ++i) vc[i] += wrc[i];
      double exact = 0.0;
      for (int i = 0; i < 3; ++i) exact += 0.5 * mass * vc[i] * vc[i] + 0.5 * J[i] * w[i] * w[i];
      if (D == 2) exact = 0.5 * mass * (vc[0] * vc[0] + vc[1] * vc[1]) + 0.5 * (rod + sec) * w[2] * w[2];
      EXPECT_NEAR(T, exact, 1e-13 * mass * (1.0 + 110.0)) << describe(options) << " trial " << trial;
    }
  }
}

// The centerline interpolation reproduces the nodes and straight lines: the weights of the position
// slots sum to one, and at eta = 0, 1 only the node's position slot counts.
TYPED_TEST(ElementKindTest, InterpolationReproducesNodesAndStraightLines) {
  using K = TypeParam;
  constexpr int B = K::kBlocks;
  const BodyDiscretization d{0.7, 0.7, 5};
  for (double eta : {0.0, 0.25, 0.5, 0.8, 1.0}) {
    double w[B];
    K::interpolation(d, eta, w);
    double sum = 0.0;
    for (int a = 0; a < B; ++a)
      if (K::kNodeLayout[a % K::kBlocksPerNode] == BlockRole::Position) sum += w[a];
    EXPECT_NEAR(sum, 1.0, 1e-15);
    if (eta == 0.0 || eta == 1.0) {
      for (int a = 0; a < B; ++a) EXPECT_NEAR(w[a], (a == (eta == 0.0 ? 0 : K::kBlocksPerNode)) ? 1.0 : 0.0, 1e-15);
    }
  }
}
