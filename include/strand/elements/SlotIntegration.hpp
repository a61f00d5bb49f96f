// Element forces and matrices integrated along the element by the chain rule, for every element
// kind whose pointwise kinematics is a set of C "channels" that are linear in the coordinates:
//   G_c(x) = sum_a B_c[a](x) q_a   (c = 0..C-1, each a D-vector; a = 0..S-1 the element's slots,
//                                   one block of D coordinates each).
// The cable's channels are r' and r'' (AncfCable.hpp); the shear-deformable beams' are the
// centerline tangent, the rate of the cross-section vector and the cross-section vector
// (AncfBeam2d.hpp). With the pointwise force f_G = dW/dG and stiffness K_G = d2W/dG2 of a kind,
//   f_a = sum_g w_g l sum_c B_c[a](x_g) f_G[c](x_g),
//   K_ab = sum_g w_g l sum_{c,e} B_c[a] K_G[c][e] B_e[b].
// Slot 0 is node 1's position and Pos2 node 2's. The strains of an ANCF element see the positions
// only through derivatives, whose weights on the two positions are opposite (B_c[0] = -B_c[Pos2]):
// positions enter relative to node 1 (chord = r_2 - r_1, exact to eps_mach l, where the absolute
// positions of a long cable would put eps_mach |r| / l of noise into the strains), and the rows and
// columns of slot 0 are minus those of slot Pos2 (completeFirstPosition).
//
// The points are stored as a structure of arrays, X[...][g], padded with zero-weight copies of the
// last point to an even count P, and the loops are instantiated per P (withPaddedPoints): their trip
// count is then known at compile time and the compiler evaluates two or more points per instruction
// (-O3; docs/architecture.md, decision 19).
#pragma once
#include <cmath>
#include <stdexcept>
#include <type_traits>

#include "strand/math/Gauss.hpp"

namespace strand::elements {

// The slot coefficients of one rule's points: B[c][a][g], and the chain rule's weights wB = w l B.
template <int S, int C>
struct SlotPoints {
  static constexpr int kMax = 8;  // 1 to 8 Gauss points
  int count = 0;                  // Gauss points
  int padded = 0;                 // count rounded up to even
  double B[C][S][kMax];
  double wl[kMax];                // Gauss weight times element length; 0 on the padding
  double wB[C][S][kMax];

  // Fills the table from a rule on [0, 1] and the coefficients B(eta, c, a) at each point.
  template <class Coefficients>
  static SlotPoints build(const math::QuadratureRule& rule, double length, Coefficients&& coefficients) {
    if (rule.size() < 1 || rule.size() > kMax) throw std::invalid_argument("SlotPoints: 1 to 8 Gauss points");
    SlotPoints t;
    t.count = rule.size();
    t.padded = t.count + t.count % 2;
    for (int g = 0; g < kMax; ++g) {
      const int from = g < t.count ? g : t.count - 1;
      double b[C][S];
      coefficients(rule.x[from], b);
      t.wl[g] = g < t.count ? rule.w[g] * length : 0.0;
      for (int c = 0; c < C; ++c)
        for (int a = 0; a < S; ++a) {
          t.B[c][a][g] = b[c][a];
          t.wB[c][a][g] = t.wl[g] * b[c][a];
        }
    }
    return t;
  }
};

// Call f(std::integral_constant<int, P>) with P the table's padded point count.
template <class Table, class F>
decltype(auto) withPaddedPoints(const Table& t, F&& f) {
  switch (t.padded) {
    case 2: return f(std::integral_constant<int, 2>{});
    case 4: return f(std::integral_constant<int, 4>{});
    case 6: return f(std::integral_constant<int, 6>{});
    default: return f(std::integral_constant<int, 8>{});
  }
}

// The chain rule over the slots of an element with D coordinates per slot, S slots, C channels and
// node 2's position in slot Pos2 (node 1's in slot 0).
template <int D, int S, int C, int Pos2>
struct SlotCalculus {
  static_assert(Pos2 > 0 && Pos2 < S, "node 2's position is a slot after node 1's");
  static constexpr int kG = C * D;    // size of the pointwise vector G
  static constexpr int kDof = S * D;  // element coordinates
  using Points = SlotPoints<S, C>;

