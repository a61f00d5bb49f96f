// Variable-length ANCF cable in the arbitrary Lagrangian-Eulerian description: AleCable2d,
// AleCable3d (the VLBE of Hong, Tang & Ren, J. Fluids Struct. 27 (2011); seed 000 sec. 2-3 without
// the spin angle).
//
// Each node carries its position r, its slope r' = dr/dp and its material coordinate p, the
// unstretched arc length of the material point at the node (seed 000 Eq. 16, 49). An element spans
// the material interval [p1, p2], of unstretched length L = p2 - p1 (Eq. 3), which changes when
// material flows through the nodes; with p1, p2 fixed it is the Lagrangian cable (AncfCable).
// Element slots: r1, r1', p1, r2, r2', p2, each a block of D coordinates; p sits in component 0
// of its block, the other components are padding held at zero (unit rows, like the unused
// coordinate of a 2D rigid body).
//
// Position at xi = (p - p1) / L in [0, 1] (Eq. 2, 4-5 on [0, 1]): r = sum_a N_a(xi, L) q_a with the
// cubic Hermite N = (h0, L h1, h2, L h3) on (r1, r1', r2, r2'). So
//   r' = (h0' r1 + h2' r2) / L + h1' r1' + h3' r2',   r'' = (h0'' r1 + h2'' r2) / L^2 + (h1'' r1' + h3'' r2') / L.
//
// Elastic energy (Eq. 21-22, 31, 37): U = int_{p1}^{p2} W(r', r'') dp = L sum_g w_g W(G_g) at fixed
// Gauss points xi_g, with the cable's W = EA eps^2 / 2 + EI kappa^2 / 2 and eps = (r'.r' - 1)/2
// measured from the unstretched material (p is arc length of the unstretched cable). Its
// derivatives in p1, p2 go through L: dU/dL = sum_g w_g W + L sum_g w_g f_G . G_L.
//
// Inertia (Eq. 13-17, 27-29): the velocity of the material point p is
//   rdot = sum_a N_a v_a + phi_xi xidot + phi_L Ldot,   xidot = -((1 - xi) p1dot + xi p2dot) / L,
// with phi_xi = dr/dxi and phi_L = dr/dL at fixed q (the slopes' L weights); its acceleration
//   rddot = sum_a N_a a_a + phi_xi xiddot + phi_L Lddot + 2 phi_xi(v) xidot + 2 phi_L(v) Ldot
//           + phi_xixi xidot^2 + 2 phi_xiL xidot Ldot,   xiddot = -(p1ddot + 2 xidot Ldot + xi Lddot) / L
// (phi(v): the same derivatives of the interpolated velocities). The generalized inertial force
// is F = rho A int S^T rddot dp with S = d rdot / d qdot (Eq. 15, 27): F = M(q) a + Q_p(q, v),
// M = rho A int S^T S dp (Eq. 28) and Q_p the mass-transport force (Eq. 29), all evaluated here
// pointwise with exact derivatives in q, v and a (inertiaTangent).
#pragma once
#include <cmath>

#include "strand/elements/AleCableKernels.hpp"
#include "strand/elements/AncfCable.hpp"
#include "strand/elements/ElementKind.hpp"
#include "strand/math/Dual.hpp"
#include "strand/math/Gauss.hpp"
#include "strand/math/Hermite.hpp"

namespace strand::elements {

template <int D>
class AleCable {
  using Cable = AncfCable<D>;
  using Kernels = AleCableKernels<D>;

public:
  static constexpr int kDim = D;
  static constexpr int kBlocksPerNode = 3;
  static constexpr int kBlocks = 6;  // r1, r1', p1, r2, r2', p2
  static constexpr int kDof = kBlocks * D;
  static constexpr int kG = 2 * D;  // G = (r', r'')
  static constexpr int kP1 = 2 * D, kP2 = 5 * D;  // element indices of p1 and p2
  // element index of the cable slot k (0 r1, 1 r1', 2 r2, 3 r2')
  static constexpr int slotIndex(int k) { return (k < 2 ? k : k + 1) * D; }

