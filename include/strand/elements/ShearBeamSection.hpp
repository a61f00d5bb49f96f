// The section law of the 2D shear-deformable ANCF beams (AncfBeam2d.hpp): the continuum strain
// energy of seed 004 Eq. 2.13-2.19 integrated over a rectangular cross-section in closed form.
//
// Kinematics: r(x, y) = c(x) + y d(x), x the reference arc length, y in [-h/2, h/2] across the
// section (both elements of seed 004 ch. 2 are linear in y). The deformation gradient in the
// straight stress-free reference is J = [c' + y d', d], and the Green-Lagrange strain
// E = (J^T J - I)/2 (Eq. 2.14) has the components
//   E_xx = e0 + y e1 + y^2 e2,   E_yy = g0,   E_xy = s0 + y s1,
// with the six measures (pointwise functions of G = (c', d', d))
//   e0 = (c'.c' - c0'.c0')/2,  e1 = c'.d',  e2 = d'.d'/2,  g0 = (d.d - d0.d0)/2,  s0 = c'.d/2,  s1 = d'.d/2.
// e0 and g0 are measured from the initial shape's metric, as the cable's axial strain (the initial
// centerline is unstretched; evaluated as c0'.u' + u'.u'/2, without cancellation); e1, e2, s0, s1
// from the straight reference, so a curved initial shape carries its bending.
// Over a b x h rectangle (A = b h, I = b h^3/12, I4 = b h^5/80; odd moments vanish):
//   int E_xx^2 = A e0^2 + I (e1^2 + 2 e0 e2) + I4 e2^2,  int E_yy^2 = A g0^2,
//   int E_xx E_yy = g0 (A e0 + I e2),                     int E_xy^2 = A s0^2 + I s1^2.
// The energy per unit length is W = 1/2 m^T C m, with C from the elasticity form:
//   decoupled     seed 004 Eq. 2.18: E eps_xx^2 + E eps_yy^2 + 4 k_s G eps_xy^2 (Poisson coupling
//                 dropped: no Poisson locking; the default);
//   plane_stress  E/(1-nu^2) [[1, nu], [nu, 1]] on (E_xx, E_yy), 4 k_s G on E_xy;
//   plane_strain  Lame's constants (Eq. 2.17): lambda + 2 mu, lambda, 4 k_s mu.
// Kelvin-Voigt damping with one material time constant eta: stresses S = C (m + eta dm/dt).
// With J_i = dm_i/dG (rows of J below) and H_i = d2m_i/dG2 (constant):
//   f_G = J^T S,   K_G = J^T C (J + eta J(Gd)) + sum_i S_i H_i,   D_G = eta J^T C J,
// where J(Gd) is J evaluated at the rates (dm_i/dt = J_i . Gd, and J is linear in G).
#pragma once
#include <cmath>

namespace strand::elements {

struct ShearBeamSection {
  static constexpr int kMeasures = 6;
  enum Measure { E0, E1, E2, G0, S0, S1 };
  static constexpr int kG = 6;  // G = (c'_x, c'_y, d'_x, d'_y, d_x, d_y)

  enum class Elasticity { Decoupled, PlaneStress, PlaneStrain };
  struct Material {
    double E = 0.0, nu = 0.0, rho = 0.0, width = 0.0, height = 0.0;
    double shearFactor = 0.0;  // k_s; 0: Cowper's 10 (1 + nu) / (12 + 11 nu) (decoupled), 1 (plane forms)
    double damping = 0.0;      // Kelvin-Voigt time constant [s]
    Elasticity elasticity = Elasticity::Decoupled;
  };

  double area() const { return m.width * m.height; }
  double inertia() const { return m.width * m.height * m.height * m.height / 12.0; }
  double inertia4() const { return m.width * std::pow(m.height, 5) / 80.0; }
  double shearModulus() const { return m.E / (2.0 * (1.0 + m.nu)); }
  double shearFactor() const {
    if (m.shearFactor > 0.0) return m.shearFactor;
    return m.elasticity == Elasticity::Decoupled ? 10.0 * (1.0 + m.nu) / (12.0 + 11.0 * m.nu) : 1.0;
  }

