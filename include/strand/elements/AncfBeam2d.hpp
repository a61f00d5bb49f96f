// Shear-deformable 2D ANCF beams of seed 004, ch. 2: the position of a particle of the element is
//   r(x, y) = c(x) + y d(x),   x in [0, l] along the reference centerline, y across the section,
// with the centerline c and the cross-section vector d interpolated from the nodal coordinates:
//   AncfBeam2dShear   Omar & Shabana (J. Sound Vib. 243, 2001): per node r, r_x, r_y (six per
//                     node); c is the cubic Hermite of (r, r_x), d linear in r_y (seed 004 Eq. 2.9:
//                     cubic in x, linear in y).
//   AncfBeam2dLinear  Kerkkanen, Sopanen & Mikkola (J. Mech. Des. 127, 2005; seed 004 Eq. 2.10-2.12):
//                     per node r, r_y (four per node); c and d linear: S1 = 1 - xi, S2 = y (1 - xi),
//                     S3 = xi, S4 = y xi (xi = x / l).
// Elastic forces from continuum mechanics (Green-Lagrange strain, Eq. 2.13-2.19), integrated over
// the rectangular section in closed form and along x by Gauss rules (ShearBeamSection.hpp).
//
// Integration along x, a formulation option (seed 004 sec. 2.2.1); points per rule:
//                        normal strains + shear gradient s1   mean shear s0
//   full                 exact: Shear 5, Linear 3              (same rule)
//   reduced              Shear 3, Linear 1 (one rule for all terms, the fewest without spurious modes)
//   selective (default)  exact as full                         Shear 2, Linear 1
// Selective integration under-integrates only the mean shear strain s0 = c'.d/2: in the Linear
// element c' is constant and d linear, so the one-point rule removes the parasitic shear of a
// bent element (seed 004 Fig. 2.2, shear locking); in the Shear element (c' quadratic) two points
// sample s0 where its quadratic part vanishes. Kerkkanen integrates the normal strains with two
// points (seed 004 p. 36); we integrate them exactly (the transverse strain g0^2 is quartic in x).
//
// Slots per element: node 1's blocks, then node 2's. Channels (SlotIntegration.hpp): c', d', d.
// Sign convention as everywhere: f is the internal force on the left-hand side, M a + f_int = f_ext.
#pragma once
#include <cmath>

#include "strand/core/KernelClones.hpp"
#include "strand/elements/ElementKind.hpp"
#include "strand/elements/ShearBeamSection.hpp"
#include "strand/elements/SlotIntegration.hpp"
#include "strand/math/Gauss.hpp"
#include "strand/math/Hermite.hpp"

