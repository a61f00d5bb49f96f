// Holonomic constraint kernels for joints (design section 3): g(q) = 0, held by Lagrange
// multipliers. Pure functions of the joint's coordinates q (its blocks concatenated, D each);
// no PETSc here.
//
// A constraint relates two vector fields a(q), b(q) of the joint's coordinates:
//   Constant        a ground point or direction c;
//   Block           the coordinates of block k (a cable node's position or slope vector);
//   RigidPoint      a body point: 2D r + R(phi) c (position block k, phi = first entry of block k+1);
//                   3D r + c_1 a_1 + c_2 a_2 + c_3 a_3 (block k, then the frame blocks a_i);
//   RigidDirection  a body direction: 2D R(phi) c (phi in block k); 3D c_i a_i (a_1 in block k).
// A 3D rigid body is described by natural coordinates: its centre of mass r and its frame vectors
// a_i, the columns of the rotation matrix (Garcia de Jalon & Bayo 1994, ch. 3; Shabana's ANCF
// reference node). Its points and directions are linear in them, so their Hessians vanish.
// Forms:
//   Equal       a - b = 0                     (D equations: pins, node-to-node);
//   Distance    |a - b| - L = 0               (1 equation; the multiplier is the tension);
//   Orthogonal  a . b = 0                     (1 equation: a slope normal to a direction);
//   Linear      sum_k c_k q_k - length = 0 over component 0 of blocks 0, 1, 2, c = a.c (1 equation:
//               material coordinates held equally spaced, seed 000 Eq. 51: p_n - (1-w) p_a - w p_c;
//               a reel paying out, p_exit +/- R phi - p_exit(0), + at node 0, - at the last).
// For each form: g, its gradient G = dg/dq (m x n, row-major) and the contracted Hessian
// H = sum_k w_k d^2 g_k / dq^2 (n x n) that the Newton matrix needs for the term G^T lambda.
#pragma once
#include <array>
#include <cmath>

namespace strand::elements {

inline constexpr int kMaxJointCoordinates = 24;  // two 3D rigid bodies: eight blocks of three

struct JointField {
  enum class Kind { Constant, Block, RigidPoint, RigidDirection } kind = Kind::Constant;
  int block = 0;                      // index among the joint's blocks
  std::array<double, 3> c{};          // Constant: the value; Rigid*: body-frame vector
};

enum class ConstraintForm { Equal, Distance, Orthogonal, Linear };

struct ConstraintEq {
  ConstraintForm form = ConstraintForm::Equal;
  JointField a, b;
  double length = 0.0;  // Distance: the length; Linear: the constant
};

template <int D>
struct Constraint {
  static constexpr int kMax = kMaxJointCoordinates;

  static int equations(const ConstraintEq& c) { return c.form == ConstraintForm::Equal ? D : 1; }

  // Value v (D) and derivative dv (D x n) of a field.
  static void field(const JointField& f, const double* q, int n, double* v, double* dv) {
    for (int i = 0; i < D; ++i) v[i] = 0.0;
    for (int i = 0; i < D * n; ++i) dv[i] = 0.0;
    switch (f.kind) {
      case JointField::Kind::Constant:
        for (int i = 0; i < D; ++i) v[i] = f.c[i];
        return;
      case JointField::Kind::Block:
        for (int i = 0; i < D; ++i) {
          v[i] = q[f.block * D + i];
          dv[i * n + f.block * D + i] = 1.0;
        }
        return;
      case JointField::Kind::RigidPoint:
      case JointField::Kind::RigidDirection: {
        const bool point = f.kind == JointField::Kind::RigidPoint;
        const int rot = point ? f.block + 1 : f.block;
        if constexpr (D == 3) {  // natural coordinates: (r +) sum_k c_k a_k, linear
          for (int i = 0; i < 3; ++i) {
            v[i] = point ? q[f.block * 3 + i] : 0.0;
            if (point) dv[i * n + f.block * 3 + i] = 1.0;
            for (int k = 0; k < 3; ++k) {
              v[i] += f.c[k] * q[(rot + k) * 3 + i];
              dv[i * n + (rot + k) * 3 + i] = f.c[k];
            }
          }
          return;
        }
        const double phi = q[rot * D], c = std::cos(phi), s = std::sin(phi);
        const double R[2] = {c * f.c[0] - s * f.c[1], s * f.c[0] + c * f.c[1]};  // R(phi) c
        for (int i = 0; i < 2; ++i) {
          v[i] = (point ? q[f.block * D + i] : 0.0) + R[i];
          if (point) dv[i * n + f.block * D + i] = 1.0;
        }
        dv[0 * n + rot * D] = -R[1];  // dR/dphi c = [e_z]x R c
        dv[1 * n + rot * D] = R[0];
        return;
      }
    }
  }

  // H += s sum_i w_i d^2 v_i / dq^2 (only 2D rigid fields are nonlinear: d^2 (R c)/dphi^2 = -R c).
  static void addFieldHessian(const JointField& f, const double* q, int n, const double* w, double s, double* H) {
    if constexpr (D == 3) return;
    if (f.kind != JointField::Kind::RigidPoint && f.kind != JointField::Kind::RigidDirection) return;
    const int rot = f.kind == JointField::Kind::RigidPoint ? f.block + 1 : f.block;
    const double phi = q[rot * D], c = std::cos(phi), sn = std::sin(phi);
    const double R[2] = {c * f.c[0] - sn * f.c[1], sn * f.c[0] + c * f.c[1]};
    H[rot * D * n + rot * D] -= s * (w[0] * R[0] + w[1] * R[1]);
  }

