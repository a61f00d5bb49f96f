// Gradient-deficient ANCF cable element in 2D and 3D: AncfCable2d, AncfCable3d.
//
// Coordinates of one element (seed 003 Eq. 66-68, extended to 3D):
//   q_e = [ r_1 (D), sigma_1 r_1' (D), r_2 (D), sigma_2 r_2' (D) ],   r' = dr/dx,
// x the reference arc length, l the element length, sigma_a the slope scale of node a (1: plain
// slopes; l: the scaled slopes "l dr/dx" of seed 003 Eq. 68). Interpolation (Eq. 69-71):
//   r(eta) = sum_a N_a(eta) e_a,  N = [s1, s2 l/sigma_1, s3, s4 l/sigma_2],  eta = x/l in [0, 1].
//
// Elastic line approach (Gerstmayr & Irschik, J. Sound Vib. 318 (2008); seed 003 Eq. 60-64):
//   W = 1/2 EA eps^2 + 1/2 EI |kappa - kappa0|^2 per unit reference length, with the Green strain
//   eps = (r'.r' - r0'.r0')/2 relative to the reference shape r0 (Eq. 62 for an arc-length
//   parameterized r0) and the curvature vector kappa = r' x r'' / |r'|^3 (Eq. 64; a scalar in 2D,
//   so a reference curvature kappa0 != 0 exists only in 2D).
// Unknowns are displacements u = q - q0 from the reference coordinates q0, and the strain is
// evaluated as eps = r0'.u' + u'.u'/2: no cancellation, so the residual has no round-off floor of
// size EA eps_mach L / l (absolute positions of a long cable; docs/validation.md, "Conditioning").
// Kelvin-Voigt damping on the strain and curvature rates (seed 000 Eq. 31-40):
//   generalized stresses  N = EA (eps + c_eps deps/dt),  m = EI (kappa - kappa0 + c_kap dkappa/dt).
// In 3D the curvature-vector rate also sees rigid rotations of a curved cable out of its plane;
// docs/elements/ancf-cable.md states this limitation.
//
// Everything below is a function of the pointwise vector G = (r', r'') (2D entries). The element
// residual and tangent follow by the chain rule with the slot coefficients B1 = dN/dx, B2 = d2N/dx2:
//   f_a = int (B1_a f_G[r'] + B2_a f_G[r'']) dx,   K_ab = int sum B_a K_G B_b dx.
// Sign convention: f is the internal force on the left-hand side,
//   M a + f_int(q, v) - f_ext = 0.
#pragma once
#include <array>
#include <cmath>
#include <stdexcept>

#include "strand/elements/CableSection.hpp"
#include "strand/elements/CableShapeTable.hpp"
#include "strand/elements/ElementKind.hpp"
#include "strand/elements/SlotIntegration.hpp"

namespace strand::elements {

// The slots r_1, r_1', r_2, r_2' at the Gauss points of one rule, channels r' (B1) and r'' (B2).
using CablePointTable = SlotPoints<4, 2>;

template <int D>
class AncfCable final {
  static_assert(D == 2 || D == 3, "AncfCable is 2D or 3D");

public:
  static constexpr int kDim = D;
  static constexpr int kNodes = 2;
  static constexpr int kDofPerNode = 2 * D;
  static constexpr int kDof = 4 * D;
  static constexpr int kCurv = (D == 2) ? 1 : 3;  // components of the curvature vector
  static constexpr int kG = 2 * D;                // size of G = (r', r'')
  using Calc = SlotCalculus<D, 4, 2, 2>;           // slots r_1, r_1', r_2, r_2'; channels r', r''

  // Shape-function values N and their x-derivatives B1, B2 for the four coordinate slots.
  struct Slots {
    double N[4], B1[4], B2[4];
  };

  struct Geometry {
    double length = 0.0;                 // reference length l of the element [m]
    double slopeScale[2] = {1.0, 1.0};   // sigma of node 1 and 2
    const double* kappa0 = nullptr;      // reference curvature at each Gauss point, 2D (null: 0)
    double eps0 = 0.0;                   // the initial state's axial strain (lambda0^2 - 1) / 2: a pretension
    // pointTable() precomputed at the points of one table (uniform elements); used only with that table
    const CablePointTable* points = nullptr;
    const CableShapeTable* pointsOf = nullptr;
  };

  static Slots slots(const Geometry& geo, const math::HermiteValues& h) {
    const double l = geo.length;
    const double scale[4] = {1.0, l / geo.slopeScale[0], 1.0, l / geo.slopeScale[1]};
    Slots sl;
    for (int a = 0; a < 4; ++a) {
      sl.N[a] = h.s[a] * scale[a];
      sl.B1[a] = h.ds[a] * scale[a] / l;
      sl.B2[a] = h.dds[a] * scale[a] / (l * l);
    }
    return sl;
  }

  // The slots at all points of tab as a structure of arrays (SlotIntegration.hpp).
  static CablePointTable pointTable(const Geometry& geo, const CableShapeTable& tab) {
    if (tab.size() < 1 || tab.size() > CablePointTable::kMax)
      throw std::invalid_argument("AncfCable: 1 to 8 Gauss points");
    CablePointTable t;
    t.count = tab.size();
    t.padded = t.count + t.count % 2;
    for (int g = 0; g < CablePointTable::kMax; ++g) {
      const Slots sl = slots(geo, tab.at[g < t.count ? g : t.count - 1]);
      t.wl[g] = g < t.count ? tab.rule.w[g] * geo.length : 0.0;
      for (int a = 0; a < 4; ++a) {
        t.B[0][a][g] = sl.B1[a];
        t.B[1][a][g] = sl.B2[a];
        t.wB[0][a][g] = t.wl[g] * sl.B1[a];
        t.wB[1][a][g] = t.wl[g] * sl.B2[a];
      }
    }
    return t;
  }