  // G[c D + i][g] at every point: chord first, then the other slots in order.
  template <int P, class Sc, class Q>
  static void gather(const Points& t, const Q* q, Sc G[kG][P]) {
    for (int i = 0; i < D; ++i) {
      const Q chord = q[Pos2 * D + i] - q[i];
      for (int c = 0; c < C; ++c)
        for (int g = 0; g < P; ++g) {
          Sc sum = t.B[c][Pos2][g] * chord;
          for (int a = 1; a < S; ++a)
            if (a != Pos2) sum += t.B[c][a][g] * q[a * D + i];
          G[c * D + i][g] = sum;
        }
    }
  }

  // f_a = sum_g sum_c wB[c][a][g] fG[c D + i][g] for the slots a >= 1; slot 0 = -slot Pos2.
  template <int P, class Sc>
  static void integrateForce(const Points& t, const Sc fG[kG][P], Sc* f) {
    for (int a = 1; a < S; ++a)
      for (int i = 0; i < D; ++i) {
        Sc sum(0.0);
        for (int g = 0; g < P; ++g) {
          Sc term = t.wB[0][a][g] * fG[i][g];
          for (int c = 1; c < C; ++c) term = term + t.wB[c][a][g] * fG[c * D + i][g];
          sum += term;
        }
        f[a * D + i] = sum;
      }
    for (int i = 0; i < D; ++i) f[i] = -f[Pos2 * D + i];
  }

  // Element matrix entries sum_g w_g l sum_{c,e} B_c[a] X[c i][e j] B_e[b] for the slots a, b >= 1;
  // with upperOnly, only the blocks b >= a (mirrorUpper completes a symmetric result). Slot 0
  // follows from completeFirstPosition.
  template <int P>
  static void integrateMatrix(const Points& t, const double X[kG][kG][P], double* K, bool upperOnly) {
    // T[a][i][k][g] = w l sum_c B_c[a] X[c i][k] first: elementwise over the points, so it
    // vectorizes; what is left is one sum over the points per entry
    double T[S - 1][D][kG][P];
    for (int a = 1; a < S; ++a)
      for (int i = 0; i < D; ++i)
        for (int k = 0; k < kG; ++k)
          for (int g = 0; g < P; ++g) {
            double term = t.wB[0][a][g] * X[i][k][g];
            for (int c = 1; c < C; ++c) term = term + t.wB[c][a][g] * X[c * D + i][k][g];
            T[a - 1][i][k][g] = term;
          }
    for (int a = 1; a < S; ++a)
      for (int b = upperOnly ? a : 1; b < S; ++b)
        for (int i = 0; i < D; ++i)
          for (int j = 0; j < D; ++j) {
            double sum = 0.0;
            for (int g = 0; g < P; ++g) {
              double term = T[a - 1][i][j][g] * t.B[0][b][g];
              for (int e = 1; e < C; ++e) term = term + T[a - 1][i][e * D + j][g] * t.B[e][b][g];
              sum += term;
            }
            K[(a * D + i) * kDof + b * D + j] = sum;
          }
  }

  // The lower blocks of slots a, b >= 1 from the upper ones (after integrateMatrix(upperOnly)).
  static void mirrorUpper(double* K) {
    for (int r = D; r < kDof; ++r)
      for (int c = (r / D + 1) * D; c < kDof; ++c) K[c * kDof + r] = K[r * kDof + c];
  }

  // Rows and columns of slot 0 are minus those of slot Pos2 (B_c[0] = -B_c[Pos2]); block (0, 0)
  // equals block (Pos2, Pos2).
  static void completeFirstPosition(double* K) {
    for (int r = D; r < kDof; ++r)
      for (int j = 0; j < D; ++j) K[r * kDof + j] = -K[r * kDof + Pos2 * D + j];
    for (int i = 0; i < D; ++i)
      for (int c = 0; c < kDof; ++c) K[i * kDof + c] = -K[(Pos2 * D + i) * kDof + c];
  }

  // Point g of an array X[k][g] (pointwise laws take one point's values).
  template <int P, class Sc>
  [[gnu::always_inline]] static void lane(const Sc X[kG][P], int g, Sc* x) {
    for (int k = 0; k < kG; ++k) x[k] = X[k][g];
  }
};

}  // namespace strand::elements