  // The full 6 x 6 section stiffness C (row-major) over (e0, e1, e2, g0, s0, s1).
  void stiffness(double C[kMeasures][kMeasures]) const {
    double C11 = m.E, C22 = m.E, C12 = 0.0, C33 = shearFactor() * shearModulus();
    if (m.elasticity == Elasticity::PlaneStress) {
      C11 = C22 = m.E / (1.0 - m.nu * m.nu);
      C12 = m.nu * C11;
    } else if (m.elasticity == Elasticity::PlaneStrain) {
      const double lambda = m.E * m.nu / ((1.0 + m.nu) * (1.0 - 2.0 * m.nu)), mu = shearModulus();
      C11 = C22 = lambda + 2.0 * mu;
      C12 = lambda;
      C33 = shearFactor() * mu;
    }
    const double A = area(), I = inertia(), I4 = inertia4();
    for (int i = 0; i < kMeasures; ++i)
      for (int j = 0; j < kMeasures; ++j) C[i][j] = 0.0;
    C[E0][E0] = C11 * A;
    C[E1][E1] = C11 * I;
    C[E0][E2] = C[E2][E0] = C11 * I;
    C[E2][E2] = C11 * I4;
    C[G0][G0] = C22 * A;
    C[G0][E0] = C[E0][G0] = C12 * A;
    C[G0][E2] = C[E2][G0] = C12 * I;
    C[S0][S0] = 4.0 * C33 * A;
    C[S1][S1] = 4.0 * C33 * I;
  }

  // J = dm/dG (row i: the gradient of measure i) at G; linear in G, so also dm/dt = J(Gd) . ...
  template <class S>
  [[gnu::always_inline]] static void gradients(const S* G, S J[kMeasures][kG]) {
    const S* c1 = G;      // c'
    const S* d1 = G + 2;  // d'
    const S* d = G + 4;   // d
    for (int i = 0; i < kMeasures; ++i)
      for (int k = 0; k < kG; ++k) J[i][k] = S(0.0);
    for (int k = 0; k < 2; ++k) {
      J[E0][k] = c1[k];
      J[E1][k] = d1[k];
      J[E1][2 + k] = c1[k];
      J[E2][2 + k] = d1[k];
      J[G0][4 + k] = d[k];
      J[S0][k] = 0.5 * d[k];
      J[S0][4 + k] = 0.5 * c1[k];
      J[S1][2 + k] = 0.5 * d[k];
      J[S1][4 + k] = 0.5 * d1[k];
    }
  }

  // The measures at G = Gr + Gu (Gr: the initial shape) (e0, g0 from the initial metric without cancellation).
  template <class S>
  [[gnu::always_inline]] static void measures(const double* Gr, const S* Gu, const S* G, S* mv) {
    mv[E0] = Gr[0] * Gu[0] + Gr[1] * Gu[1] + 0.5 * (Gu[0] * Gu[0] + Gu[1] * Gu[1]);
    mv[E1] = G[0] * G[2] + G[1] * G[3];
    mv[E2] = 0.5 * (G[2] * G[2] + G[3] * G[3]);
    mv[G0] = Gr[4] * Gu[4] + Gr[5] * Gu[5] + 0.5 * (Gu[4] * Gu[4] + Gu[5] * Gu[5]);
    mv[S0] = 0.5 * (G[0] * G[4] + G[1] * G[5]);
    mv[S1] = 0.5 * (G[2] * G[4] + G[3] * G[5]);
  }

  // Pointwise force f_G = J^T C (m + eta dm/dt) for one rule's C (Gd null: no damping).
  template <class S>
  [[gnu::always_inline]] static void force(const double C[kMeasures][kMeasures], double eta, const double* Gr,
                                           const S* Gu, const S* Gd, S* fG) {
    S G[kG], J[kMeasures][kG], mv[kMeasures], stress[kMeasures];
    for (int k = 0; k < kG; ++k) G[k] = Gr[k] + Gu[k];
    measures(Gr, Gu, G, mv);
    gradients(G, J);
    if (Gd)
      for (int i = 0; i < kMeasures; ++i) {
        S rate(0.0);
        for (int k = 0; k < kG; ++k) rate += J[i][k] * Gd[k];
        mv[i] += eta * rate;
      }
    for (int i = 0; i < kMeasures; ++i) {
      stress[i] = S(0.0);
      for (int j = 0; j < kMeasures; ++j) stress[i] += C[i][j] * mv[j];
    }
    for (int k = 0; k < kG; ++k) {
      fG[k] = S(0.0);
      for (int i = 0; i < kMeasures; ++i) fG[k] += J[i][k] * stress[i];
    }
  }

