// Variable-length ANCF beam-shaft in the arbitrary Lagrangian-Eulerian description: AleBeamShaft3d
// (the VLBSE of seed 000, sec. 2-3): the ALE cable AleCable3d (positions, slopes, material
// coordinates; bending and stretching) plus the spin angle theta of the cross-section about the
// centerline, for a circular (or annular) Euler-Bernoulli section.
//
// Node blocks: r, r' = dr/dp, (p, theta, padding). theta sits in component 1 of the material block
// (BlockRole::MaterialSpin), so the element's slots and the cable part are AleCable3d's.
//
// theta is interpolated linearly in the element's material (Eq. 6-7 on xi in [0, 1]):
//   theta(xi) = (1 - xi) theta1 + xi theta2,   theta' = (theta2 - theta1) / L   (Eq. 23, 26),
// independent of the bending (the seed's model: no coupling of spin and bending but through the
// material flow). Torsion energy (Eq. 38, elastic part): U_t = G I_p / 2 int theta'^2 dp
// = G I_p (theta2 - theta1)^2 / (2 L), exact. Polar inertia (Eq. 27-29, the fourth row of the
// block-diagonal integrand): the material point's spin rate and its rate are
//   thetadot  = (1 - xi) vt1 + xi vt2 + theta_xi xidot,
//   thetaddot = (1 - xi) at1 + xi at2 + 2 thetadot_xi xidot + theta_xi xiddot,
// (theta_xi = theta2 - theta1, xidot and xiddot as in AleCable.hpp), and the generalized inertial
// force adds rho I_p int S_r^T thetaddot dp with the row S_r = d thetadot / d qdot:
//   S_r = (1 - xi) on theta1, xi on theta2, -theta_xi (1 - xi) / L on p1, -theta_xi xi / L on p2.
// The section's rho I_p includes no rotary inertia of bending (Euler-Bernoulli, assumption (b)).
#pragma once
#include <cmath>

#include "strand/elements/AleCable.hpp"

namespace strand::elements {

class AleBeamShaft3d : public AleCable<3> {
  using Cable = AleCable<3>;

public:
  static constexpr int kT1 = kP1 + 1, kT2 = kP2 + 1;  // element indices of theta1 and theta2

  static constexpr const char* kName = "AleBeamShaft3d";
  static constexpr BlockRole kNodeLayout[kBlocksPerNode] = {BlockRole::Position, BlockRole::AxialGradient,
                                                           BlockRole::MaterialSpin};
  static constexpr SectionKey kSectionKeys[] = {
      {"E", "Young's modulus [Pa]", true, 0.0, 0.0, false, kNoLimit},
      {"nu", "Poisson's ratio (G = E / (2 (1 + nu)))", false, 0.3, -1.0, false, 0.5},
      {"rho", "density [kg/m^3]", true, 0.0, 0.0, false, kNoLimit},
      {"radius", "outer radius of the circular section [m]", true, 0.0, 0.0, false, kNoLimit},
      {"inner_radius", "inner radius of a tube [m] (0: solid)", false, 0.0, 0.0, true, kNoLimit},
      {"damping_axial", "Kelvin-Voigt coefficient on the material's axial strain rate [s]", false, 0.0, 0.0, true, kNoLimit},
      {"damping_bending", "Kelvin-Voigt coefficient on the material's curvature rate [s]", false, 0.0, 0.0, true, kNoLimit},
      {"damping_torsion", "Kelvin-Voigt coefficient on the material's twist rate [s]", false, 0.0, 0.0, true, kNoLimit},
  };

  // A = pi (R^2 - r^2), I = pi (R^4 - r^4) / 4, I_p = 2 I (circular section).
  struct Circle {
    double A, I, Ip;
    explicit Circle(const SectionValues& v) {
      const double R = v.number("radius"), r = v.number("inner_radius");
      A = M_PI * (R * R - r * r);
      I = M_PI * (R * R * R * R - r * r * r * r) / 4.0;
      Ip = 2.0 * I;
    }
  };
  struct Body : Cable::Body {
    double GIp = 0.0, rhoIp = 0.0;  // torsion stiffness [N m^2], polar inertia per length [kg m]
    double dampTorsion = 0.0;       // Kelvin-Voigt coefficient on the twist rate [s] (Eq. 38)
  };
  struct Element {
    const Body* body = nullptr;
  };