  // geo's own table when it has one for tab, else one built in scratch.
  static const CablePointTable& pointsAt(const Geometry& geo, const CableShapeTable& tab, CablePointTable& scratch) {
    if (geo.points && geo.pointsOf == &tab) return *geo.points;
    scratch = pointTable(geo, tab);
    return scratch;
  }

  // ---- pointwise kinematics, templated on the scalar (double, or math::Dual for tests) ----

  // c = r' x r'' (2D: the scalar z-component).
  template <class S>
  [[gnu::always_inline]] static void cross(const S* g1, const S* g2, S* c) {
    if constexpr (D == 2) {
      c[0] = g1[0] * g2[1] - g1[1] * g2[0];
    } else {
      c[0] = g1[1] * g2[2] - g1[2] * g2[1];
      c[1] = g1[2] * g2[0] - g1[0] * g2[2];
      c[2] = g1[0] * g2[1] - g1[1] * g2[0];
    }
  }

  // G = (r', r'') at one Gauss point from element coordinates. The position weights of B1 and B2
  // sum to zero, so positions enter relative to node 1: r2 - r1 is exact to eps_mach l, while the
  // absolute positions of a long cable would put eps_mach |r| / l^2 of noise into r''.
  template <class S>
  static void gather(const Slots& sl, const S* q, S* G) {
    for (int i = 0; i < D; ++i) {
      const S chord = q[2 * D + i] - q[i];
      G[i] = sl.B1[2] * chord + sl.B1[1] * q[D + i] + sl.B1[3] * q[3 * D + i];
      G[D + i] = sl.B2[2] * chord + sl.B2[1] * q[D + i] + sl.B2[3] * q[3 * D + i];
    }
  }

  // Curvature vector kappa = r' x r'' / |r'|^3 (the axial strain comes from pointKinematics()).
  template <class S>
  static void curvature(const S* G, S* kappa) {
    S s = G[0] * G[0];
    for (int i = 1; i < D; ++i) s += G[i] * G[i];
    using std::sqrt;
    const S inv = 1.0 / (s * sqrt(s));
    S c[kCurv];
    cross(G, G + D, c);
    for (int i = 0; i < kCurv; ++i) kappa[i] = c[i] * inv;
  }

  // Strain energy of the element (no damping): int W dx.
  template <class S>
  static S strainEnergy(const CableSection& sec, const Geometry& geo, const CableShapeTable& tab,
                        const double* q0, const S* u) {
    CablePointTable scratch;
    const CablePointTable& t = pointsAt(geo, tab, scratch);
    return withPaddedPoints(t, [&](auto p) { return strainEnergyAt<decltype(p)::value>(sec, geo, t, q0, u); });
  }

  // Rayleigh dissipation function R = int 1/2 (EA c_eps deps^2 + EI c_kap |dkappa|^2) dx;
  // the damping force is dR/dv (tests check it), the dissipated power is 2R.
  template <class S>
  static S dissipation(const CableSection& sec, const Geometry& geo, const CableShapeTable& tab,
                       const double* q0, const S* u, const S* v) {
    CablePointTable scratch;
    const CablePointTable& t = pointsAt(geo, tab, scratch);
    return withPaddedPoints(t, [&](auto p) { return dissipationAt<decltype(p)::value>(sec, t, q0, u, v); });
  }

  // ---- residual and tangent ----

  // Internal force f_int(u, v) = dU/du + dR/dv (elastic + Kelvin-Voigt damping) at q = q0 + u.
  template <class S>
  static void force(const CableSection& sec, const Geometry& geo, const CableShapeTable& tab,
                    const double* q0, const S* u, const S* v, S* f) {
    CablePointTable scratch;
    const CablePointTable& t = pointsAt(geo, tab, scratch);
    const bool damped = v && (sec.dampAxial != 0.0 || sec.dampBending != 0.0);
    withPaddedPoints(t, [&](auto p) { forceAt<decltype(p)::value>(sec, geo, t, q0, u, damped ? v : nullptr, f); });
  }

  // K = df/dq and Dm = df/dv (row-major kDof x kDof), returned separately (design section 2).
  // f (optional) receives the internal force; Dm may be null.
  static void tangent(const CableSection& sec, const Geometry& geo, const CableShapeTable& tab,
                      const double* q0, const double* u, const double* v, double* f, double* K, double* Dm) {
    CablePointTable scratch;
    const CablePointTable& t = pointsAt(geo, tab, scratch);
    const bool damped = v && (sec.dampAxial != 0.0 || sec.dampBending != 0.0);
    withPaddedPoints(t, [&](auto p) {
      tangentAt<decltype(p)::value>(sec, geo, t, q0, u, damped ? v : nullptr, f, K, Dm);
    });
  }

  // Consistent mass M = rhoA int N^T N dx (constant). tab must integrate degree 6 exactly (>= 4 points).
  static void mass(const CableSection& sec, const Geometry& geo, const CableShapeTable& tab, double* M) {
    double m[4][4] = {};
    for (int g = 0; g < tab.size(); ++g) {
      const Slots sl = slots(geo, tab.at[g]);
      const double wl = tab.rule.w[g] * geo.length * sec.rhoA;
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) m[a][b] += wl * sl.N[a] * sl.N[b];
    }
    for (int k = 0; k < kDof * kDof; ++k) M[k] = 0.0;
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        for (int i = 0; i < D; ++i) M[(a * D + i) * kDof + b * D + i] = m[a][b];
  }

