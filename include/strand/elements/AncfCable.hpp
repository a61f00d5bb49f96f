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
// Sign convention (docs/architecture.md): f is the internal force on the left-hand side,
//   M a + f_int(q, v) - f_ext = 0.
#pragma once
#include <array>
#include <cmath>

#include "strand/elements/CableSection.hpp"
#include "strand/elements/CableShapeTable.hpp"

namespace strand::elements {

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

  // Shape-function values N and their x-derivatives B1, B2 for the four coordinate slots.
  struct Slots {
    double N[4], B1[4], B2[4];
  };

  struct Geometry {
    double length = 0.0;                 // reference length l of the element [m]
    double slopeScale[2] = {1.0, 1.0};   // sigma of node 1 and 2
    const double* kappa0 = nullptr;      // reference curvature at each Gauss point, 2D (null: 0)
    // slots() precomputed at the points of one table (uniform elements); used only with that table
    const Slots* atGauss = nullptr;
    const CableShapeTable* atGaussOf = nullptr;
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
  static Slots slotsAt(const Geometry& geo, const CableShapeTable& tab, int g) {
    return (geo.atGauss && geo.atGaussOf == &tab) ? geo.atGauss[g] : slots(geo, tab.at[g]);
  }

  // ---- pointwise kinematics, templated on the scalar (double, or math::Dual for tests) ----

