// Finite elements for the floating-frame beam (seed 001, "FEM", after Chung & Yoo, J. Sound Vib.
// 249 (2002) 147): `elements` equal elements, linear axial shapes and Hermite cubic bending shapes.
// Node k = 1..N carries (u_k, w_k, w'_k) at d[3(k-1) .. 3(k-1)+2]; node 0 is clamped.
#pragma once
#include "strand/ffr/DeformationBasis.hpp"

namespace strand::ffr {

class HermiteFem : public DeformationBasis {
public:
  HermiteFem(double length, int elements);
  int size() const override { return 3 * _N; }
  double length() const override { return _L; }
  std::string name() const override;
  void shapes(double x, ShapeRows& rows) const override;
  // 4 Gauss points per element: exact for every matrix of HubBeamMatrices (degree <= 7).
  std::vector<QuadraturePoint> quadrature() const override;

private:
  double _L;
  int _N;
};

}  // namespace strand::ffr
