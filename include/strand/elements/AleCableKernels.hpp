// The ALE cable's element forces with the Gauss points of an element as arrays (AleCable.hpp has
// the formulation; docs/architecture.md, decisions 19 and 29). Each function evaluates its points
// as X[...][g] over a compile-time count P (the rule padded with zero-weight copies of its last
// point to an even count, SlotIntegration.hpp's withPaddedPoints), so that the compiler evaluates
// two or more points per instruction; the pointwise physics is the cable's pointForce.
//
// Element layout (D coordinates per slot): x1 = 0, s1 = D, p1 = 2D, x2 = 3D, s2 = 4D, p2 = 5D
// (positions, slopes r' = dr/dp, material coordinates in component 0 of their block). Positions
// enter through the chord x2 - x1 and the element length as (p2 - p1) of the reference plus that of
// the displacements, so that neither carries the round-off of the absolute coordinates (AncfCable's
// gather does the same).
#pragma once
#include <cmath>
#include <stdexcept>

#include "strand/core/KernelClones.hpp"
#include "strand/elements/AncfCable.hpp"
#include "strand/math/Gauss.hpp"
#include "strand/math/Hermite.hpp"

namespace strand::elements {

// The points of one rule as arrays: positions xi_g in [0, 1], weights and the cubic Hermite
// functions h_k(xi_g) with their first and second derivatives; padded points have zero weight.
struct AlePointArrays {
  static constexpr int kMax = 8;
  int count = 0, padded = 0;
  double x[kMax], w[kMax], h[4][kMax], dh[4][kMax], ddh[4][kMax];

  static AlePointArrays of(const math::QuadratureRule& rule) {
    if (rule.size() < 1 || rule.size() > kMax) throw std::invalid_argument("ALE kinds: 1 to 8 Gauss points");
    AlePointArrays t;
    t.count = rule.size();
    t.padded = t.count + t.count % 2;
    for (int g = 0; g < kMax; ++g) {
      const int from = g < t.count ? g : t.count - 1;
      const math::HermiteValues hv = math::hermite(rule.x[from]);
      t.x[g] = rule.x[from];
      t.w[g] = g < t.count ? rule.w[g] : 0.0;
      for (int k = 0; k < 4; ++k) t.h[k][g] = hv.s[k], t.dh[k][g] = hv.ds[k], t.ddh[k][g] = hv.dds[k];
    }
    return t;
  }
};

template <int D>
struct AleCableKernels {
  using Cable = AncfCable<D>;
  static constexpr int kG = 2 * D;
  static constexpr int kDof = 6 * D;
  static constexpr int kX1 = 0, kS1 = D, kP1 = 2 * D, kX2 = 3 * D, kS2 = 4 * D, kP2 = 5 * D;

  // sum_g t[g] as a pairwise tree: the terms are formed elementwise over the points (vectorized),
  // and the halves are added pairwise, which the compiler vectorizes too (a running sum it may not
  // reorder).
  template <int P, class S>
  [[gnu::always_inline]] static S sum(const S* t) {
    if constexpr (P == 1) {
      return t[0];
    } else if constexpr (P % 2 == 1) {
      return sum<P - 1>(t) + t[P - 1];
    } else {
      S h[P / 2];
      for (int g = 0; g < P / 2; ++g) h[g] = t[g] + t[g + P / 2];
      return sum<P / 2>(h);
    }
  }

  // The element's current chord, slopes and material length (relative forms, see above).
  template <class S>
  struct Nodes {
    S chord[D], s1[D], s2[D], L;
    Nodes(const double* q0, const S* u) {
      for (int i = 0; i < D; ++i) {
        chord[i] = (q0[kX2 + i] - q0[kX1 + i]) + (u[kX2 + i] - u[kX1 + i]);
        s1[i] = q0[kS1 + i] + u[kS1 + i];
        s2[i] = q0[kS2 + i] + u[kS2 + i];
      }
      L = (q0[kP2] - q0[kP1]) + (u[kP2] - u[kP1]);
    }
  };