  // ---- the element-kind contract (ElementKind.hpp) ----
  static constexpr const char* kName = D == 2 ? "AleCable2d" : "AleCable3d";
  static constexpr BlockRole kNodeLayout[kBlocksPerNode] = {BlockRole::Position, BlockRole::AxialGradient,
                                                           BlockRole::MaterialCoordinate};
  static constexpr int kOrientationBlock = 1;
  static constexpr bool kStressFreeInitial = false;
  static constexpr bool kInitialStretch = true;  // initial_stretch (through the material coordinates)
  static constexpr bool kConstantMass = false;  // M(q): the inertia is the element's (inertia, inertiaTangent)
  // the cable's keys: E, A, I, rho and the Kelvin-Voigt coefficients (here on the material's rates)
  static constexpr const auto& kSectionKeys = AncfCable<D>::kSectionKeys;

  static constexpr int kOptionCount = 0;
  static constexpr OptionKey kOptions[1] = {{nullptr, nullptr, {nullptr}}};

  struct Body {
    CableSection section;
    math::QuadratureRule elastic, inertial;  // the elastic rule (gauss_points) and 4 points for the inertia
    AlePointArrays elasticPoints, inertialPoints;  // the same as arrays (AleCableKernels.hpp)
  };
  struct Element {
    const Body* body = nullptr;
  };

  static BeamProperties properties(const SectionValues& v) {
    return {v.number("E") * v.number("A"), v.number("E") * v.number("I"), v.number("rho") * v.number("A")};
  }
  static Body body(const SectionValues& v, const BodyDiscretization& d) {
    Body b;
    b.section = {v.number("E") * v.number("A"), v.number("E") * v.number("I"), v.number("rho") * v.number("A"),
                 v.number("damping_axial"), v.number("damping_bending")};
    b.elastic = math::gaussLegendre(d.gaussPoints);
    b.inertial = math::gaussLegendre(4);
    b.elasticPoints = AlePointArrays::of(b.elastic);
    b.inertialPoints = AlePointArrays::of(b.inertial);
    return b;
  }
  static Element element(const Body& b, const double*) { return Element{&b}; }
  // Kelvin-Voigt damping on the material's strain rates (seed 000 Eq. 31-37); the inertia is separate
  static bool velocityDependent(const Body& b) { return b.section.dampAxial != 0.0 || b.section.dampBending != 0.0; }

  // ---- elastic force and tangent ----

  // Damping (Eq. 31-37, with the rates of Eq. 33-34): the Kelvin-Voigt stresses act on the strain
  // rates of the material point, the material derivative of G = (r', r'') at fixed p:
  //   Gdot = (dG/dq at fixed xi) qdot + G_xi xidot,   G_xi = (L r'', L r'''),
  // with xidot = -((1 - xi) p1dot + xi p2dot) / L; their virtual work is taken at fixed xi, as the
  // seed's Eq. 31 does (delta eps = eps_q delta q), so the p rows get L f_G . G_L and no W term.
  // (AleCableKernels::force, the points as arrays.)
  template <class S>
  static void force(const Body& b, const Element&, const double* q0, const S* u, const S* v, S* f) {
    const bool damped = v && velocityDependent(b);
    withPaddedPoints(b.elasticPoints, [&](auto p) {
      constexpr int P = decltype(p)::value;
      if (damped) Kernels::template force<P, true>(b.section, b.elasticPoints, q0, u, v, f);
      else Kernels::template force<P, false>(b.section, b.elasticPoints, q0, u, v, f);
    });
  }