namespace strand::elements {

// Omar-Shabana: slots r1, rx1, ry1, r2, rx2, ry2.
struct CubicCenterline {
  static constexpr const char* kName = "AncfBeam2dShear";
  static constexpr int kBlocksPerNode = 3;
  static constexpr BlockRole kNodeLayout[3] = {BlockRole::Position, BlockRole::AxialGradient,
                                               BlockRole::TransverseGradient};
  static constexpr int kOrientationBlock = 2;
  static constexpr int kPoints[3] = {5, 3, 3};  // full (exact), reduced, selective mean shear
  // N_c, dN_c/dx and N_d at eta (gradient slots scaled by l / sigma, as the cable's slopes)
  static void shapes(double eta, double l, double sigma, double Nc[6], double dNc[6], double Nd[6], double dNd[6]) {
    const math::HermiteValues h = math::hermite(eta);
    const double s = l / sigma;
    const double nc[6] = {h.s[0], h.s[1] * s, 0.0, h.s[2], h.s[3] * s, 0.0};
    const double dc[6] = {h.ds[0] / l, h.ds[1] * s / l, 0.0, h.ds[2] / l, h.ds[3] * s / l, 0.0};
    const double nd[6] = {0.0, 0.0, 1.0 - eta, 0.0, 0.0, eta};
    const double dd[6] = {0.0, 0.0, -1.0 / l, 0.0, 0.0, 1.0 / l};
    for (int a = 0; a < 6; ++a) Nc[a] = nc[a], dNc[a] = dc[a], Nd[a] = nd[a], dNd[a] = dd[a];
  }
};

// Kerkkanen's linear element: slots r1, ry1, r2, ry2.
struct LinearCenterline {
  static constexpr const char* kName = "AncfBeam2dLinear";
  static constexpr int kBlocksPerNode = 2;
  static constexpr BlockRole kNodeLayout[2] = {BlockRole::Position, BlockRole::TransverseGradient};
  static constexpr int kOrientationBlock = 1;
  static constexpr int kPoints[3] = {3, 1, 1};
  static void shapes(double eta, double l, double, double Nc[4], double dNc[4], double Nd[4], double dNd[4]) {
    const double nc[4] = {1.0 - eta, 0.0, eta, 0.0}, dc[4] = {-1.0 / l, 0.0, 1.0 / l, 0.0};
    const double nd[4] = {0.0, 1.0 - eta, 0.0, eta}, dd[4] = {0.0, -1.0 / l, 0.0, 1.0 / l};
    for (int a = 0; a < 4; ++a) Nc[a] = nc[a], dNc[a] = dc[a], Nd[a] = nd[a], dNd[a] = dd[a];
  }
};

template <class Centerline>
class AncfBeam2d final {
public:
  static constexpr int kDim = 2;
  static constexpr int kBlocksPerNode = Centerline::kBlocksPerNode;
  static constexpr int kBlocks = 2 * kBlocksPerNode;
  static constexpr int kDof = kBlocks * kDim;
  static constexpr int kG = ShearBeamSection::kG;  // (c', d', d)
  static constexpr int kMeasures = ShearBeamSection::kMeasures;
  using Calc = SlotCalculus<2, kBlocks, 3, kBlocksPerNode>;
  using Points = typename Calc::Points;

  // ---- the element-kind contract (ElementKind.hpp) ----
  static constexpr const char* kName = Centerline::kName;
  static constexpr const BlockRole* kNodeLayout = Centerline::kNodeLayout;
  static constexpr int kOrientationBlock = Centerline::kOrientationBlock;  // r_y: the cross-section
  static constexpr bool kStressFreeInitial = false;
  static constexpr bool kInitialStretch = false;  // initial_stretch: not built
  static constexpr bool kConstantMass = true;
  static constexpr bool kConfigurationLoads = false;
  static constexpr SectionKey kSectionKeys[] = {
      {"E", "Young's modulus [Pa]", true, 0.0, 0.0, false, kNoLimit},
      {"nu", "Poisson's ratio", false, 0.0, 0.0, true, 0.5},
      {"rho", "density [kg/m^3]", true, 0.0, 0.0, false, kNoLimit},
      {"width", "section width, out of the plane [m]", true, 0.0, 0.0, false, kNoLimit},
      {"height", "section height, in the plane [m]", true, 0.0, 0.0, false, kNoLimit},
      {"shear_factor", "shear correction k_s (default: Cowper's 10 (1 + nu) / (12 + 11 nu) with decoupled elasticity, "
                       "else 1)", false, 0.0, 0.0, false, kNoLimit},
      {"damping", "Kelvin-Voigt time constant of the material [s]", false, 0.0, 0.0, true, kNoLimit},
  };
  static constexpr int kOptionCount = 2;
  static constexpr OptionKey kOptions[2] = {
      {"integration", "Gauss rules along the element (seed 004 sec. 2.2.1)", {"selective", "full", "reduced", nullptr}},
      {"elasticity", "elastic law (Poisson locking)", {"decoupled", "plane_stress", "plane_strain", nullptr}},
  };

  // One Gauss rule along x and the part of the section stiffness it integrates.
  struct Rule {
    Points points;
    double C[kMeasures][kMeasures];
  };
  struct Body {
    ShearBeamSection section;
    double length = 0.0, sigma = 1.0;
    int rules = 1;
    Rule rule[2];
  };
  struct Element {
    const Body* body = nullptr;
  };