  static BeamProperties properties(const SectionValues& v) {
    const Circle c(v);
    return {v.number("E") * c.A, v.number("E") * c.I, v.number("rho") * c.A};
  }
  static Body body(const SectionValues& v, const BodyDiscretization& d) {
    const Circle c(v);
    SectionValues cable;
    cable.numbers = {{"E", v.number("E")},
                     {"A", c.A},
                     {"I", c.I},
                     {"rho", v.number("rho")},
                     {"damping_axial", v.number("damping_axial")},
                     {"damping_bending", v.number("damping_bending")}};
    Body b;
    static_cast<Cable::Body&>(b) = Cable::body(cable, d);
    b.GIp = v.number("E") / (2.0 * (1.0 + v.number("nu", 0.3))) * c.Ip;
    b.rhoIp = v.number("rho") * c.Ip;
    b.dampTorsion = v.number("damping_torsion");
    return b;
  }
  static Element element(const Body& b, const double*) { return Element{&b}; }

  // ---- elastic force and tangent: the cable's plus torsion ----

  // Twist damping (Eq. 38): the torque G I_p c_t thetadot' on the material's twist rate, the
  // material derivative of theta' = tx / L (uniform in the element): (txdot L - tx Ldot) / L^2; its
  // virtual work at fixed xi, L int torque delta(tx / L) dxi, adds -torque tx / L to the p2 row.
  template <class S>
  static void force(const Body& b, const Element&, const double* q0, const S* u, const S* v, S* f) {
    Cable::force(b, Cable::Element{&b}, q0, u, v, f);
    const S L = (q0[kP2] + u[kP2]) - (q0[kP1] + u[kP1]);
    const S tx = (q0[kT2] + u[kT2]) - (q0[kT1] + u[kT1]);
    S torque = b.GIp * tx / L, dUdL = -0.5 * b.GIp * tx * tx / (L * L);
    if (v && b.dampTorsion != 0.0) {
      const S rate = ((v[kT2] - v[kT1]) * L - tx * (v[kP2] - v[kP1])) / (L * L);
      const S damped = b.GIp * b.dampTorsion * rate;
      torque += damped;
      dUdL -= damped * tx / L;
    }
    f[kT1] -= torque;
    f[kT2] += torque;
    f[kP1] -= dUdL;
    f[kP2] += dUdL;
  }

  static void tangent(const Body& b, const Element& e, const double* q0, const double* u, const double* v, double* f,
                      double* K, double* Dm) {
    if (v && velocityDependent(b)) {
      dualTangent<AleBeamShaft3d>(b, e, q0, u, v, f, K, Dm);
      return;
    }
    Cable::tangent(b, Cable::Element{&b}, q0, u, v, nullptr, K, Dm);
    if (f) force(b, Element{&b}, q0, u, v, f);
    const double L = (q0[kP2] + u[kP2]) - (q0[kP1] + u[kP1]);
    const double tx = (q0[kT2] + u[kT2]) - (q0[kT1] + u[kT1]);
    const double k = b.GIp / L, kTL = -b.GIp * tx / (L * L), kLL = b.GIp * tx * tx / (L * L * L);
    // d(torque on theta2)/d(theta1, theta2) = k (-1, 1); d/dL = kTL; d^2 U / dL^2 = kLL
    const int T[2] = {kT1, kT2}, P[2] = {kP1, kP2};
    const double sign[2] = {-1.0, 1.0};
    for (int a = 0; a < 2; ++a)
      for (int c = 0; c < 2; ++c) {
        K[T[a] * kDof + T[c]] += sign[a] * sign[c] * k;
        K[T[a] * kDof + P[c]] += sign[a] * sign[c] * kTL;
        K[P[a] * kDof + T[c]] += sign[a] * sign[c] * kTL;
        K[P[a] * kDof + P[c]] += sign[a] * sign[c] * kLL;
      }
  }

  template <class S>
  static S strainEnergy(const Body& b, const Element&, const double* q0, const S* u) {
    const S L = (q0[kP2] + u[kP2]) - (q0[kP1] + u[kP1]);
    const S tx = (q0[kT2] + u[kT2]) - (q0[kT1] + u[kT1]);
    return Cable::strainEnergy(b, Cable::Element{&b}, q0, u) + 0.5 * b.GIp * tx * tx / L;
  }

  // ---- inertia: the cable's plus the polar inertia of the spinning material ----

  template <class S>
  static void inertia(const Body& b, const Element&, const double* q0, const S* u, const S* v, const S* a, S* F) {
    Cable::inertia(b, Cable::Element{&b}, q0, u, v, a, F);
    addSpinInertia(b, q0, u, v, a, F);
  }

  // The inertia less the load per unit length on the material (the dynamic residual's): the force
  // load[0..2] and the torque load[3] about the centerline (spinTorqueLoad).
  template <class S>
  static void inertiaLessLoad(const Body& b, const Element&, const double* q0, const S* u, const S* v, const S* a,
                              const double* load, S* F) {
    Cable::inertiaLessLoad(b, Cable::Element{&b}, q0, u, v, a, load, F);
    addSpinInertia(b, q0, u, v, a, F);
    addSpinTorqueLoad(q0, u, -load[3], F);
  }