  // G = (r', r'') at the points and G_L = dG/dL at fixed coordinates. With h0' = -h2':
  //   r' = h2' chord / L + h1' s1 + h3' s2,   r'' = (h2'' chord / L + h1'' s1 + h3'' s2) / L.
  template <int P, class S>
  static void kinematics(const AlePointArrays& t, const Nodes<S>& n, const S& iL, S G[kG][P], S GL[kG][P]) {
    for (int i = 0; i < D; ++i) {
      const S d = n.chord[i] * iL;
      for (int g = 0; g < P; ++g) {
        const S bend = t.ddh[1][g] * n.s1[i] + t.ddh[3][g] * n.s2[i], a = t.ddh[2][g] * d;
        G[i][g] = t.dh[2][g] * d + t.dh[1][g] * n.s1[i] + t.dh[3][g] * n.s2[i];
        G[D + i][g] = (a + bend) * iL;
        GL[i][g] = -t.dh[2][g] * d * iL;
        GL[D + i][g] = -(2.0 * a + bend) * iL * iL;
      }
    }
  }

  // G alone (kinematics without G_L: the undamped force and the strain energy).
  template <int P, class S>
  static void positionGradients(const AlePointArrays& t, const Nodes<S>& n, const S& iL, S G[kG][P]) {
    for (int i = 0; i < D; ++i) {
      const S d = n.chord[i] * iL;
      for (int g = 0; g < P; ++g) {
        G[i][g] = t.dh[2][g] * d + t.dh[1][g] * n.s1[i] + t.dh[3][g] * n.s2[i];
        G[D + i][g] = (t.ddh[2][g] * d + t.ddh[1][g] * n.s1[i] + t.ddh[3][g] * n.s2[i]) * iL;
      }
    }
  }

  // The material rate of G (AleCable::force): Gdot = G(v) + G_L Ldot + (L r'', L r''') xidot, with
  // r''' = (-12 chord / L + 6 (s1 + s2)) / L^2 (uniform: h''' = 12, 6, -12, 6) and
  // xidot = -((1 - xi) p1dot + xi p2dot) / L.
  template <int P, class S>
  static void materialRates(const AlePointArrays& t, const Nodes<S>& n, const S& iL, const S* v, const S G[kG][P],
                            const S GL[kG][P], S Gd[kG][P]) {
    const S Ldot = v[kP2] - v[kP1];
    S xid[P];
    for (int g = 0; g < P; ++g) xid[g] = -((1.0 - t.x[g]) * v[kP1] + t.x[g] * v[kP2]) * iL;
    for (int i = 0; i < D; ++i) {
      const S dv = (v[kX2 + i] - v[kX1 + i]) * iL, r3 = (-12.0 * n.chord[i] * iL + 6.0 * (n.s1[i] + n.s2[i])) * iL * iL;
      for (int g = 0; g < P; ++g) {
        const S Gv1 = t.dh[2][g] * dv + t.dh[1][g] * v[kS1 + i] + t.dh[3][g] * v[kS2 + i];
        const S Gv2 = (t.ddh[2][g] * dv + t.ddh[1][g] * v[kS1 + i] + t.ddh[3][g] * v[kS2 + i]) * iL;
        Gd[i][g] = Gv1 + GL[i][g] * Ldot + n.L * G[D + i][g] * xid[g];
        Gd[D + i][g] = Gv2 + GL[D + i][g] * Ldot + n.L * r3 * xid[g];
      }
    }
  }

  // W = EA eps^2 / 2 + EI |r' x r''|^2 / (2 |r'|^6), eps = (|r'|^2 - 1) / 2, at every point,
  // elementwise over the points (point by point the loop compiled to scalar roots and divisions);
  // |kappa|^2 = |r' x r''|^2 / s^3 needs no root.
  template <int P, class S>
  static void energyDensities(const CableSection& sec, const S G[kG][P], S W[P]) {
    for (int g = 0; g < P; ++g) {
      S s = G[0][g] * G[0][g];
      for (int i = 1; i < D; ++i) s += G[i][g] * G[i][g];
      S c2;
      if constexpr (D == 2) {
        const S c = G[0][g] * G[3][g] - G[1][g] * G[2][g];
        c2 = c * c;
      } else {
        const S cx = G[1][g] * G[5][g] - G[2][g] * G[4][g], cy = G[2][g] * G[3][g] - G[0][g] * G[5][g],
                cz = G[0][g] * G[4][g] - G[1][g] * G[3][g];
        c2 = cx * cx + cy * cy + cz * cz;
      }
      const S eps = 0.5 * (s - 1.0);
      W[g] = 0.5 * sec.EA * eps * eps + 0.5 * sec.EI * c2 / (s * s * s);
    }
  }

