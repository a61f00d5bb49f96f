// A moment applied at a cable node, acting on its slope coordinates e = sigma r'.
//
// The node's rotation is carried by its tangent: delta(phi) = (e x delta e) / |e|^2, so the virtual
// work M . delta(phi) gives the generalized force Q = W e / (e . e) with W e = M x e, i.e.
//   2D: W = M_z [[0, -1], [1, 0]],   3D: W = [M]_x (the cross-product matrix).
// In 2D this is conservative (potential -M theta); in 3D a fixed moment vector is not.
// Q is configuration dependent, so it has a tangent dQ/de = W/s - 2 (W e) e^T / s^2, s = e . e.
#pragma once
#include <array>

namespace strand::elements {

template <int D>
struct NodalMoment {
  static void matrixW(const std::array<double, 3>& M, double W[D][D]) {
    if constexpr (D == 2) {
      W[0][0] = 0.0; W[0][1] = -M[2];
      W[1][0] = M[2]; W[1][1] = 0.0;
    } else {
      W[0][0] = 0.0;   W[0][1] = -M[2]; W[0][2] = M[1];
      W[1][0] = M[2];  W[1][1] = 0.0;   W[1][2] = -M[0];
      W[2][0] = -M[1]; W[2][1] = M[0];  W[2][2] = 0.0;
    }
  }
  // Q (D entries) and optionally dQ/de (row-major D x D).
  static void force(const std::array<double, 3>& M, const double* e, double* Q, double* dQ) {
    double W[D][D], We[D] = {}, s = 0.0;
    matrixW(M, W);
    for (int i = 0; i < D; ++i) {
      s += e[i] * e[i];
      for (int j = 0; j < D; ++j) We[i] += W[i][j] * e[j];
    }
    for (int i = 0; i < D; ++i) Q[i] = We[i] / s;
    if (dQ)
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) dQ[i * D + j] = W[i][j] / s - 2.0 * We[i] * e[j] / (s * s);
  }
};

}  // namespace strand::elements