  static ShearBeamSection::Material material(const SectionValues& v) {
    ShearBeamSection::Material m;
    m.E = v.number("E");
    m.nu = v.number("nu");
    m.rho = v.number("rho");
    m.width = v.number("width");
    m.height = v.number("height");
    m.shearFactor = v.number("shear_factor");
    m.damping = v.number("damping");
    const std::string e = v.option("elasticity", "decoupled");
    m.elasticity = e == "plane_stress"   ? ShearBeamSection::Elasticity::PlaneStress
                   : e == "plane_strain" ? ShearBeamSection::Elasticity::PlaneStrain
                                         : ShearBeamSection::Elasticity::Decoupled;
    return m;
  }

  static BeamProperties properties(const SectionValues& v) {
    const ShearBeamSection s{material(v)};
    return {s.m.E * s.area(), s.m.E * s.inertia(), s.m.rho * s.area()};
  }

  // Slot coefficients at eta for the channels c', d', d.
  static void channels(double eta, double l, double sigma, double B[3][kBlocks]) {
    double Nc[kBlocks], dNc[kBlocks], Nd[kBlocks], dNd[kBlocks];
    Centerline::shapes(eta, l, sigma, Nc, dNc, Nd, dNd);
    for (int a = 0; a < kBlocks; ++a) {
      B[0][a] = dNc[a];
      B[1][a] = dNd[a];
      B[2][a] = Nd[a];
    }
  }

  static Body body(const SectionValues& v, const BodyDiscretization& d) {
    Body b;
    b.section.m = material(v);
    b.length = d.elementLength;
    b.sigma = d.gradientScale;
    double C[kMeasures][kMeasures];
    b.section.stiffness(C);
    const std::string integration = v.option("integration", "selective");
    auto table = [&](int n) {
      return Points::build(math::gaussLegendre(n), b.length,
                           [&](double eta, double B[3][kBlocks]) { channels(eta, b.length, b.sigma, B); });
    };
    auto copy = [&](Rule& r, bool meanShear, bool others) {
      for (int i = 0; i < kMeasures; ++i)
        for (int j = 0; j < kMeasures; ++j) {
          const bool isMeanShear = i == ShearBeamSection::S0 && j == ShearBeamSection::S0;
          r.C[i][j] = (isMeanShear ? meanShear : others) ? C[i][j] : 0.0;
        }
    };
    if (integration == "selective") {
      b.rules = 2;
      b.rule[0].points = table(Centerline::kPoints[0]);
      copy(b.rule[0], false, true);
      b.rule[1].points = table(Centerline::kPoints[2]);
      copy(b.rule[1], true, false);
    } else {
      b.rules = 1;
      b.rule[0].points = table(Centerline::kPoints[integration == "reduced" ? 1 : 0]);
      copy(b.rule[0], true, true);
    }
    return b;
  }

  static Element element(const Body& b, const double*) { return Element{&b}; }
  static bool velocityDependent(const Body& b) { return b.section.m.damping != 0.0; }

  // Internal force f_int(u, v) = dU/du + dR/dv at q = q0 + u (v null: no damping force).
  template <class S>
  static void force(const Body& b, const Element&, const double* q0, const S* u, const S* v, S* f) {
    const bool damped = v && velocityDependent(b);
    for (int k = 0; k < kDof; ++k) f[k] = S(0.0);
    for (int r = 0; r < b.rules; ++r)
      withPaddedPoints(b.rule[r].points, [&](auto p) {
        constexpr int P = decltype(p)::value;
        S fr[kDof];
        forceAt<P>(b.rule[r], b.section.m.damping, q0, u, damped ? v : nullptr, fr);
        for (int k = 0; k < kDof; ++k) f[k] += fr[k];
      });
  }

  // K = df/du and Dm = df/dv (row-major kDof x kDof); f optional, Dm may be null.
  static void tangent(const Body& b, const Element&, const double* q0, const double* u, const double* v, double* f,
                      double* K, double* Dm) {
    const bool damped = v && velocityDependent(b);
    for (int k = 0; k < kDof * kDof; ++k) {
      K[k] = 0.0;
      if (Dm) Dm[k] = 0.0;
    }
    if (f)
      for (int k = 0; k < kDof; ++k) f[k] = 0.0;
    for (int r = 0; r < b.rules; ++r)
      withPaddedPoints(b.rule[r].points, [&](auto p) {
        tangentAt<decltype(p)::value>(b.rule[r], b.section.m.damping, q0, u, damped ? v : nullptr, f, K,
                                      damped ? Dm : nullptr);
      });
  }