  // f = dU/dq (+ the damping force at fixed xi, Damped): the slots get L sum w (B1 f_r' + B2 f_r''),
  // the material coordinates -+ dU/dL = sum w (W + L f_G . G_L). With d = chord / L,
  //   L f_G . G_L = -d . (h2' f_r' + h2'' f_r'' / L) - f_r'' . r''
  // (G_L = (-h2' d, -(h2'' d + L r'') / L) / L), whose first term is the chord force's integrand:
  //   dU/dL = sum w (W - f_r'' . r'') - d . f_chord,
  // so that G_L is formed only for the damping's rates.
  template <int P, bool Damped, class S>
  [[gnu::noinline]] static void force(const CableSection& sec, const AlePointArrays& t, const double* q0, const S* u,
                                      const S* v, S* f) {
    const Nodes<S> n(q0, u);
    const S iL = 1.0 / n.L;
    S G[kG][P], Gd[kG][P], fG[kG][P], W[P];
    if constexpr (Damped) {
      S GL[kG][P];
      kinematics<P>(t, n, iL, G, GL);
      materialRates<P>(t, n, iL, v, G, GL, Gd);
    } else {
      positionGradients<P>(t, n, iL, G);
    }
    for (int g = 0; g < P; ++g) {
      S Gg[kG], Gdg[kG], fGg[kG];
      for (int k = 0; k < kG; ++k) Gg[k] = G[k][g];
      if constexpr (Damped)
        for (int k = 0; k < kG; ++k) Gdg[k] = Gd[k][g];
      S s = Gg[0] * Gg[0];
      for (int i = 1; i < D; ++i) s += Gg[i] * Gg[i];
      Cable::pointForce(sec, 0.0, 0.5 * (s - 1.0), Gg, Damped ? Gdg : static_cast<const S*>(nullptr), fGg);
      for (int k = 0; k < kG; ++k) fG[k][g] = fGg[k];
    }
    energyDensities<P>(sec, G, W);
    for (int k = 0; k < kDof; ++k) f[k] = S(0.0);
    S tL[P];
    for (int g = 0; g < P; ++g) {
      S dot = fG[D][g] * G[D][g];
      for (int i = 1; i < D; ++i) dot += fG[D + i][g] * G[D + i][g];
      tL[g] = t.w[g] * (W[g] - dot);
    }
    S tx[D][P], t1[D][P], t2[D][P];  // the slots' integrands, elementwise over the points
    for (int g = 0; g < P; ++g)
      for (int i = 0; i < D; ++i) {
        tx[i][g] = t.w[g] * (t.dh[2][g] * fG[i][g] + t.ddh[2][g] * iL * fG[D + i][g]);
        t1[i][g] = t.w[g] * (n.L * t.dh[1][g] * fG[i][g] + t.ddh[1][g] * fG[D + i][g]);
        t2[i][g] = t.w[g] * (n.L * t.dh[3][g] * fG[i][g] + t.ddh[3][g] * fG[D + i][g]);
      }
    S fL = sum<P>(tL);
    for (int i = 0; i < D; ++i) {
      const S fx = sum<P>(tx[i]);
      f[kX1 + i] = -fx;
      f[kX2 + i] = fx;
      f[kS1 + i] = sum<P>(t1[i]);
      f[kS2 + i] = sum<P>(t2[i]);
      fL -= n.chord[i] * iL * fx;
    }
    f[kP1] = -fL;
    f[kP2] = fL;
  }