  // Point mass m at eta in [0, 1] (seed 003 Eq. 53): M += m N(eta)^T N(eta).
  static void addPointMass(const Geometry& geo, double m, double eta, double* M) {
    const Slots sl = slots(geo, math::hermite(eta));
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        for (int i = 0; i < D; ++i) M[(a * D + i) * kDof + b * D + i] += m * sl.N[a] * sl.N[b];
  }

  // Consistent load of a force per unit length p (constant over the element): f_a = int N_a p dx.
  static void distributedLoad(const Geometry& geo, const CableShapeTable& tab, const double* p, double* f) {
    for (int k = 0; k < kDof; ++k) f[k] = 0.0;
    for (int g = 0; g < tab.size(); ++g) {
      const Slots sl = slots(geo, tab.at[g]);
      const double wl = tab.rule.w[g] * geo.length;
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < D; ++i) f[a * D + i] += wl * sl.N[a] * p[i];
    }
  }

  // ---- the element-kind contract (ElementKind.hpp; docs/architecture.md, "Element kinds") ----
  static constexpr const char* kName = D == 2 ? "AncfCable2d" : "AncfCable3d";
  static constexpr int kBlocksPerNode = 2;
  static constexpr int kBlocks = 4;  // r_1, r_1', r_2, r_2'
  static constexpr BlockRole kNodeLayout[kBlocksPerNode] = {BlockRole::Position, BlockRole::AxialGradient};
  static constexpr int kOrientationBlock = 1;          // a clamp holds the slope; a moment turns it
  static constexpr bool kStressFreeInitial = D == 2;   // stress_free: initial (reference curvature)
  static constexpr bool kInitialStretch = true;        // initial_stretch: a pretensioned initial state (eps0)
  static constexpr bool kConstantMass = true;
  static constexpr bool kConfigurationLoads = false;  // distributed loads: the constant consistentLoad
  static constexpr SectionKey kSectionKeys[] = {
      {"E", "Young's modulus [Pa]", true, 0.0, 0.0, false, kNoLimit},
      {"A", "cross-section area [m^2]", true, 0.0, 0.0, false, kNoLimit},
      {"I", "second moment of area [m^4]", true, 0.0, 0.0, false, kNoLimit},
      {"rho", "density [kg/m^3]", true, 0.0, 0.0, false, kNoLimit},
      {"damping_axial", "Kelvin-Voigt coefficient on the axial strain rate [s]", false, 0.0, 0.0, true, kNoLimit},
      {"damping_bending", "Kelvin-Voigt coefficient on the curvature rate [s]", false, 0.0, 0.0, true, kNoLimit},
  };
  static constexpr int kOptionCount = 0;
  static constexpr OptionKey kOptions[1] = {{nullptr, nullptr, {nullptr}}};

  // The constants of one body (uniform elements): section, rules, the Gauss-point slots.
  struct Body {
    CableSection section;
    CableShapeTable tab{5}, massTab{4};  // elastic rule (discretization.gauss_points), exact mass rule
    Geometry geo;                        // of every element, but kappa0 and the table pointers
    CablePointTable points;              // pointTable(geo, tab)
  };
  using Element = Geometry;

  static BeamProperties properties(const SectionValues& v) {
    return {v.number("E") * v.number("A"), v.number("E") * v.number("I"), v.number("rho") * v.number("A")};
  }

  static Body body(const SectionValues& v, const BodyDiscretization& d) {
    Body b;
    b.section = {v.number("E") * v.number("A"), v.number("E") * v.number("I"), v.number("rho") * v.number("A"),
                 v.number("damping_axial"), v.number("damping_bending")};
    b.tab = CableShapeTable(d.gaussPoints);
    b.geo.length = d.elementLength;
    b.geo.slopeScale[0] = b.geo.slopeScale[1] = d.gradientScale;
    b.geo.eps0 = 0.5 * (d.initialStretch * d.initialStretch - 1.0);
    b.points = pointTable(b.geo, b.tab);
    return b;
  }

  // referenceValues: the element's kappa0 at the points of b.tab (null: straight).
  static Element element(const Body& b, const double* referenceValues) {
    Element e = b.geo;
    e.kappa0 = referenceValues;
    e.points = &b.points;
    e.pointsOf = &b.tab;
    return e;
  }

  static bool velocityDependent(const Body& b) {
    return b.section.dampAxial != 0.0 || b.section.dampBending != 0.0;
  }

  template <class S>
  static void force(const Body& b, const Element& e, const double* q0, const S* u, const S* v, S* f) {
    force(b.section, e, b.tab, q0, u, v, f);
  }
  static void tangent(const Body& b, const Element& e, const double* q0, const double* u, const double* v, double* f,
                      double* K, double* Dm) {
    tangent(b.section, e, b.tab, q0, u, v, f, K, Dm);
  }
  template <class S>
  static S strainEnergy(const Body& b, const Element& e, const double* q0, const S* u) {
    return strainEnergy(b.section, e, b.tab, q0, u);
  }

  // The slot mass m (4 x 4, row-major): M = m (x) I_D.
  static void slotMass(const Body& b, double* m) {
    double Me[kDof * kDof];
    mass(b.section, b.geo, b.massTab, Me);
    for (int a = 0; a < 4; ++a)
      for (int c = 0; c < 4; ++c) m[a * 4 + c] = Me[(a * D) * kDof + c * D];
  }

  // Centerline position r(eta) = sum_a w_a q_a (slots N of seed 003 Eq. 69-71).
  static void interpolation(const BodyDiscretization& d, double eta, double* w) {
    Geometry geo;
    geo.length = d.elementLength;
    geo.slopeScale[0] = geo.slopeScale[1] = d.gradientScale;
    const Slots sl = slots(geo, math::hermite(eta));
    for (int a = 0; a < 4; ++a) w[a] = sl.N[a];
  }

  // The axial force T = EA eps |r'| at eta (eps = (|r'|^2 - 1)/2, the Green strain of the elastic
  // line against the unit-stretch reference, pretension included: r' = dr/dx of the current
  // coordinates q; |r'| the stretch), the elastic part (no Kelvin-Voigt rate).
  static double axialForce(const SectionValues& v, const BodyDiscretization& d, const double* q, double eta) {
    Geometry geo;
    geo.length = d.elementLength;
    geo.slopeScale[0] = geo.slopeScale[1] = d.gradientScale;
    const Slots sl = slots(geo, math::hermite(eta));
    double rp[D] = {};
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < D; ++i) rp[i] += sl.B1[a] * q[a * D + i];
    double l2 = 0.0;
    for (int i = 0; i < D; ++i) l2 += rp[i] * rp[i];
    return v.number("E") * v.number("A") * 0.5 * (l2 - 1.0) * std::sqrt(l2);
  }

  // The same at the element's current coordinates q (its shape functions do not depend on them).
  static void interpolationAt(const BodyDiscretization& d, const double*, double eta, double* w) {
    interpolation(d, eta, w);
  }

  // Consistent load of a constant force per unit length p.
  static void consistentLoad(const Body& b, const double* p, double* f) { distributedLoad(b.geo, b.tab, p, f); }

  // Stress-free initial shape (2D): the curvature of the interpolated initial shape at the points.
  static int referenceValueCount(const Body& b) { return b.tab.size(); }
  static void referenceValues(const Body& b, const double* q0, double* kappa0) {
    for (int g = 0; g < b.tab.size(); ++g) {
      double G[kG], kap[kCurv];
      gather(slots(b.geo, b.tab.at[g]), q0, G);
      curvature(G, kap);
      kappa0[g] = kap[0];
    }
  }