  static void tangent(const Body& b, const Element& e, const double* q0, const double* u, const double* v, double* f,
                      double* K, double* Dm) {
    if (v && velocityDependent(b)) {
      dualTangent<AleCable>(b, e, q0, u, v, f, K, Dm);
      return;
    }
    double q[kDof];
    for (int k = 0; k < kDof; ++k) q[k] = q0[k] + u[k];
    for (int k = 0; k < kDof * kDof; ++k) {
      K[k] = 0.0;
      if (Dm) Dm[k] = 0.0;
    }
    if (f) force(b, e, q0, u, v, f);
    const double L = q[kP2] - q[kP1];
    double KqL[4][D] = {}, KLL = 0.0;
    for (int g = 0; g < b.elastic.size(); ++g) {
      Coefficients<double> c(b.elastic.x[g], L);
      double G[kG], GL[kG], GLL[kG], fG[kG], KG[kG][kG], DG[kG][kG];
      c.gather(q, G);
      c.gatherL(q, GL);
      c.gatherLL(q, GLL);
      double eps = 0.0;
      for (int i = 0; i < D; ++i) eps += 0.5 * G[i] * G[i];
      Cable::pointTangent(b.section, 0.0, eps - 0.5, G, nullptr, fG, KG, DG);
      const double w = b.elastic.w[g], wl = w * L;
      double KGL[kG] = {}, fGL = 0.0, fGLL = 0.0, GLKGL = 0.0;  // K_G G_L, f_G.G_L, f_G.G_LL, G_L.K_G.G_L
      for (int m = 0; m < kG; ++m) {
        for (int n = 0; n < kG; ++n) KGL[m] += KG[m][n] * GL[n];
        fGL += fG[m] * GL[m];
        fGLL += fG[m] * GLL[m];
      }
      for (int m = 0; m < kG; ++m) GLKGL += GL[m] * KGL[m];
      // K_qq: the cable's tangent with the current L
      for (int a = 0; a < 4; ++a)
        for (int bb = 0; bb < 4; ++bb)
          for (int i = 0; i < D; ++i)
            for (int j = 0; j < D; ++j) {
              const double kij = c.B1[a] * (KG[i][j] * c.B1[bb] + KG[i][D + j] * c.B2[bb]) +
                                 c.B2[a] * (KG[D + i][j] * c.B1[bb] + KG[D + i][D + j] * c.B2[bb]);
              K[(slotIndex(a) + i) * kDof + slotIndex(bb) + j] += wl * kij;
            }
      // K_qL = w f_G . B_a + w L (B_a^T K_G G_L + f_G . dB_a/dL)
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < D; ++i)
          KqL[a][i] += w * (c.B1[a] * fG[i] + c.B2[a] * fG[D + i]) +
                       wl * (c.B1[a] * KGL[i] + c.B2[a] * KGL[D + i] + c.dB1[a] * fG[i] + c.dB2[a] * fG[D + i]);
      // K_LL = 2 w f_G . G_L + w L (G_L^T K_G G_L + f_G . G_LL)
      KLL += 2.0 * w * fGL + wl * (GLKGL + fGLL);
    }
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < D; ++i) {
        const int r = slotIndex(a) + i;
        K[r * kDof + kP2] += KqL[a][i];
        K[r * kDof + kP1] -= KqL[a][i];
        K[kP2 * kDof + r] += KqL[a][i];
        K[kP1 * kDof + r] -= KqL[a][i];
      }
    K[kP1 * kDof + kP1] += KLL;
    K[kP2 * kDof + kP2] += KLL;
    K[kP1 * kDof + kP2] -= KLL;
    K[kP2 * kDof + kP1] -= KLL;
  }

  // The damped tangent: K = df/du and D = df/dv of E::force by forward-mode dual numbers, exact to
  // round-off (the rate terms' hand derivation through xidot and r''' is not written; its cost is
  // in docs/elements/ale.md). The undamped tangent stays the hand-derived one above.
  template <class E>
  static void dualTangent(const typename E::Body& b, const typename E::Element& e, const double* q0, const double* u,
                          const double* v, double* f, double* K, double* Dm) {
    using Dl = math::Dual<kDof>;
    Dl x[kDof], y[kDof], fd[kDof];
    for (int k = 0; k < kDof; ++k) x[k] = Dl::variable(u[k], k), y[k] = Dl(v[k]);
    E::force(b, e, q0, x, y, fd);
    for (int r = 0; r < kDof; ++r) {
      if (f) f[r] = fd[r].v;
      for (int c = 0; c < kDof; ++c) K[r * kDof + c] = fd[r].d[c];
    }
    if (!Dm) return;
    for (int k = 0; k < kDof; ++k) x[k] = Dl(u[k]), y[k] = Dl::variable(v[k], k);
    E::force(b, e, q0, x, y, fd);
    for (int r = 0; r < kDof; ++r)
      for (int c = 0; c < kDof; ++c) Dm[r * kDof + c] = fd[r].d[c];
  }

  template <class S>
  static S strainEnergy(const Body& b, const Element&, const double* q0, const S* u) {
    return withPaddedPoints(b.elasticPoints, [&](auto p) {
      return Kernels::template strainEnergy<decltype(p)::value>(b.section, b.elasticPoints, q0, u);
    });
  }

  // ---- inertia: F = M(q) a + Q_p(q, v) ----

  // (AleCableKernels::materialForce, the points as arrays.)
  template <class S>
  static void inertia(const Body& b, const Element&, const double* q0, const S* u, const S* v, const S* a, S* F) {
    Kernels::template materialForce<4, true>(b.section.rhoA, b.inertialPoints, q0, u, v, a, nullptr, F);
  }

  // The inertia less a load per unit length on the material, F - Q_f (inertia() and
  // distributedLoad() in one pass over the points: the dynamic residual's).
  template <class S>
  static void inertiaLessLoad(const Body& b, const Element&, const double* q0, const S* u, const S* v, const S* a,
                              const double* load, S* F) {
    Kernels::template materialForce<4, true>(b.section.rhoA, b.inertialPoints, q0, u, v, a, load, F);
  }

  // Kinetic energy 1/2 int rho A |rdot|^2 dp = 1/2 v^T M(q) v.
  template <class S>
  static S kineticEnergy(const Body& b, const double* q0, const S* u, const S* v) {
    return Kernels::template kineticEnergy<4>(b.section.rhoA, b.inertialPoints, q0, u, v);
  }

  // v . Q_f of a force per unit length f on the material (distributedLoad), from the material
  // velocity: int rdot . f dp.
  template <class S>
  static S loadPower(const Body& b, const double* q0, const S* u, const S* v, const double* f) {
    return Kernels::template loadPower<4>(b.inertialPoints, q0, u, v, f);
  }

  // The inertia's derivatives: M = dF/da, C = dF/dv, Kq = dF/du (row-major kDof x kDof); F optional.
  // F = L sum_g w rhoA S^T rddot. The slot columns of S are N_k I_D, and rddot depends on a slot's
  // velocity and position through one scalar each (Point::RddotDerivatives), so the slot-slot
  // blocks of M, C and Kq are scalar 4 x 4 matrices times I_D, summed over the points before they
  // are spread; the p1, p2 rows and columns are D-vectors per point.
  static void inertiaTangent(const Body& b, const Element& e, const double* q0, const double* u, const double* v,
                             const double* a, double* F, double* M, double* C, double* Kq) {
    if (F) inertia(b, e, q0, u, v, a, F);
    double q[kDof];
    for (int k = 0; k < kDof; ++k) q[k] = q0[k] + u[k];
    for (int k = 0; k < kDof * kDof; ++k) M[k] = C[k] = Kq[k] = 0.0;
    const double L = q[kP2] - q[kP1];
    double m4[4][4] = {}, c4[4][4] = {}, k4[4][4] = {};  // the slot-slot blocks' scalars
    const int p[2] = {kP1, kP2};
    for (int g = 0; g < b.inertial.size(); ++g) {
      const double xi = b.inertial.x[g];
      const Point<double> pt(xi, q, v, a, L);
      const typename Point<double>::RddotDerivatives d = pt.rddotDerivatives(xi);
      const double wr = b.inertial.w[g] * b.section.rhoA, scale = wr * L;
      const double* Sp[2] = {pt.Sp1, pt.Sp2};
      const double* dRv[2] = {d.byV1, d.byV2};
      const double pm[2] = {-1.0, 1.0};  // d L / d p1, d L / d p2
      for (int k = 0; k < 4; ++k)
        for (int l = 0; l < 4; ++l) {
          m4[k][l] += scale * pt.N[k] * pt.N[l];
          c4[k][l] += scale * pt.N[k] * d.cv[l];
          k4[k][l] += scale * pt.N[k] * d.kq[l];
        }
      for (int k = 0; k < 4; ++k)
        for (int i = 0; i < D; ++i) {
          const int r = slotIndex(k) + i;
          const double sN = scale * pt.N[k];
          for (int j = 0; j < 2; ++j) {
            // slot rows, p columns
            M[r * kDof + p[j]] += sN * Sp[j][i];
            C[r * kDof + p[j]] += sN * dRv[j][i];
            Kq[r * kDof + p[j]] += pm[j] * (sN * d.byL[i] + wr * pt.N[k] * pt.rdd[i]);  // + the factor L
            // p rows, slot columns
            M[p[j] * kDof + r] += scale * Sp[j][i] * pt.N[k];
            C[p[j] * kDof + r] += scale * Sp[j][i] * d.cv[k];
            Kq[p[j] * kDof + r] += scale * Sp[j][i] * d.kq[k];
          }
        }
      for (int j = 0; j < 2; ++j) {
        double SpRdd = 0.0;
        for (int i = 0; i < D; ++i) SpRdd += Sp[j][i] * pt.rdd[i];
        for (int jj = 0; jj < 2; ++jj) {
          double mm = 0.0, cc = 0.0, kk = 0.0;
          for (int i = 0; i < D; ++i) {
            mm += Sp[j][i] * Sp[jj][i];
            cc += Sp[j][i] * dRv[jj][i];
            kk += Sp[j][i] * d.byL[i];
          }
          M[p[j] * kDof + p[jj]] += scale * mm;
          C[p[j] * kDof + p[jj]] += scale * cc;
          Kq[p[j] * kDof + p[jj]] += pm[jj] * (scale * kk + wr * SpRdd);  // + the factor L
        }
      }
      // dS/dq applied to rddot: the columns' own derivatives
      double sr[D];
      for (int i = 0; i < D; ++i) sr[i] = scale * pt.rdd[i];
      pt.columnDerivatives(xi, sr, reinterpret_cast<double (*)[kDof]>(Kq));
    }
    for (int k = 0; k < 4; ++k)
      for (int l = 0; l < 4; ++l)
        for (int i = 0; i < D; ++i) {
          const int at = (slotIndex(k) + i) * kDof + slotIndex(l) + i;
          M[at] += m4[k][l];
          C[at] += c4[k][l];
          Kq[at] += k4[k][l];
        }
  }

  // ---- distributed loads: a force per unit length f on the moving material ----
  // Q_f = int_{p1}^{p2} S^T f dp (seed 000 Eq. 43-44 with the p columns of S): it depends on the
  // coordinates (the element's length and the material it holds), so it is assembled with the
  // elastic force (kConfigurationLoads) and has a tangent. The load arrays (fvec, load, f) hold D
  // force components and then a torque per unit length on a spin angle (AleBeamShaft3d), which
  // the cable ignores.
  static constexpr bool kConfigurationLoads = true;

  template <class S>
  static void distributedLoad(const Body& b, const double* q0, const S* u, const double* fvec, S* Q) {
    Kernels::template materialForce<4, false>(0.0, b.inertialPoints, q0, u, static_cast<const S*>(nullptr),
                                              static_cast<const S*>(nullptr), fvec, Q);
    for (int k = 0; k < kDof; ++k) Q[k] = -Q[k];
  }

  // dQ_f/du (row-major kDof x kDof).
  static void distributedLoadTangent(const Body& b, const double* q0, const double* u, const double* fvec, double* K) {
    double q[kDof], zero[kDof] = {};
    for (int k = 0; k < kDof; ++k) q[k] = q0[k] + u[k];
    for (int k = 0; k < kDof * kDof; ++k) K[k] = 0.0;
    const double L = q[kP2] - q[kP1];
    for (int g = 0; g < b.inertial.size(); ++g) {
      const double xi = b.inertial.x[g], w = b.inertial.w[g];
      const Point<double> pt(xi, q, zero, zero, L);
      double dSf[kDof][kDof] = {};
      pt.columnDerivatives(xi, fvec, dSf);
      for (int r = 0; r < kDof; ++r)
        for (int c = 0; c < kDof; ++c) K[r * kDof + c] += w * L * dSf[r][c];
      // the factor L
      double sf[kDof] = {};
      for (int k = 0; k < 4; ++k)
        for (int i = 0; i < D; ++i) sf[slotIndex(k) + i] = pt.N[k] * fvec[i];
      for (int i = 0; i < D; ++i) {
        sf[kP1] += pt.Sp1[i] * fvec[i];
        sf[kP2] += pt.Sp2[i] * fvec[i];
      }
      for (int r = 0; r < kDof; ++r) {
        K[r * kDof + kP2] += w * sf[r];
        K[r * kDof + kP1] -= w * sf[r];
      }
    }
  }

  // ---- the remaining contract members ----

  // The mass at the reference state is not used (kConstantMass = false): inertia() is the element's.
  static void slotMass(const Body&, double* m) {
    for (int k = 0; k < kBlocks * kBlocks; ++k) m[k] = 0.0;
  }
  // Centerline position at eta of an element of length l (the material coordinates at rest).
  static void interpolation(const BodyDiscretization& d, double eta, double* w) {
    const math::HermiteValues h = math::hermite(eta);
    const double l = d.elementLength, ww[kBlocks] = {h.s[0], l * h.s[1], 0.0, h.s[2], l * h.s[3], 0.0};
    for (int k = 0; k < kBlocks; ++k) w[k] = ww[k];
  }
  // At the element's current coordinates: the slopes' weights take the current material length
  // L = p2 - p1 (eta is then the fraction of the element's current material).
  static void interpolationAt(const BodyDiscretization& d, const double* q, double eta, double* w) {
    interpolation(d, eta, w);
    if (!q) return;
    const double L = q[kP2] - q[kP1], h1 = math::hermite(eta).s[1], h3 = math::hermite(eta).s[3];
    w[1] = L * h1;
    w[4] = L * h3;
  }
  static void consistentLoad(const Body&, const double*, double* f) {
    for (int k = 0; k < kDof; ++k) f[k] = 0.0;  // none constant: distributedLoad() (kConfigurationLoads)
  }
  static int referenceValueCount(const Body&) { return 0; }
  static void referenceValues(const Body&, const double*, double*) {}