  // U = L sum_g w_g W_g.
  template <int P, class S>
  static S strainEnergy(const CableSection& sec, const AlePointArrays& t, const double* q0, const S* u) {
    const Nodes<S> n(q0, u);
    const S iL = 1.0 / n.L;
    S G[kG][P], W[P];
    positionGradients<P>(t, n, iL, G);
    energyDensities<P>(sec, G, W);
    for (int g = 0; g < P; ++g) W[g] *= t.w[g];
    return n.L * sum<P>(W);
  }

  // The inertial force of the moving material less a load per unit length on it (Moving), or minus
  // the load alone (v, a unused):
  //   F = L sum_g w_g S_g^T (rhoA rddot_g - load),
  // S's columns N_k I (slots) and S_p1, S_p2; rddot of AleCable.hpp (seed 000 Eq. 13-17):
  //   rddot = N a + phi_xi xiddot + phi_L Lddot + 2 v_xi xidot + 2 v_L Ldot + phi_xixi xidot^2 + 2 phi_xiL xidot Ldot,
  //   S_p1 = -phi_xi (1 - xi) / L - phi_L,   S_p2 = -phi_xi xi / L + phi_L,
  // where phi_xi = h2' chord + L (h1' s1 + h3' s2), phi_xiL = h1' s1 + h3' s2, phi_L = h1 s1 + h3 s2,
  // phi_xixi = h2'' chord + L (h1'' s1 + h3'' s2) and v_xi, v_L the same of the velocities.
  template <int P, bool Moving, class S>
  STRAND_KERNEL_CLONES [[gnu::noinline]]
  static void materialForce(double rhoA, const AlePointArrays& t, const double* q0, const S* u,
                            const S* v, const S* a, const double* load, S* F) {
    const Nodes<S> n(q0, u);
    const S iL = 1.0 / n.L;
    S xid[P], xidd[P], Ldot(0.0), Lddot(0.0);
    if constexpr (Moving) {
      Ldot = v[kP2] - v[kP1];
      Lddot = a[kP2] - a[kP1];
      for (int g = 0; g < P; ++g) {
        xid[g] = -(v[kP1] + t.x[g] * Ldot) * iL;
        xidd[g] = -(a[kP1] + 2.0 * xid[g] * Ldot + t.x[g] * Lddot) * iL;
      }
    }
    S e[D][P], sp1[P], sp2[P];  // e = rhoA rddot - load; sp = S_p . e
    for (int g = 0; g < P; ++g) sp1[g] = sp2[g] = S(0.0);
    double li[D];
    for (int i = 0; i < D; ++i) li[i] = load ? load[i] : 0.0;
    for (int g = 0; g < P; ++g) {  // (points outer: the compiler then vectorizes over them)
      for (int i = 0; i < D; ++i) {
        const S phiXL = t.dh[1][g] * n.s1[i] + t.dh[3][g] * n.s2[i];
        const S phiX = t.dh[2][g] * n.chord[i] + n.L * phiXL;
        const S phiL = t.h[1][g] * n.s1[i] + t.h[3][g] * n.s2[i];
        S ei = S(-li[i]);
        if constexpr (Moving) {
          const S phiXX = t.ddh[2][g] * n.chord[i] + n.L * (t.ddh[1][g] * n.s1[i] + t.ddh[3][g] * n.s2[i]);
          const S vX = t.dh[2][g] * (v[kX2 + i] - v[kX1 + i]) + n.L * (t.dh[1][g] * v[kS1 + i] + t.dh[3][g] * v[kS2 + i]);
          const S vL = t.h[1][g] * v[kS1 + i] + t.h[3][g] * v[kS2 + i];
          const S Na = t.h[0][g] * a[kX1 + i] + t.h[2][g] * a[kX2 + i] + n.L * (t.h[1][g] * a[kS1 + i] + t.h[3][g] * a[kS2 + i]);
          const S rdd = Na + phiX * xidd[g] + phiL * Lddot + 2.0 * vX * xid[g] + 2.0 * vL * Ldot +
                        phiXX * xid[g] * xid[g] + 2.0 * phiXL * xid[g] * Ldot;
          ei += rhoA * rdd;
        }
        e[i][g] = ei;
        sp1[g] += (-phiX * (1.0 - t.x[g]) * iL - phiL) * ei;
        sp2[g] += (-phiX * t.x[g] * iL + phiL) * ei;
      }
    }
    for (int g = 0; g < P; ++g) {
      sp1[g] *= t.w[g];
      sp2[g] *= t.w[g];
    }
    const S Fp1 = sum<P>(sp1), Fp2 = sum<P>(sp2);
    S tx1[D][P], tx2[D][P], t1[D][P], t2[D][P];
    for (int g = 0; g < P; ++g)
      for (int i = 0; i < D; ++i) {
        const S we = t.w[g] * e[i][g];
        tx1[i][g] = t.h[0][g] * we;
        tx2[i][g] = t.h[2][g] * we;
        t1[i][g] = t.h[1][g] * we;
        t2[i][g] = t.h[3][g] * we;
      }
    for (int i = 0; i < D; ++i) {
      F[kX1 + i] = n.L * sum<P>(tx1[i]);
      F[kX2 + i] = n.L * sum<P>(tx2[i]);
      F[kS1 + i] = n.L * n.L * sum<P>(t1[i]);
      F[kS2 + i] = n.L * n.L * sum<P>(t2[i]);
      F[kP1 + i] = F[kP2 + i] = S(0.0);  // the padding of the material blocks
    }
    F[kP1] = n.L * Fp1;
    F[kP2] = n.L * Fp2;
  }