  // c = r' x r'' (2D: the scalar z-component).
  template <class S>
  static void cross(const S* g1, const S* g2, S* c) {
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

  // Curvature vector kappa = r' x r'' / |r'|^3 (the axial strain comes from kinematics()).
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

  // Pointwise G = G0 + Gu and the axial strain eps = r0'.u' + u'.u'/2 (no cancellation).
  template <class S>
  static S kinematics(const Slots& sl, const double* q0, const S* u, S* G) {
    double G0[kG];
    S Gu[kG];
    gather(sl, q0, G0);
    gather(sl, u, Gu);
    S eps(0.0);
    for (int i = 0; i < D; ++i) eps += G0[i] * Gu[i] + 0.5 * Gu[i] * Gu[i];
    for (int k = 0; k < kG; ++k) G[k] = G0[k] + Gu[k];
    return eps;
  }

  // Strain energy of the element (no damping): int W dx.
  template <class S>
  static S strainEnergy(const CableSection& sec, const Geometry& geo, const CableShapeTable& tab,
                        const double* q0, const S* u) {
    S U(0.0);
    for (int g = 0; g < tab.size(); ++g) {
      const Slots sl = slotsAt(geo, tab, g);
      S G[kG];
      const S eps = kinematics(sl, q0, u, G);
      S w = 0.5 * sec.EA * eps * eps;
      if constexpr (D == 3) {  // no reference curvature: |kappa|^2 = |r' x r''|^2 / s^3, no root
        S c[3], s = G[0] * G[0] + G[1] * G[1] + G[2] * G[2];
        cross(G, G + D, c);
        w += 0.5 * sec.EI * (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / (s * s * s);
      } else {
        S kap[kCurv];
        curvature(G, kap);
        const double k0 = geo.kappa0 ? geo.kappa0[g] : 0.0;
        w += 0.5 * sec.EI * (kap[0] - k0) * (kap[0] - k0);
      }
      U += tab.rule.w[g] * geo.length * w;
    }
    return U;
  }

  // Rayleigh dissipation function R = int 1/2 (EA c_eps deps^2 + EI c_kap |dkappa|^2) dx;
  // the damping force is dR/dv (tests check it), the dissipated power is 2R.
  template <class S>
  static S dissipation(const CableSection& sec, const Geometry& geo, const CableShapeTable& tab,
                       const double* q0, const S* u, const S* v) {
    S R(0.0);
    for (int g = 0; g < tab.size(); ++g) {
      const Slots sl = slotsAt(geo, tab, g);
      S G[kG], Gd[kG];
      kinematics(sl, q0, u, G);
      gather(sl, v, Gd);
      S epsDot = G[0] * Gd[0];
      for (int i = 1; i < D; ++i) epsDot += G[i] * Gd[i];
      // kappa-dot by the exact time derivative of c / s^(3/2)
      S s = G[0] * G[0], sDot = 2.0 * G[0] * Gd[0];
      for (int i = 1; i < D; ++i) { s += G[i] * G[i]; sDot += 2.0 * G[i] * Gd[i]; }
      using std::sqrt;
      const S s32 = s * sqrt(s);
      S c[kCurv], c1[kCurv], c2[kCurv];
      cross(G, G + D, c);
      cross(Gd, G + D, c1);
      cross(G, Gd + D, c2);
      S r = 0.5 * sec.EA * sec.dampAxial * epsDot * epsDot;
      for (int i = 0; i < kCurv; ++i) {
        const S kd = (c1[i] + c2[i]) / s32 - 1.5 * c[i] * sDot / (s32 * s);
        r += 0.5 * sec.EI * sec.dampBending * kd * kd;
      }
      R += tab.rule.w[g] * geo.length * r;
    }
    return R;
  }

  // ---- residual and tangent ----

  // Internal force f_int(u, v) = dU/du + dR/dv (elastic + Kelvin-Voigt damping) at q = q0 + u.
  template <class S>
  static void force(const CableSection& sec, const Geometry& geo, const CableShapeTable& tab,
                    const double* q0, const S* u, const S* v, S* f) {
    for (int k = 0; k < kDof; ++k) f[k] = S(0.0);
    const bool damped = v && (sec.dampAxial != 0.0 || sec.dampBending != 0.0);
    for (int g = 0; g < tab.size(); ++g) {
      const Slots sl = slotsAt(geo, tab, g);
      S G[kG], Gd[kG];
      const S eps = kinematics(sl, q0, u, G);
      if (damped) gather(sl, v, Gd);
      S fG[kG];
      pointForce(sec, geo, g, eps, G, damped ? Gd : nullptr, fG);
      const double wl = tab.rule.w[g] * geo.length;
      for (int a = 1; a < 4; ++a)
        for (int i = 0; i < D; ++i) f[a * D + i] += wl * (sl.B1[a] * fG[i] + sl.B2[a] * fG[D + i]);
    }
    for (int i = 0; i < D; ++i) f[i] = -f[2 * D + i];  // B_0 = -B_2 (completeFirstPosition)
  }

  // K = df/dq and Dm = df/dv (row-major kDof x kDof), returned separately (design section 2).
  // f (optional) receives the internal force; Dm may be null.
  static void tangent(const CableSection& sec, const Geometry& geo, const CableShapeTable& tab,
                      const double* q0, const double* u, const double* v, double* f, double* K, double* Dm) {
    for (int k = 0; k < kDof * kDof; ++k) K[k] = 0.0;
    if (Dm)
      for (int k = 0; k < kDof * kDof; ++k) Dm[k] = 0.0;
    if (f)
      for (int k = 0; k < kDof; ++k) f[k] = 0.0;
    const bool damped = v && (sec.dampAxial != 0.0 || sec.dampBending != 0.0);
    for (int g = 0; g < tab.size(); ++g) {
      const Slots sl = slotsAt(geo, tab, g);
      double G[kG], Gd[kG] = {};
      const double eps = kinematics(sl, q0, u, G);
      if (damped) gather(sl, v, Gd);
      double fG[kG], KG[kG][kG], DG[kG][kG];
      pointTangent(sec, geo, g, eps, G, damped ? Gd : nullptr, fG, KG, DG);
      const double wl = tab.rule.w[g] * geo.length;
      if (f)
        for (int a = 1; a < 4; ++a)
          for (int i = 0; i < D; ++i) f[a * D + i] += wl * (sl.B1[a] * fG[i] + sl.B2[a] * fG[D + i]);
      scatterPointMatrix(sl, wl, KG, K, !damped);
      if (Dm && damped) scatterPointMatrix(sl, wl, DG, Dm, false);
    }
    if (!damped)  // K is symmetric without damping: only blocks b >= a were summed
      for (int r = D; r < kDof; ++r)
        for (int c = (r / D + 1) * D; c < kDof; ++c) K[c * kDof + r] = K[r * kDof + c];
    completeFirstPosition(K);
    if (Dm && damped) completeFirstPosition(Dm);
    if (f)
      for (int i = 0; i < D; ++i) f[i] = -f[2 * D + i];
  }

  // Consistent mass M = rhoA int N^T N dx (constant). tab must integrate degree 6 exactly (>= 4 points).
  static void mass(const CableSection& sec, const Geometry& geo, const CableShapeTable& tab, double* M) {
    double m[4][4] = {};
    for (int g = 0; g < tab.size(); ++g) {
      const Slots sl = slotsAt(geo, tab, g);
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
      const Slots sl = slotsAt(geo, tab, g);
      const double wl = tab.rule.w[g] * geo.length;
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < D; ++i) f[a * D + i] += wl * sl.N[a] * p[i];
    }
  }

private:
  // Pointwise generalized force f_G = N de/dG + m . dkappa/dG, with dkappa_i/dG = A dc_i/dG -
  // 3 c_i B (r', 0) (A = s^-3/2, B = s^-5/2, s = r'.r'). The sum over the curvature components
  // collapses: sum_i m_i dc_i/dG = (r'' x m, m x r') for c = r' x r'' (2D: m along z), so
  //   f_G = (N r' - 3 B (m.c) r' + A r'' x m,  A m x r').
  // The curvature rate (damping) is A dc - 3 B c (r'.r'_dot) with dc = r'_dot x r'' + r' x r''_dot.
  template <class S>
  static void pointForce(const CableSection& sec, const Geometry& geo, int g, const S& eps, const S* G, const S* Gd,
                         S* fG) {
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
      const double k0 = (geo.kappa0 && D == 2) ? geo.kappa0[g * kCurv + ci] : 0.0;
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
  static void pointTangent(const CableSection& sec, const Geometry& geo, int g, double eps, const double* G,
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
    if constexpr (D == 3) {
      if (cKap == 0.0) {  // no curvature-rate damping: the closed form below
        bendingTangent3d(sec.EI, A, B, C7, G, c, fG, KG);
        return;
      }
    }
    crossGradient(G, cG);
    // bending part. sum_i m_i H_i collapses to rank-one terms in w = sum_i m_i c_i,G and
    // mu = sum_i m_i c_i (plus the constant c_i,GG), so no Hessian is formed per component.
    double J[kCurv][kG], moment[kCurv], w[kG] = {}, mu = 0.0;
    for (int ci = 0; ci < kCurv; ++ci) {
      for (int k = 0; k < kG; ++k) J[ci][k] = A * cG[ci][k];
      for (int i = 0; i < D; ++i) J[ci][i] -= 3.0 * c[ci] * B * G[i];
      const double k0 = (geo.kappa0 && D == 2) ? geo.kappa0[g * kCurv + ci] : 0.0;
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

  // The bending part of pointTangent in 3D without curvature-rate damping, summed over the three
  // curvature components in closed form. With C = dc/dG = [-[r'']x, [r']x] (3 x 6), the moments
  // m = EI A c, mu = m.c, p = m + EI A c and z = C^T p = (r'' x p, p x r'):
  //   EI sum_i J_i J_i^T = EI (A^2 C^T C - 3AB (C^T c e^T + e c^T C) + 9 B^2 |c|^2 e e^T),
  //   C^T C = [[|r''|^2 I - r'' r''^T, r' r''^T - (r'.r'') I], [sym., |r'|^2 I - r' r'^T]]
  // ([a]x^T [b]x = (a.b) I - b a^T), and with pointTangent's moment terms
  //   K_G += (9 EI B^2 |c|^2 + 15 mu s^-7/2) e e^T - 3 mu B P1 - 3B (z e^T + e z^T)
  //          + EI A^2 C^T C + A [[0, E], [E^T, 0]],   E_jk = sum_i m_i eps_ijk,
  // and f_G += (-3 B mu r' + A r'' x m, A m x r'). Same terms as the general path, fewer flops.
  static void bendingTangent3d(double EI, double A, double B, double C7, const double* G, const double* c, double* fG,
                               double KG[kG][kG]) {
    const double* g1 = G;
    const double* g2 = G + 3;
    double m[3], p[3], mu = 0.0, cc = 0.0;
    for (int i = 0; i < 3; ++i) {
      m[i] = EI * A * c[i];
      p[i] = 2.0 * m[i];  // m + EI A c
      mu += m[i] * c[i];
      cc += c[i] * c[i];
    }
    double mc1[3], mc2[3], z1[3], z2[3];
    cross(g2, m, mc1);
    cross(m, g1, mc2);
    cross(g2, p, z1);
    cross(p, g1, z2);
    double s1 = 0.0, s2 = 0.0, s12 = 0.0;
    for (int i = 0; i < 3; ++i) {
      s1 += g1[i] * g1[i];
      s2 += g2[i] * g2[i];
      s12 += g1[i] * g2[i];
      fG[i] += -3.0 * B * mu * g1[i] + A * mc1[i];
      fG[3 + i] += A * mc2[i];
    }
    const double a2 = EI * A * A, ee = 9.0 * EI * B * B * cc + 15.0 * mu * C7;
    const double E[3][3] = {{0.0, m[2], -m[1]}, {-m[2], 0.0, m[0]}, {m[1], -m[0], 0.0}};
    for (int j = 0; j < 3; ++j) {
      KG[j][j] += a2 * s2 - 3.0 * mu * B;
      KG[3 + j][3 + j] += a2 * s1;
      KG[j][3 + j] -= a2 * s12;
      KG[3 + j][j] -= a2 * s12;
      for (int k = 0; k < 3; ++k) {
        KG[j][k] += ee * g1[j] * g1[k] - a2 * g2[j] * g2[k] - 3.0 * B * (z1[j] * g1[k] + g1[j] * z1[k]);
        const double offDiagonal = a2 * g1[j] * g2[k] + A * E[j][k] - 3.0 * B * g1[j] * z2[k];
        KG[j][3 + k] += offDiagonal;
        KG[3 + k][j] += offDiagonal;
        KG[3 + j][3 + k] -= a2 * g1[j] * g1[k];
      }
    }
  }

  // Element matrix += wl * sum_{alpha,beta} B_alpha[a] X[alpha i][beta j] B_beta[b] for the slots
  // a, b = 1..3; with upperOnly, only the blocks b >= a (the caller mirrors a symmetric result).
  // Slot 0 (position of node 1) follows from completeFirstPosition.
  static void scatterPointMatrix(const Slots& sl, double wl, const double X[kG][kG], double* K, bool upperOnly) {
    for (int a = 1; a < 4; ++a) {
      double T[D][kG];  // rows of node-slot a: B1_a X[r', :] + B2_a X[r'', :]
      for (int i = 0; i < D; ++i)
        for (int k = 0; k < kG; ++k) T[i][k] = wl * (sl.B1[a] * X[i][k] + sl.B2[a] * X[D + i][k]);
      for (int b = upperOnly ? a : 1; b < 4; ++b)
        for (int i = 0; i < D; ++i) {
          double* row = K + (a * D + i) * kDof + b * D;
          for (int j = 0; j < D; ++j) row[j] += T[i][j] * sl.B1[b] + T[i][D + j] * sl.B2[b];
        }
    }
  }

  // The strains see the positions only through the chord r_2 - r_1 (gather), so the derivative
  // weights of the two position slots are opposite (B_0 = -B_2): the rows and the columns of
  // slot 0 are minus those of slot 2, and block (0, 0) equals block (2, 2).
  static void completeFirstPosition(double* K) {
    for (int r = D; r < kDof; ++r)
      for (int j = 0; j < D; ++j) K[r * kDof + j] = -K[r * kDof + 2 * D + j];
    for (int i = 0; i < D; ++i)
      for (int c = 0; c < kDof; ++c) K[i * kDof + c] = -K[(2 * D + i) * kDof + c];
  }
};

using AncfCable2d = AncfCable<2>;
using AncfCable3d = AncfCable<3>;

}  // namespace strand::elements