  template <class S>
  static S strainEnergy(const Body& b, const Element&, const double* q0, const S* u) {
    S U(0.0);
    for (int r = 0; r < b.rules; ++r)
      withPaddedPoints(b.rule[r].points, [&](auto p) {
        constexpr int P = decltype(p)::value;
        double G0[kG][P];
        S Gu[kG][P];
        Calc::template gather<P>(b.rule[r].points, q0, G0);
        Calc::template gather<P>(b.rule[r].points, u, Gu);
        for (int g = 0; g < P; ++g) {
          double g0[kG];
          S gu[kG];
          Calc::template lane<P>(G0, g, g0);
          Calc::template lane<P>(Gu, g, gu);
          U += b.rule[r].points.wl[g] * ShearBeamSection::energy(b.rule[r].C, g0, gu);
        }
      });
    return U;
  }

  // Rayleigh dissipation R (the damping force is dR/dv).
  template <class S>
  static S dissipation(const Body& b, const double* q0, const S* u, const S* v) {
    S R(0.0);
    for (int r = 0; r < b.rules; ++r)
      withPaddedPoints(b.rule[r].points, [&](auto p) {
        constexpr int P = decltype(p)::value;
        double G0[kG][P];
        S Gu[kG][P], Gd[kG][P];
        Calc::template gather<P>(b.rule[r].points, q0, G0);
        Calc::template gather<P>(b.rule[r].points, u, Gu);
        Calc::template gather<P>(b.rule[r].points, v, Gd);
        for (int g = 0; g < P; ++g) {
          double g0[kG];
          S gu[kG], gd[kG];
          Calc::template lane<P>(G0, g, g0);
          Calc::template lane<P>(Gu, g, gu);
          Calc::template lane<P>(Gd, g, gd);
          R += b.rule[r].points.wl[g] * ShearBeamSection::dissipation(b.rule[r].C, b.section.m.damping, g0, gu, gd);
        }
      });
    return R;
  }

  // Slot mass m_ab = rho A int Nc_a Nc_b dx + rho I int Nd_a Nd_b dx (rotary inertia of the
  // section; the odd moment of the section vanishes), exact with 4 points: M = m (x) I_2.
  static void slotMass(const Body& b, double* m) {
    const math::QuadratureRule rule = math::gaussLegendre(4);
    const double rhoA = b.section.m.rho * b.section.area(), rhoI = b.section.m.rho * b.section.inertia();
    for (int k = 0; k < kBlocks * kBlocks; ++k) m[k] = 0.0;
    for (int g = 0; g < rule.size(); ++g) {
      double Nc[kBlocks], dNc[kBlocks], Nd[kBlocks], dNd[kBlocks];
      Centerline::shapes(rule.x[g], b.length, b.sigma, Nc, dNc, Nd, dNd);
      const double wl = rule.w[g] * b.length;
      for (int a = 0; a < kBlocks; ++a)
        for (int c = 0; c < kBlocks; ++c) m[a * kBlocks + c] += wl * (rhoA * Nc[a] * Nc[c] + rhoI * Nd[a] * Nd[c]);
    }
  }

  // Centerline position c(eta) = sum_a w_a q_a.
  static void interpolation(const BodyDiscretization& d, double eta, double* w) {
    double dNc[kBlocks], Nd[kBlocks], dNd[kBlocks];
    Centerline::shapes(eta, d.elementLength, d.gradientScale, w, dNc, Nd, dNd);
  }

  // The same at the element's current coordinates q (its shape functions do not depend on them).
  static void interpolationAt(const BodyDiscretization& d, const double*, double eta, double* w) {
    interpolation(d, eta, w);
  }