  // g (m) and G (m x n).
  static void evaluate(const ConstraintEq& k, const double* q, int n, double* g, double* G) {
    if (k.form == ConstraintForm::Linear) {  // G constant, no Hessian
      g[0] = -k.length;
      for (int j = 0; j < n; ++j) G[j] = 0.0;
      for (int b = 0; b < 3 && b * D < n; ++b) {
        g[0] += k.a.c[b] * q[b * D];
        G[b * D] = k.a.c[b];
      }
      return;
    }
    double a[D], b[D], da[D * kMax], db[D * kMax];
    field(k.a, q, n, a, da);
    field(k.b, q, n, b, db);
    switch (k.form) {
      case ConstraintForm::Linear:
        return;  // above
      case ConstraintForm::Equal:
        for (int i = 0; i < D; ++i) {
          g[i] = a[i] - b[i];
          for (int j = 0; j < n; ++j) G[i * n + j] = da[i * n + j] - db[i * n + j];
        }
        return;
      case ConstraintForm::Distance: {
        double d[D], len = 0.0;
        for (int i = 0; i < D; ++i) {
          d[i] = a[i] - b[i];
          len += d[i] * d[i];
        }
        len = std::sqrt(len);
        g[0] = len - k.length;
        for (int j = 0; j < n; ++j) {
          double s = 0.0;
          for (int i = 0; i < D; ++i) s += d[i] * (da[i * n + j] - db[i * n + j]);
          G[j] = s / len;
        }
        return;
      }
      case ConstraintForm::Orthogonal:
        g[0] = 0.0;
        for (int i = 0; i < D; ++i) g[0] += a[i] * b[i];
        for (int j = 0; j < n; ++j) {
          double s = 0.0;
          for (int i = 0; i < D; ++i) s += b[i] * da[i * n + j] + a[i] * db[i * n + j];
          G[j] = s;
        }
        return;
    }
  }

  // H += s sum_k w_k d^2 g_k / dq^2 (n x n).
  static void addHessian(const ConstraintEq& k, const double* q, int n, const double* w, double s, double* H) {
    if (k.form == ConstraintForm::Linear) return;  // linear
    if (k.form == ConstraintForm::Equal) {  // g = a - b: only the fields' own curvature
      double mw[D];
      for (int i = 0; i < D; ++i) mw[i] = -w[i];
      addFieldHessian(k.a, q, n, w, s, H);
      addFieldHessian(k.b, q, n, mw, s, H);
      return;
    }
    double a[D], b[D], da[D * kMax], db[D * kMax];
    field(k.a, q, n, a, da);
    field(k.b, q, n, b, db);
    switch (k.form) {
      case ConstraintForm::Equal:
      case ConstraintForm::Linear:
        return;
      case ConstraintForm::Distance: {
        // g = |d|, d = a - b: d^2 g = (Dd^T (I - e e^T) Dd) / |d| + sum_i e_i d^2 d_i, e = d / |d|
        double d[D], e[D], len = 0.0, Dd[D * kMax];
        for (int i = 0; i < D; ++i) {
          d[i] = a[i] - b[i];
          len += d[i] * d[i];
        }
        len = std::sqrt(len);
        for (int i = 0; i < D; ++i) e[i] = d[i] / len;
        for (int i = 0; i < D * n; ++i) Dd[i] = da[i] - db[i];
        double eD[kMax];
        for (int j = 0; j < n; ++j) {
          eD[j] = 0.0;
          for (int i = 0; i < D; ++i) eD[j] += e[i] * Dd[i * n + j];
        }
        const double sw = s * w[0];
        for (int r = 0; r < n; ++r)
          for (int c = 0; c < n; ++c) {
            double dd = 0.0;
            for (int i = 0; i < D; ++i) dd += Dd[i * n + r] * Dd[i * n + c];
            H[r * n + c] += sw * (dd - eD[r] * eD[c]) / len;
          }
        double we[D], mwe[D];
        for (int i = 0; i < D; ++i) {
          we[i] = w[0] * e[i];
          mwe[i] = -we[i];
        }
        addFieldHessian(k.a, q, n, we, s, H);
        addFieldHessian(k.b, q, n, mwe, s, H);
        return;
      }
      case ConstraintForm::Orthogonal: {
        // g = a . b: d^2 g = da^T db + db^T da + sum_i b_i d^2 a_i + sum_i a_i d^2 b_i
        const double sw = s * w[0];
        for (int r = 0; r < n; ++r)
          for (int c = 0; c < n; ++c) {
            double x = 0.0;
            for (int i = 0; i < D; ++i) x += da[i * n + r] * db[i * n + c] + db[i * n + r] * da[i * n + c];
            H[r * n + c] += sw * x;
          }
        double wb[D], wa[D];
        for (int i = 0; i < D; ++i) {
          wb[i] = w[0] * b[i];
          wa[i] = w[0] * a[i];
        }
        addFieldHessian(k.a, q, n, wb, s, H);
        addFieldHessian(k.b, q, n, wa, s, H);
        return;
      }
    }
  }
};

}  // namespace strand::elements