private:
  // The slot coefficients of r' (B1) and r'' (B2) at xi for the length L, and their L-derivatives.
  template <class S>
  struct Coefficients {
    S B1[4], B2[4], dB1[4], dB2[4], ddB1[4], ddB2[4];
    Coefficients(double xi, const S& L) {
      const math::HermiteValues h = math::hermite(xi);
      const S i1 = 1.0 / L, i2 = i1 * i1, i3 = i2 * i1, i4 = i3 * i1;  // one division per point
      for (int k = 0; k < 4; ++k) {
        const bool pos = k % 2 == 0;
        B1[k] = pos ? h.ds[k] * i1 : S(h.ds[k]);
        B2[k] = pos ? h.dds[k] * i2 : h.dds[k] * i1;
        dB1[k] = pos ? -h.ds[k] * i2 : S(0.0);
        dB2[k] = pos ? -2.0 * h.dds[k] * i3 : -h.dds[k] * i2;
        ddB1[k] = pos ? 2.0 * h.ds[k] * i3 : S(0.0);
        ddB2[k] = pos ? 6.0 * h.dds[k] * i4 : 2.0 * h.dds[k] * i3;
      }
    }
    template <class Q>
    void combine(const S* c1, const S* c2, const Q* q, S* G) const {
      for (int i = 0; i < D; ++i) {
        G[i] = S(0.0);
        G[D + i] = S(0.0);
        for (int k = 0; k < 4; ++k) {
          G[i] += c1[k] * q[slotIndex(k) + i];
          G[D + i] += c2[k] * q[slotIndex(k) + i];
        }
      }
    }
    template <class Q> void gather(const Q* q, S* G) const { combine(B1, B2, q, G); }
    template <class Q> void gatherL(const Q* q, S* G) const { combine(dB1, dB2, q, G); }
    template <class Q> void gatherLL(const Q* q, S* G) const { combine(ddB1, ddB2, q, G); }
  };

  // One material point xi of the element: its velocity and acceleration (seed 000 Eq. 13-17), the
  // columns S_p1, S_p2 of S = d rdot / d qdot, and the exact derivatives of rddot
  // (rddotDerivatives()) and of S's columns (columnDerivatives()).
  template <class S>
  struct Point {
    S N[4], Nx[4], Nxx[4], NL[4], NxL[4];  // shape values and their xi / L derivatives per cable slot
    S L, Ldot, Lddot, xid, xidd;
    S phiX[D], phiXX[D], phiL[D], phiXL[D], phiXXL[D], vX[D], vL[D], vXL[D], aL[D];
    S rd[D], rdd[D], Sp1[D], Sp2[D];

    template <class Q>
    Point(double xi, const Q* q, const S* v, const S* a, const S& length) : L(length) {
      const math::HermiteValues h = math::hermite(xi);
      for (int k = 0; k < 4; ++k) {
        const bool pos = k % 2 == 0;
        N[k] = pos ? S(h.s[k]) : L * h.s[k];
        Nx[k] = pos ? S(h.ds[k]) : L * h.ds[k];
        Nxx[k] = pos ? S(h.dds[k]) : L * h.dds[k];
        NL[k] = pos ? S(0.0) : S(h.s[k]);
        NxL[k] = pos ? S(0.0) : S(h.ds[k]);
      }
      Ldot = v[kP2] - v[kP1];
      Lddot = a[kP2] - a[kP1];
      xid = -((1.0 - xi) * v[kP1] + xi * v[kP2]) / L;
      xidd = -(a[kP1] + 2.0 * xid * Ldot + xi * Lddot) / L;
      for (int i = 0; i < D; ++i) {
        phiX[i] = phiXX[i] = phiL[i] = phiXL[i] = phiXXL[i] = vX[i] = vL[i] = vXL[i] = aL[i] = S(0.0);
        S Nv(0.0), Na(0.0);
        for (int k = 0; k < 4; ++k) {
          const int s = slotIndex(k) + i;
          phiX[i] += Nx[k] * q[s];
          phiXX[i] += Nxx[k] * q[s];
          phiL[i] += NL[k] * q[s];
          phiXL[i] += NxL[k] * q[s];
          phiXXL[i] += (k % 2 == 0 ? S(0.0) : S(h.dds[k])) * q[s];
          vX[i] += Nx[k] * v[s];
          vL[i] += NL[k] * v[s];
          vXL[i] += NxL[k] * v[s];
          aL[i] += NL[k] * a[s];
          Nv += N[k] * v[s];
          Na += N[k] * a[s];
        }
        rd[i] = Nv + phiX[i] * xid + phiL[i] * Ldot;
        rdd[i] = Na + phiX[i] * xidd + phiL[i] * Lddot + 2.0 * vX[i] * xid + 2.0 * vL[i] * Ldot +
                 phiXX[i] * xid * xid + 2.0 * phiXL[i] * xid * Ldot;
        Sp1[i] = -phiX[i] * (1.0 - xi) / L - phiL[i];
        Sp2[i] = -phiX[i] * xi / L + phiL[i];
      }
    }

    // The derivatives of rddot: in a slot's position q_(k,j) and velocity v_(k,j), e_j kq[k] and
    // e_j cv[k] (rddot is linear in the slots through phi_xi, phi_xixi, phi_L, phi_xiL); in L (p2: +,
    // p1: -) at fixed q, v, a, byL; in the material velocities v_p1, v_p2, byV1 and byV2.
    struct RddotDerivatives {
      double kq[4], cv[4], byL[D], byV1[D], byV2[D];
    };
    RddotDerivatives rddotDerivatives(double xi) const {
      RddotDerivatives d;
      for (int k = 0; k < 4; ++k) {
        d.kq[k] = Nx[k] * xidd + NL[k] * Lddot + Nxx[k] * xid * xid + 2.0 * NxL[k] * xid * Ldot;
        d.cv[k] = 2.0 * Nx[k] * xid + 2.0 * NL[k] * Ldot;
      }
      // d xid/dL = -xid/L; d xidd/dL = -xidd/L + 2 Ldot xid / L^2
      const double dxidL = -xid / L, dxiddL = -xidd / L + 2.0 * Ldot * xid / (L * L);
      // velocity derivatives of xid, xidd
      const double dxid1 = -(1.0 - xi) / L, dxid2 = -xi / L;  // d xid / d v_p1, v_p2
      const double dxidd1 = -(2.0 * Ldot * dxid1 - 2.0 * xid) / L;
      const double dxidd2 = -(2.0 * Ldot * dxid2 + 2.0 * xid) / L;
      for (int i = 0; i < D; ++i) {
        d.byL[i] = aL[i] + phiXL[i] * xidd + phiX[i] * dxiddL + 2.0 * vXL[i] * xid + 2.0 * vX[i] * dxidL +
                 phiXXL[i] * xid * xid + 2.0 * phiXX[i] * xid * dxidL + 2.0 * phiXL[i] * Ldot * dxidL;
        // v_p1, v_p2 (Ldot: -1, +1)
        d.byV1[i] = phiX[i] * dxidd1 + 2.0 * vX[i] * dxid1 - 2.0 * vL[i] + 2.0 * phiXX[i] * xid * dxid1 +
                  2.0 * phiXL[i] * (dxid1 * Ldot - xid);
        d.byV2[i] = phiX[i] * dxidd2 + 2.0 * vX[i] * dxid2 + 2.0 * vL[i] + 2.0 * phiXX[i] * xid * dxid2 +
                  2.0 * phiXL[i] * (dxid2 * Ldot + xid);
      }
      return d;
    }

    // dSw[r][c] += d(S_r . w)/d q_c with w held: the derivatives of the columns of S, the cable
    // slots N_k (the slopes' depend on L) and S_p1, S_p2 (on q and L).
    void columnDerivatives(double xi, const double* w, double dSw[kDof][kDof]) const {
      for (int k = 0; k < 4; ++k)
        for (int i = 0; i < D; ++i) {
          const int r = slotIndex(k) + i;
          dSw[r][kP2] += NL[k] * w[i];
          dSw[r][kP1] -= NL[k] * w[i];
        }
      for (int k = 0; k < 4; ++k)
        for (int j = 0; j < D; ++j) {
          const int c = slotIndex(k) + j;
          dSw[kP1][c] += (-Nx[k] * (1.0 - xi) / L - NL[k]) * w[j];
          dSw[kP2][c] += (-Nx[k] * xi / L + NL[k]) * w[j];
        }
      double dSp1L = 0.0, dSp2L = 0.0;  // d(S_p . w)/dL at fixed q
      for (int i = 0; i < D; ++i) {
        dSp1L += (-phiXL[i] * (1.0 - xi) / L + phiX[i] * (1.0 - xi) / (L * L)) * w[i];
        dSp2L += (-phiXL[i] * xi / L + phiX[i] * xi / (L * L)) * w[i];
      }
      dSw[kP1][kP2] += dSp1L;
      dSw[kP1][kP1] -= dSp1L;
      dSw[kP2][kP2] += dSp2L;
      dSw[kP2][kP1] -= dSp2L;
    }
  };
};

using AleCable2d = AleCable<2>;
using AleCable3d = AleCable<3>;

}  // namespace strand::elements