  // ---- distributed loads: a force f (load[0..2], the cable's Q_f) and a torque m (load[3]) per
  // unit length on the moving material ----
  // The torque's virtual work at fixed material points, int_{p1}^{p2} m delta theta dp
  // (Eq. 43-44 with the spin row S_r for S_t), is Q_m = L int_0^1 S_r^T m dxi: on (theta1, theta2,
  // p1, p2), exactly,
  //   Q_m = m (L / 2, L / 2, -theta_xi / 2, -theta_xi / 2),   theta_xi = theta2 - theta1,
  // the p entries from the material sliding past a twisted element. Not a gradient: its tangent
  // has m/2 (-1, 1) in the theta rows' p columns and m/2 (1, -1) in the p rows' theta columns.
  template <class S>
  static void distributedLoad(const Body& b, const double* q0, const S* u, const double* load, S* Q) {
    Cable::distributedLoad(b, q0, u, load, Q);
    addSpinTorqueLoad(q0, u, load[3], Q);
  }

  static void distributedLoadTangent(const Body& b, const double* q0, const double* u, const double* load, double* K) {
    Cable::distributedLoadTangent(b, q0, u, load, K);
    const double h = 0.5 * load[3];
    for (int r : {kT1, kT2}) {
      K[r * kDof + kP1] -= h;
      K[r * kDof + kP2] += h;
    }
    for (int r : {kP1, kP2}) {
      K[r * kDof + kT1] += h;
      K[r * kDof + kT2] -= h;
    }
  }

  // v . (Q_f + Q_m): the torque's power is int m thetadot dp with the material's spin rate,
  // m / 2 (L (vt1 + vt2) - theta_xi (vp1 + vp2)).
  template <class S>
  static S loadPower(const Body& b, const double* q0, const S* u, const S* v, const double* load) {
    S P = Cable::loadPower(b, q0, u, v, load), Qm[4];
    if (load[3] == 0.0) return P;
    spinTorqueLoad(q0, u, load[3], Qm);
    for (int k = 0; k < 4; ++k) P += Qm[k] * v[kSpinColumns[k]];
    return P;
  }

  template <class S>
  static S kineticEnergy(const Body& b, const double* q0, const S* u, const S* v) {
    S zero[kDof];
    for (int k = 0; k < kDof; ++k) zero[k] = S(0.0);
    const S L = (q0[kP2] + u[kP2]) - (q0[kP1] + u[kP1]);
    S T = Cable::kineticEnergy(b, q0, u, v);
    for (int g = 0; g < b.inertial.size(); ++g) {
      const Spin<S> s(b.inertial.x[g], q0, u, v, zero, L);
      T += 0.5 * b.inertial.w[g] * L * b.rhoIp * s.thd * s.thd;
    }
    return T;
  }

  static void inertiaTangent(const Body& b, const Element&, const double* q0, const double* u, const double* v,
                             const double* a, double* F, double* M, double* C, double* Kq) {
    Cable::inertiaTangent(b, Cable::Element{&b}, q0, u, v, a, nullptr, M, C, Kq);
    if (F) inertia(b, Element{&b}, q0, u, v, a, F);
    const double L = (q0[kP2] + u[kP2]) - (q0[kP1] + u[kP1]);
    for (int g = 0; g < b.inertial.size(); ++g) {
      const double xi = b.inertial.x[g], wr = b.inertial.w[g] * b.rhoIp, scale = wr * L;
      const Spin<double> s(xi, q0, u, v, a, L);
      // d thetaddot / d(a, v, q) over the four spin columns (theta1, theta2, p1, p2)
      double dA[4], dV[4], dQ[4];
      s.derivatives(xi, dA, dV, dQ);
      // d S_r / d q applied to thetaddot: S_r(p1) = -theta_xi (1 - xi) / L, S_r(p2) = -theta_xi xi / L
      const double dS[4][4] = {{0, 0, 0, 0},
                               {0, 0, 0, 0},
                               {(1 - xi) / L, -(1 - xi) / L, -s.tx * (1 - xi) / (L * L), s.tx * (1 - xi) / (L * L)},
                               {xi / L, -xi / L, -s.tx * xi / (L * L), s.tx * xi / (L * L)}};
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
          const int R = s.col[r], Cc = s.col[c];
          M[R * kDof + Cc] += scale * s.Sr[r] * dA[c];
          C[R * kDof + Cc] += scale * s.Sr[r] * dV[c];
          Kq[R * kDof + Cc] += scale * (s.Sr[r] * dQ[c] + dS[r][c] * s.thdd);
        }
      // the factor L: d/dp2 = +, d/dp1 = -
      for (int r = 0; r < 4; ++r) {
        Kq[s.col[r] * kDof + kP2] += wr * s.Sr[r] * s.thdd;
        Kq[s.col[r] * kDof + kP1] -= wr * s.Sr[r] * s.thdd;
      }
    }
  }