  // Consistent load of a constant force per unit length p acting on the centerline (and of a body
  // force rho g over the section, whose y-moment vanishes): f_a = int Nc_a p dx.
  static void consistentLoad(const Body& b, const double* p, double* f) {
    const math::QuadratureRule rule = math::gaussLegendre(4);
    for (int k = 0; k < kDof; ++k) f[k] = 0.0;
    for (int g = 0; g < rule.size(); ++g) {
      double Nc[kBlocks], dNc[kBlocks], Nd[kBlocks], dNd[kBlocks];
      Centerline::shapes(rule.x[g], b.length, b.sigma, Nc, dNc, Nd, dNd);
      for (int a = 0; a < kBlocks; ++a)
        for (int i = 0; i < 2; ++i) f[a * 2 + i] += rule.w[g] * b.length * Nc[a] * p[i];
    }
  }

  static int referenceValueCount(const Body&) { return 0; }
  static void referenceValues(const Body&, const double*, double*) {}

private:
  template <int P, class S>
  STRAND_KERNEL_CLONES
  static void forceAt(const Rule& rule, double eta, const double* q0, const S* u, const S* v, S* f) {
    double G0[kG][P];
    S Gu[kG][P], Gd[kG][P], fG[kG][P];
    Calc::template gather<P>(rule.points, q0, G0);
    Calc::template gather<P>(rule.points, u, Gu);
    if (v) Calc::template gather<P>(rule.points, v, Gd);
    for (int g = 0; g < P; ++g) {
      double g0[kG];
      S gu[kG], gd[kG], fg[kG];
      Calc::template lane<P>(G0, g, g0);
      Calc::template lane<P>(Gu, g, gu);
      if (v) Calc::template lane<P>(Gd, g, gd);
      ShearBeamSection::force(rule.C, eta, g0, gu, v ? gd : static_cast<const S*>(nullptr), fg);
      for (int k = 0; k < kG; ++k) fG[k][g] = fg[k];
    }
    Calc::template integrateForce<P>(rule.points, fG, f);
  }

  // Adds one rule's force (if f), K and D (if Dm) to the element's.
  template <int P>
  STRAND_KERNEL_CLONES
  static void tangentAt(const Rule& rule, double eta, const double* q0, const double* u, const double* v, double* f,
                        double* K, double* Dm) {
    double G0[kG][P], Gu[kG][P], Gd[kG][P], fG[kG][P], KG[kG][kG][P], DG[kG][kG][P];
    Calc::template gather<P>(rule.points, q0, G0);
    Calc::template gather<P>(rule.points, u, Gu);
    if (v) Calc::template gather<P>(rule.points, v, Gd);
    for (int g = 0; g < P; ++g) {
      double g0[kG], gu[kG], gd[kG], fg[kG], kg[kG][kG], dg[kG][kG];
      Calc::template lane<P>(G0, g, g0);
      Calc::template lane<P>(Gu, g, gu);
      if (v) Calc::template lane<P>(Gd, g, gd);
      ShearBeamSection::tangent(rule.C, eta, g0, gu, v ? gd : nullptr, fg, kg, dg);
      for (int k = 0; k < kG; ++k) {
        fG[k][g] = fg[k];
        for (int l = 0; l < kG; ++l) {
          KG[k][l][g] = kg[k][l];
          if (v) DG[k][l][g] = dg[k][l];
        }
      }
    }
    double fr[kDof], Kr[kDof * kDof];
    if (f) {
      Calc::template integrateForce<P>(rule.points, fG, fr);
      for (int k = 0; k < kDof; ++k) f[k] += fr[k];
    }
    Calc::template integrateMatrix<P>(rule.points, KG, Kr, !v);
    if (!v) Calc::mirrorUpper(Kr);  // K_G is symmetric without damping
    Calc::completeFirstPosition(Kr);
    for (int k = 0; k < kDof * kDof; ++k) K[k] += Kr[k];
    if (Dm) {
      Calc::template integrateMatrix<P>(rule.points, DG, Kr, false);
      Calc::completeFirstPosition(Kr);
      for (int k = 0; k < kDof * kDof; ++k) Dm[k] += Kr[k];
    }
  }
};

using AncfBeam2dShear = AncfBeam2d<CubicCenterline>;
using AncfBeam2dLinear = AncfBeam2d<LinearCenterline>;

}  // namespace strand::elements