private:
  // ---- the Gauss points of one element as a structure of arrays ----
  // X[k][g] is component k at point g, for the P (padded, SlotIntegration.hpp) points of the
  // element. Pointwise physics stays in pointForce and pointTangent; the loops here call them point
  // by point (inlined), and with a compile-time P the compiler evaluates two or more points per
  // instruction (-O3; docs/performance.md). The 3D tangent, too large for that, is written in array
  // form (pointTangents3d).

  // G = G0 + Gu and the axial strain eps = eps0 + r0'.u' + u'.u'/2 at every point (no
  // cancellation; eps0 = (|r0'|^2 - 1) / 2 of a pretensioned initial state, else 0).
  template <int P, class S>
  static void pointKinematics(const CablePointTable& t, const double* q0, const S* u, S G[kG][P], S eps[P],
                              double eps0 = 0.0) {
    double G0[kG][P];
    Calc::template gather<P>(t, q0, G0);
    Calc::template gather<P>(t, u, G);
    for (int g = 0; g < P; ++g) eps[g] = S(eps0);
    for (int i = 0; i < D; ++i)
      for (int g = 0; g < P; ++g) eps[g] += G0[i][g] * G[i][g] + 0.5 * G[i][g] * G[i][g];
    for (int k = 0; k < kG; ++k)
      for (int g = 0; g < P; ++g) G[k][g] += G0[k][g];
  }

  // The 2D reference curvature at every point (0 on the padding, and in 3D).
  template <int P>
  static void referenceCurvature(const Geometry& geo, const CablePointTable& t, double k0[P]) {
    for (int g = 0; g < P; ++g) k0[g] = (D == 2 && geo.kappa0 && g < t.count) ? geo.kappa0[g] : 0.0;
  }

  // pointForce at every point; Damped is a template argument so that the loop has no branch.
  template <bool Damped, int P, class S>
  static void pointForces(const CableSection& sec, const double k0[P], const S eps[P], const S G[kG][P],
                          const S Gd[kG][P], S fG[kG][P]) {
    for (int g = 0; g < P; ++g) {
      S Gg[kG], Gdg[kG], fGg[kG];
      Calc::template lane<P>(G, g, Gg);
      if (Damped) Calc::template lane<P>(Gd, g, Gdg);
      pointForce(sec, k0[g], eps[g], Gg, Damped ? Gdg : nullptr, fGg);
      for (int k = 0; k < kG; ++k) fG[k][g] = fGg[k];
    }
  }

  // forceAt and tangentAt are not inlined into force() and tangent(): with all four point counts
  // inlined, tangent() was 53 kB of code and the element loop missed the instruction cache 24
  // times as often (cachegrind, 1e5 elements: 4.07M against 0.17M misses)
  template <int P, class S>
  [[gnu::noinline]] static void forceAt(const CableSection& sec, const Geometry& geo, const CablePointTable& t, const double* q0,
                      const S* u, const S* v, S* f) {
    S G[kG][P], eps[P], fG[kG][P];
    double k0[P];
    pointKinematics<P>(t, q0, u, G, eps, geo.eps0);
    referenceCurvature<P>(geo, t, k0);
    if (v) {
      S Gd[kG][P];
      Calc::template gather<P>(t, v, Gd);
      pointForces<true, P>(sec, k0, eps, G, Gd, fG);
    } else {
      pointForces<false, P>(sec, k0, eps, G, G, fG);  // (the rates argument is unused)
    }
    Calc::template integrateForce<P>(t, fG, f);
  }

  // W = 1/2 EA eps^2 + 1/2 EI |kappa - kappa0|^2 at every point, integrated.
  template <int P, class S>
  static S strainEnergyAt(const CableSection& sec, const Geometry& geo, const CablePointTable& t, const double* q0,
                          const S* u) {
    S G[kG][P], eps[P], w[P];
    double k0[P];
    pointKinematics<P>(t, q0, u, G, eps, geo.eps0);
    referenceCurvature<P>(geo, t, k0);
    for (int g = 0; g < P; ++g) {
      S Gg[kG];
      Calc::template lane<P>(G, g, Gg);
      w[g] = 0.5 * sec.EA * eps[g] * eps[g];
      if constexpr (D == 3) {  // no reference curvature: |kappa|^2 = |r' x r''|^2 / s^3, no root
        S c[3];
        const S s = Gg[0] * Gg[0] + Gg[1] * Gg[1] + Gg[2] * Gg[2];
        cross(Gg, Gg + D, c);
        w[g] += 0.5 * sec.EI * (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / (s * s * s);
      } else {
        S kap[kCurv];
        curvature(Gg, kap);
        w[g] += 0.5 * sec.EI * (kap[0] - k0[g]) * (kap[0] - k0[g]);
      }
    }
    S U(0.0);
    for (int g = 0; g < P; ++g) U += t.wl[g] * w[g];
    return U;
  }

  // R = 1/2 (EA c_eps deps^2 + EI c_kap |dkappa|^2) at every point, integrated.
  template <int P, class S>
  static S dissipationAt(const CableSection& sec, const CablePointTable& t, const double* q0, const S* u,
                         const S* v) {
    S G[kG][P], Gd[kG][P], eps[P];
    pointKinematics<P>(t, q0, u, G, eps);
    Calc::template gather<P>(t, v, Gd);
    S R(0.0);
    for (int g = 0; g < P; ++g) {
      S Gg[kG], Gdg[kG];
      Calc::template lane<P>(G, g, Gg);
      Calc::template lane<P>(Gd, g, Gdg);
      S epsDot = Gg[0] * Gdg[0];
      for (int i = 1; i < D; ++i) epsDot += Gg[i] * Gdg[i];
      // kappa-dot by the exact time derivative of c / s^(3/2)
      S s = Gg[0] * Gg[0], sDot = 2.0 * Gg[0] * Gdg[0];
      for (int i = 1; i < D; ++i) {
        s += Gg[i] * Gg[i];
        sDot += 2.0 * Gg[i] * Gdg[i];
      }
      using std::sqrt;
      const S s32 = s * sqrt(s);
      S c[kCurv], c1[kCurv], c2[kCurv];
      cross(Gg, Gg + D, c);
      cross(Gdg, Gg + D, c1);
      cross(Gg, Gdg + D, c2);
      S r = 0.5 * sec.EA * sec.dampAxial * epsDot * epsDot;
      for (int i = 0; i < kCurv; ++i) {
        const S kd = (c1[i] + c2[i]) / s32 - 1.5 * c[i] * sDot / (s32 * s);
        r += 0.5 * sec.EI * sec.dampBending * kd * kd;
      }
      R += t.wl[g] * r;
    }
    return R;
  }

  // pointTangent at every point (Damped: with the velocity-dependent terms and D_G); in 3D without
  // curvature-rate damping the closed form pointTangents3d.
  template <bool Damped, int P>
  static void pointTangents(const CableSection& sec, const double k0[P], const double eps[P], const double G[kG][P],
                            const double Gd[kG][P], double fG[kG][P], double KG[kG][kG][P], double DG[kG][kG][P]) {
    if constexpr (D == 3) {
      if (!(Damped && sec.dampBending != 0.0)) {
        pointTangents3d<Damped, P>(sec, eps, G, Gd, fG, KG, DG);
        return;
      }
    }
    for (int g = 0; g < P; ++g) {
      double Gg[kG], Gdg[kG], fGg[kG], KGg[kG][kG], DGg[kG][kG];
      Calc::template lane<P>(G, g, Gg);
      if (Damped) Calc::template lane<P>(Gd, g, Gdg);
      pointTangent(sec, k0[g], eps[g], Gg, Damped ? Gdg : nullptr, fGg, KGg, DGg);
      for (int k = 0; k < kG; ++k) {
        fG[k][g] = fGg[k];
        for (int l = 0; l < kG; ++l) {
          KG[k][l][g] = KGg[k][l];
          if (Damped) DG[k][l][g] = DGg[k][l];
        }
      }
    }
  }

  // The 3D pointwise tangent without curvature-rate damping, the three curvature components summed
  // in closed form. With C = dc/dG = [-[r'']x, [r']x] (3 x 6), e = (r', 0), the moments m = EI A c,
  // mu = m.c and z = C^T (2m) = 2 (r'' x m, m x r'):
  //   EI sum_i J_i J_i^T = EI (A^2 C^T C - 3AB (C^T c e^T + e c^T C) + 9 B^2 |c|^2 e e^T),
  //   C^T C = [[|r''|^2 I - r'' r''^T, r' r''^T - (r'.r'') I], [sym., |r'|^2 I - r' r'^T]]
  // ([a]x^T [b]x = (a.b) I - b a^T), and with pointTangent's moment terms
  //   K_G = N P1 + EA e e^T (+ EA c_eps e (r'_dot, 0)^T) + (9 EI B^2 |c|^2 + 15 mu s^-7/2) e e^T
  //         - 3 mu B P1 - 3B (z e^T + e z^T) + EI A^2 C^T C + A [[0, E], [E^T, 0]],  E_jk = sum_i m_i eps_ijk,
  //   f_G = (N r' - 3 B mu r' + A r'' x m, A m x r'),   D_G = EA c_eps e e^T.
  // Array form: every statement runs over the points in its innermost loop, so the loops vectorize.
  template <bool Damped, int P>
  static void pointTangents3d(const CableSection& sec, const double eps[P], const double G[6][P], const double Gd[6][P],
                              double fG[6][P], double KG[6][6][P], double DG[6][6][P]) {
    const double(*g1)[P] = G;      // r'
    const double(*g2)[P] = G + 3;  // r''
    double tension[P], A[P], B[P], mu[P], a2[P], ee[P], s1[P], s2[P], s12[P], m[3][P], mc1[3][P], mc2[3][P];
    for (int g = 0; g < P; ++g) {
      s1[g] = g1[0][g] * g1[0][g] + g1[1][g] * g1[1][g] + g1[2][g] * g1[2][g];
      s2[g] = g2[0][g] * g2[0][g] + g2[1][g] * g2[1][g] + g2[2][g] * g2[2][g];
      s12[g] = g1[0][g] * g2[0][g] + g1[1][g] * g2[1][g] + g1[2][g] * g2[2][g];
      A[g] = 1.0 / (s1[g] * std::sqrt(s1[g]));
      B[g] = A[g] / s1[g];
      const double c0 = g1[1][g] * g2[2][g] - g1[2][g] * g2[1][g];
      const double c1 = g1[2][g] * g2[0][g] - g1[0][g] * g2[2][g];
      const double c2 = g1[0][g] * g2[1][g] - g1[1][g] * g2[0][g];
      m[0][g] = sec.EI * A[g] * c0;
      m[1][g] = sec.EI * A[g] * c1;
      m[2][g] = sec.EI * A[g] * c2;
      mu[g] = m[0][g] * c0 + m[1][g] * c1 + m[2][g] * c2;
      a2[g] = sec.EI * A[g] * A[g];
      ee[g] = 9.0 * sec.EI * B[g] * B[g] * (c0 * c0 + c1 * c1 + c2 * c2) + 15.0 * mu[g] * B[g] / s1[g];
      tension[g] = sec.EA * eps[g];
      if (Damped)
        tension[g] += sec.EA * sec.dampAxial * (g1[0][g] * Gd[0][g] + g1[1][g] * Gd[1][g] + g1[2][g] * Gd[2][g]);
    }
    for (int i = 0; i < 3; ++i) {  // r'' x m and m x r'
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      for (int g = 0; g < P; ++g) {
        mc1[i][g] = g2[j][g] * m[k][g] - g2[k][g] * m[j][g];
        mc2[i][g] = m[j][g] * g1[k][g] - m[k][g] * g1[j][g];
        fG[i][g] = (tension[g] - 3.0 * B[g] * mu[g]) * g1[i][g] + A[g] * mc1[i][g];
        fG[3 + i][g] = A[g] * mc2[i][g];
      }
    }
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) {
        const double same = j == k ? 1.0 : 0.0;
        const int i = j == k ? 0 : 3 - j - k;  // E_jk = eps_ijk m_i
        const double levi = j == k ? 0.0 : crossHessianE(i, j, k);
        for (int g = 0; g < P; ++g) {
          double rr = (sec.EA + ee[g]) * g1[j][g] * g1[k][g] - a2[g] * g2[j][g] * g2[k][g] -
                      6.0 * B[g] * (mc1[j][g] * g1[k][g] + g1[j][g] * mc1[k][g]) +
                      same * (tension[g] + a2[g] * s2[g] - 3.0 * mu[g] * B[g]);
          if (Damped) {
            rr += sec.EA * sec.dampAxial * g1[j][g] * Gd[k][g];
            DG[j][k][g] = sec.EA * sec.dampAxial * g1[j][g] * g1[k][g];
            DG[j][3 + k][g] = DG[3 + j][k][g] = DG[3 + j][3 + k][g] = 0.0;
          }
          const double rs = a2[g] * (g1[j][g] * g2[k][g] - same * s12[g]) + A[g] * levi * m[i][g] -
                            6.0 * B[g] * g1[j][g] * mc2[k][g];
          KG[j][k][g] = rr;
          KG[j][3 + k][g] = rs;
          KG[3 + k][j][g] = rs;
          KG[3 + j][3 + k][g] = a2[g] * (same * s1[g] - g1[j][g] * g1[k][g]);
        }
      }
  }

  template <int P>
  [[gnu::noinline]] static void tangentAt(const CableSection& sec, const Geometry& geo, const CablePointTable& t, const double* q0,
                        const double* u, const double* v, double* f, double* K, double* Dm) {
    double G[kG][P], Gd[kG][P], eps[P], k0[P], fG[kG][P], KG[kG][kG][P], DG[kG][kG][P];
    pointKinematics<P>(t, q0, u, G, eps, geo.eps0);
    referenceCurvature<P>(geo, t, k0);
    if (v) {
      Calc::template gather<P>(t, v, Gd);
      pointTangents<true, P>(sec, k0, eps, G, Gd, fG, KG, DG);
    } else {
      pointTangents<false, P>(sec, k0, eps, G, G, fG, KG, DG);  // (the rates argument is unused)
    }
    if (f) Calc::template integrateForce<P>(t, fG, f);
    Calc::template integrateMatrix<P>(t, KG, K, !v);
    if (!v) Calc::mirrorUpper(K);  // K is symmetric without damping: only blocks b >= a were summed
    Calc::completeFirstPosition(K);
    if (Dm && v) {
      Calc::template integrateMatrix<P>(t, DG, Dm, false);
      Calc::completeFirstPosition(Dm);
    } else if (Dm) {
      for (int k = 0; k < kDof * kDof; ++k) Dm[k] = 0.0;
    }
  }