  static bool velocityDependent(const Body& b) { return Cable::velocityDependent(b) || b.dampTorsion != 0.0; }

private:
  static constexpr int kSpinColumns[4] = {kT1, kT2, kP1, kP2};

  // Q_m of a torque m per unit length (distributedLoad) on kSpinColumns.
  template <class S>
  static void spinTorqueLoad(const double* q0, const S* u, double m, S Qm[4]) {
    const S L = (q0[kP2] + u[kP2]) - (q0[kP1] + u[kP1]), tx = (q0[kT2] + u[kT2]) - (q0[kT1] + u[kT1]);
    Qm[0] = Qm[1] = 0.5 * m * L;
    Qm[2] = Qm[3] = -0.5 * m * tx;
  }

  // Q += Q_m.
  template <class S>
  static void addSpinTorqueLoad(const double* q0, const S* u, double m, S* Q) {
    if (m == 0.0) return;
    S Qm[4];
    spinTorqueLoad(q0, u, m, Qm);
    for (int k = 0; k < 4; ++k) Q[kSpinColumns[k]] += Qm[k];
  }

  // F += rho I_p int S_r^T thetaddot dp.
  template <class S>
  static void addSpinInertia(const Body& b, const double* q0, const S* u, const S* v, const S* a, S* F) {
    const S L = (q0[kP2] + u[kP2]) - (q0[kP1] + u[kP1]);
    for (int g = 0; g < b.inertial.size(); ++g) {
      const Spin<S> s(b.inertial.x[g], q0, u, v, a, L);
      const S scale = b.inertial.w[g] * L * b.rhoIp * s.thdd;
      for (int k = 0; k < 4; ++k) F[s.col[k]] += scale * s.Sr[k];
    }
  }

  // The spin of the material point xi: its rate thd, its acceleration thdd and the row S_r over the
  // columns col = (theta1, theta2, p1, p2).
  template <class S>
  struct Spin {
    static constexpr const int* col = kSpinColumns;
    S L, tx, txd, xid, xidd, Ldot, thd, thdd, Sr[4];
    template <class Q>
    Spin(double xi, const double* q0, const Q* u, const S* v, const S* a, const S& length) : L(length) {
      tx = (q0[kT2] + u[kT2]) - (q0[kT1] + u[kT1]);
      txd = v[kT2] - v[kT1];
      Ldot = v[kP2] - v[kP1];
      const S Lddot = a[kP2] - a[kP1];
      xid = -((1.0 - xi) * v[kP1] + xi * v[kP2]) / L;
      xidd = -(a[kP1] + 2.0 * xid * Ldot + xi * Lddot) / L;
      thd = (1.0 - xi) * v[kT1] + xi * v[kT2] + tx * xid;
      thdd = (1.0 - xi) * a[kT1] + xi * a[kT2] + 2.0 * txd * xid + tx * xidd;
      Sr[0] = S(1.0 - xi);
      Sr[1] = S(xi);
      Sr[2] = -tx * (1.0 - xi) / L;
      Sr[3] = -tx * xi / L;
    }
    // d thdd / d a, d v, d q over col (q: theta through tx, p through L at fixed v and a).
    void derivatives(double xi, double* dA, double* dV, double* dQ) const {
      for (int c = 0; c < 4; ++c) dA[c] = Sr[c];
      const double dxid1 = -(1.0 - xi) / L, dxid2 = -xi / L;  // d xid / d v_p1, v_p2
      const double dxidd1 = -(2.0 * Ldot * dxid1 - 2.0 * xid) / L;
      const double dxidd2 = -(2.0 * Ldot * dxid2 + 2.0 * xid) / L;
      dV[0] = -2.0 * xid;
      dV[1] = 2.0 * xid;
      dV[2] = 2.0 * txd * dxid1 + tx * dxidd1;
      dV[3] = 2.0 * txd * dxid2 + tx * dxidd2;
      const double dxidL = -xid / L, dxiddL = -xidd / L + 2.0 * Ldot * xid / (L * L);
      const double dL = 2.0 * txd * dxidL + tx * dxiddL;
      dQ[0] = -xidd;
      dQ[1] = xidd;
      dQ[2] = -dL;
      dQ[3] = dL;
    }
  };
};

}  // namespace strand::elements