  // Energy per unit length W = 1/2 m^T C m.
  template <class S>
  [[gnu::always_inline]] static S energy(const double C[kMeasures][kMeasures], const double* Gr, const S* Gu) {
    S G[kG], mv[kMeasures];
    for (int k = 0; k < kG; ++k) G[k] = Gr[k] + Gu[k];
    measures(Gr, Gu, G, mv);
    S w(0.0);
    for (int i = 0; i < kMeasures; ++i)
      for (int j = 0; j < kMeasures; ++j) w += 0.5 * mv[i] * C[i][j] * mv[j];
    return w;
  }

  // Rayleigh dissipation per unit length R = eta/2 dm^T C dm (the damping force is dR/dv).
  template <class S>
  static S dissipation(const double C[kMeasures][kMeasures], double eta, const double* Gr, const S* Gu, const S* Gd) {
    S G[kG], J[kMeasures][kG], rate[kMeasures];
    for (int k = 0; k < kG; ++k) G[k] = Gr[k] + Gu[k];
    gradients(G, J);
    for (int i = 0; i < kMeasures; ++i) {
      rate[i] = S(0.0);
      for (int k = 0; k < kG; ++k) rate[i] += J[i][k] * Gd[k];
    }
    S r(0.0);
    for (int i = 0; i < kMeasures; ++i)
      for (int j = 0; j < kMeasures; ++j) r += 0.5 * eta * rate[i] * C[i][j] * rate[j];
    return r;
  }

  // f_G, K_G = df_G/dG and D_G = df_G/dGd (Gd null: no damping, D_G untouched).
  [[gnu::always_inline]] static void tangent(const double C[kMeasures][kMeasures], double eta, const double* Gr,
                                             const double* Gu, const double* Gd, double* fG, double KG[kG][kG],
                                             double DG[kG][kG]) {
    double G[kG], J[kMeasures][kG], mv[kMeasures], stress[kMeasures], CJ[kMeasures][kG];
    for (int k = 0; k < kG; ++k) G[k] = Gr[k] + Gu[k];
    measures(Gr, Gu, G, mv);
    gradients(G, J);
    double Jd[kMeasures][kG];  // J(Gd): d(dm/dt)/dG
    if (Gd) {
      gradients(Gd, Jd);
      for (int i = 0; i < kMeasures; ++i) {
        double rate = 0.0;
        for (int k = 0; k < kG; ++k) rate += J[i][k] * Gd[k];
        mv[i] += eta * rate;
      }
    }
    for (int i = 0; i < kMeasures; ++i) {
      stress[i] = 0.0;
      for (int j = 0; j < kMeasures; ++j) stress[i] += C[i][j] * mv[j];
      for (int k = 0; k < kG; ++k) {
        double s = 0.0;
        for (int j = 0; j < kMeasures; ++j) s += C[i][j] * J[j][k];
        CJ[i][k] = s;
      }
    }
    for (int k = 0; k < kG; ++k) {
      fG[k] = 0.0;
      for (int i = 0; i < kMeasures; ++i) fG[k] += J[i][k] * stress[i];
    }
    // J^T C J (+ eta J^T C J(Gd): C is symmetric, so (C J)^T J(Gd))
    for (int a = 0; a < kG; ++a)
      for (int b = 0; b < kG; ++b) {
        double s = 0.0;
        for (int i = 0; i < kMeasures; ++i) s += CJ[i][a] * J[i][b];
        KG[a][b] = s;
        if (Gd) {
          DG[a][b] = eta * s;
          double t = 0.0;
          for (int i = 0; i < kMeasures; ++i) t += CJ[i][a] * Jd[i][b];
          KG[a][b] += eta * t;
        }
      }
    // sum_i S_i H_i: blocks [[S_e0, S_e1, S_s0/2], [S_e1, S_e2, S_s1/2], [S_s0/2, S_s1/2, S_g0]] (x) I_2
    const double H[3][3] = {{stress[E0], stress[E1], 0.5 * stress[S0]},
                            {stress[E1], stress[E2], 0.5 * stress[S1]},
                            {0.5 * stress[S0], 0.5 * stress[S1], stress[G0]}};
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q)
        for (int k = 0; k < 2; ++k) KG[2 * p + k][2 * q + k] += H[p][q];
  }

  Material m;
};

}  // namespace strand::elements