public:
  // ---- the pointwise law (also used by the ALE cable, AleCable.hpp) ----

  // Pointwise generalized force f_G = N de/dG + m . dkappa/dG, with dkappa_i/dG = A dc_i/dG -
  // 3 c_i B (r', 0) (A = s^-3/2, B = s^-5/2, s = r'.r'). The sum over the curvature components
  // collapses: sum_i m_i dc_i/dG = (r'' x m, m x r') for c = r' x r'' (2D: m along z), so
  //   f_G = (N r' - 3 B (m.c) r' + A r'' x m,  A m x r').
  // The curvature rate (damping) is A dc - 3 B c (r'.r'_dot) with dc = r'_dot x r'' + r' x r''_dot.
  // k0: the reference curvature (2D; 0 in 3D).
  template <class S>
  [[gnu::always_inline]] static void pointForce(const CableSection& sec, double k0, const S& eps, const S* G, const S* Gd, S* fG) {
    const S* g1 = G;
    const S* g2 = G + D;
    S s = g1[0] * g1[0];
    for (int i = 1; i < D; ++i) s += g1[i] * g1[i];
    using std::sqrt;
    const S A = 1.0 / (s * sqrt(s)), B = A / s;  // s^(-3/2), s^(-5/2)
    S c[kCurv];
    cross(g1, g2, c);
    S tension = sec.EA * eps, stretchRate(0.0), dc[kCurv];
    if (Gd) {
      for (int i = 0; i < D; ++i) stretchRate += g1[i] * Gd[i];
      tension += sec.EA * sec.dampAxial * stretchRate;
      S d1[kCurv], d2[kCurv];
      cross(Gd, g2, d1);
      cross(g1, Gd + D, d2);
      for (int i = 0; i < kCurv; ++i) dc[i] = d1[i] + d2[i];
    }
    S m[kCurv], mu(0.0);
    for (int ci = 0; ci < kCurv; ++ci) {
      m[ci] = sec.EI * (c[ci] * A - k0);
      if (Gd) m[ci] += sec.EI * sec.dampBending * (A * dc[ci] - 3.0 * B * c[ci] * stretchRate);
      mu += m[ci] * c[ci];
    }
    S mc1[D], mc2[D];  // sum_i m_i dc_i/dr', sum_i m_i dc_i/dr''
    if constexpr (D == 2) {
      mc1[0] = g2[1] * m[0];
      mc1[1] = -g2[0] * m[0];
      mc2[0] = -g1[1] * m[0];
      mc2[1] = g1[0] * m[0];
    } else {
      cross(g2, m, mc1);
      cross(m, g1, mc2);
    }
    const S axial = tension - 3.0 * B * mu;
    for (int i = 0; i < D; ++i) {
      fG[i] = axial * g1[i] + A * mc1[i];
      fG[D + i] = A * mc2[i];
    }
  }

  // dc/dG for c = r' x r''.
  template <class S>
  static void crossGradient(const S* G, S cG[kCurv][kG]) {
    const S* g1 = G;
    const S* g2 = G + D;
    if constexpr (D == 2) {
      cG[0][0] = g2[1]; cG[0][1] = -g2[0]; cG[0][2] = -g1[1]; cG[0][3] = g1[0];
    } else {
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < kG; ++k) cG[i][k] = S(0.0);
      cG[0][1] = g2[2];  cG[0][2] = -g2[1]; cG[0][4] = -g1[2]; cG[0][5] = g1[1];
      cG[1][0] = -g2[2]; cG[1][2] = g2[0];  cG[1][3] = g1[2];  cG[1][5] = -g1[0];
      cG[2][0] = g2[1];  cG[2][1] = -g2[0]; cG[2][3] = -g1[1]; cG[2][4] = g1[0];
    }
  }

  // d2c_i/dG2: constant, [[0, E_i], [E_i^T, 0]] with (E_i)_jk = d2 c_i / dr'_j dr''_k.
  static double crossHessianE(int i, int j, int k) {
    if constexpr (D == 2) {
      (void)i;
      return (j == 0 && k == 1) ? 1.0 : (j == 1 && k == 0) ? -1.0 : 0.0;
    } else {
      // Levi-Civita epsilon_ijk
      if (i == j || j == k || i == k) return 0.0;
      return ((i == 0 && j == 1) || (i == 1 && j == 2) || (i == 2 && j == 0)) ? 1.0 : -1.0;
    }
  }

  // Pointwise force, stiffness K_G = df_G/dG and damping D_G = df_G/dGd, derived by hand:
  //   f_G  = N e_G + sum_i m_i J_i,        e_G = (r', 0), J_i = dkappa_i/dG
  //   K_G  = EA e_G e_G^T + N P1 + EA c_eps e_G (r'_dot, 0)^T
  //        + EI J^T J + sum_i m_i H_i + EI c_kap sum_i J_i (H_i Gd)^T
  //   D_G  = EA c_eps e_G e_G^T + EI c_kap J^T J
  // with P1 = d e_G/dG and the curvature Hessian (A = s^-3/2, B = s^-5/2, s = r'.r')
  //   H_i  = A c_i,GG - 3B (c_i,G e_G^T + e_G c_i,G^T) + 15 c_i s^-7/2 e_G e_G^T - 3 c_i B P1.
  // (3D without curvature-rate damping: pointTangents3d, the same terms in closed form.)
  [[gnu::always_inline]] static void pointTangent(const CableSection& sec, double k0, double eps, const double* G,
                                                  const double* Gd, double* fG, double KG[kG][kG], double DG[kG][kG]) {
    double s = 0.0;
    for (int i = 0; i < D; ++i) s += G[i] * G[i];
    const double A = 1.0 / (s * std::sqrt(s)), B = A / s, C7 = B / s;
    double c[kCurv], cG[kCurv][kG];
    cross(G, G + D, c);
    double tension = sec.EA * eps;
    const double cEps = Gd ? sec.dampAxial : 0.0, cKap = Gd ? sec.dampBending : 0.0;
    if (Gd) {
      double epsDot = 0.0;
      for (int i = 0; i < D; ++i) epsDot += G[i] * Gd[i];
      tension += sec.EA * cEps * epsDot;
    }
    for (int a = 0; a < kG; ++a) {
      fG[a] = 0.0;
      for (int b = 0; b < kG; ++b) KG[a][b] = DG[a][b] = 0.0;
    }
    // axial part
    for (int i = 0; i < D; ++i) {
      fG[i] = tension * G[i];
      KG[i][i] += tension;
      for (int j = 0; j < D; ++j) {
        KG[i][j] += sec.EA * G[i] * G[j];
        if (Gd) {
          KG[i][j] += sec.EA * cEps * G[i] * Gd[j];
          DG[i][j] += sec.EA * cEps * G[i] * G[j];
        }
      }
    }
    crossGradient(G, cG);
    // bending part. sum_i m_i H_i collapses to rank-one terms in w = sum_i m_i c_i,G and
    // mu = sum_i m_i c_i (plus the constant c_i,GG), so no Hessian is formed per component.
    double J[kCurv][kG], moment[kCurv], w[kG] = {}, mu = 0.0;
    for (int ci = 0; ci < kCurv; ++ci) {
      for (int k = 0; k < kG; ++k) J[ci][k] = A * cG[ci][k];
      for (int i = 0; i < D; ++i) J[ci][i] -= 3.0 * c[ci] * B * G[i];
      moment[ci] = sec.EI * (c[ci] * A - k0);
      if (Gd) {
        double kDot = 0.0;
        for (int k = 0; k < kG; ++k) kDot += J[ci][k] * Gd[k];
        moment[ci] += sec.EI * cKap * kDot;
      }
      for (int k = 0; k < kG; ++k) {
        fG[k] += moment[ci] * J[ci][k];
        w[k] += moment[ci] * cG[ci][k];
      }
      mu += moment[ci] * c[ci];
    }
    // EI J^T J
    for (int ci = 0; ci < kCurv; ++ci)
      for (int a = 0; a < kG; ++a) {
        const double t = sec.EI * J[ci][a];
        for (int b = 0; b < kG; ++b) KG[a][b] += t * J[ci][b];
      }
    // sum_i m_i H_i = A sum_i m_i c_i,GG - 3B (w e_G^T + e_G w^T) + 15 mu s^-7/2 e_G e_G^T - 3 mu B P1
    for (int j = 0; j < D; ++j)
      for (int k = 0; k < D; ++k) {
        double e = 0.0;
        for (int ci = 0; ci < kCurv; ++ci) e += moment[ci] * crossHessianE(ci, j, k);
        KG[j][D + k] += A * e;
        KG[D + k][j] += A * e;
      }
    for (int a = 0; a < kG; ++a)
      for (int j = 0; j < D; ++j) {
        const double t = -3.0 * B * w[a] * G[j];
        KG[a][j] += t;
        KG[j][a] += t;
      }
    for (int i = 0; i < D; ++i) {
      for (int j = 0; j < D; ++j) KG[i][j] += 15.0 * mu * C7 * G[i] * G[j];
      KG[i][i] -= 3.0 * mu * B;
    }
    if (Gd && cKap != 0.0) {
      // EI c_kap sum_i J_i (H_i Gd)^T and D_G = EI c_kap J^T J, with H_i formed only here
      for (int ci = 0; ci < kCurv; ++ci) {
        double HGd[kG] = {};
        for (int j = 0; j < D; ++j)
          for (int k = 0; k < D; ++k) {
            const double e = A * crossHessianE(ci, j, k);
            HGd[j] += e * Gd[D + k];
            HGd[D + k] += e * Gd[j];
          }
        double eGd = 0.0, cGGd = 0.0;
        for (int j = 0; j < D; ++j) eGd += G[j] * Gd[j];
        for (int k = 0; k < kG; ++k) cGGd += cG[ci][k] * Gd[k];
        for (int a = 0; a < kG; ++a) HGd[a] += -3.0 * B * cG[ci][a] * eGd;
        for (int j = 0; j < D; ++j) {
          HGd[j] += -3.0 * B * G[j] * cGGd + 15.0 * c[ci] * C7 * G[j] * eGd - 3.0 * c[ci] * B * Gd[j];
        }
        for (int a = 0; a < kG; ++a)
          for (int b = 0; b < kG; ++b) {
            KG[a][b] += sec.EI * cKap * J[ci][a] * HGd[b];
            DG[a][b] += sec.EI * cKap * J[ci][a] * J[ci][b];
          }
      }
    }
  }

};

using AncfCable2d = AncfCable<2>;
using AncfCable3d = AncfCable<3>;

}  // namespace strand::elements