  // The material velocity at the points: rdot = N v + phi_xi xidot + phi_L Ldot (= S qdot).
  template <int P, class S>
  static void materialVelocity(const AlePointArrays& t, const Nodes<S>& n, const S* v, S rd[D][P]) {
    const S iL = 1.0 / n.L, Ldot = v[kP2] - v[kP1];
    S xid[P];
    for (int g = 0; g < P; ++g) xid[g] = -(v[kP1] + t.x[g] * Ldot) * iL;
    for (int i = 0; i < D; ++i)
      for (int g = 0; g < P; ++g) {
        const S phiX = t.dh[2][g] * n.chord[i] + n.L * (t.dh[1][g] * n.s1[i] + t.dh[3][g] * n.s2[i]);
        const S phiL = t.h[1][g] * n.s1[i] + t.h[3][g] * n.s2[i];
        const S Nv = t.h[0][g] * v[kX1 + i] + t.h[2][g] * v[kX2 + i] + n.L * (t.h[1][g] * v[kS1 + i] + t.h[3][g] * v[kS2 + i]);
        rd[i][g] = Nv + phiX * xid[g] + phiL * Ldot;
      }
  }

  // T = 1/2 rhoA L sum_g w_g |rdot_g|^2.
  template <int P, class S>
  static S kineticEnergy(double rhoA, const AlePointArrays& t, const double* q0, const S* u, const S* v) {
    const Nodes<S> n(q0, u);
    S rd[D][P], rd2[P];
    materialVelocity<P>(t, n, v, rd);
    for (int g = 0; g < P; ++g) {
      rd2[g] = rd[0][g] * rd[0][g];
      for (int i = 1; i < D; ++i) rd2[g] += rd[i][g] * rd[i][g];
      rd2[g] *= t.w[g];
    }
    return 0.5 * rhoA * n.L * sum<P>(rd2);
  }

  // The power of a load per unit length on the moving material, v . Q_f = L sum_g w_g rdot_g . load
  // (Q_f = int S^T load dp and S v = rdot).
  template <int P, class S>
  static S loadPower(const AlePointArrays& t, const double* q0, const S* u, const S* v, const double* load) {
    const Nodes<S> n(q0, u);
    S rd[D][P], p[P];
    materialVelocity<P>(t, n, v, rd);
    for (int g = 0; g < P; ++g) {
      p[g] = rd[0][g] * load[0];
      for (int i = 1; i < D; ++i) p[g] += rd[i][g] * load[i];
      p[g] *= t.w[g];
    }
    return n.L * sum<P>(p);
  }
};

}  // namespace strand::elements
