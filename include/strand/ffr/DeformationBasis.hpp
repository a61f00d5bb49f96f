// The deformation field of a beam in its floating frame (seed 001 Eq. 39-40): axial stretch
// w1(x) = phi_a(x) d and bending deflection w2(x) = phi_b(x) d, one coordinate vector d for both
// (each row has zeros where the other field's coordinates are). The beam is clamped at x = 0, so
// every shape vanishes there with its slope; the bases build that in (no constraint rows).
//
// Three discretizations behind this interface (issue 5): AssumedModes, HermiteFem and
// RadialPointInterpolation. Each supplies its own quadrature over [0, L], exact or converged for
// its shapes, so that the constant matrices of HubBeamMatrices.hpp are integrated well.
#pragma once
#include <Eigen/Dense>

#include <string>
#include <vector>

namespace strand::ffr {

// Shape rows (1 x n) at a point x: axial phi_a and its slope; bending phi_b, slope and curvature.
struct ShapeRows {
  Eigen::RowVectorXd axial, axialSlope, bending, bendingSlope, bendingCurvature;
};

struct QuadraturePoint {
  double x = 0.0, weight = 0.0;  // position on [0, L] [m] and weight [m]
};

class DeformationBasis {
public:
  virtual ~DeformationBasis() = default;
  virtual int size() const = 0;                    // n, the number of coordinates d
  virtual double length() const = 0;               // L [m]
  virtual std::string name() const = 0;            // e.g. "fem 10 elements"
  virtual void shapes(double x, ShapeRows& rows) const = 0;
  virtual std::vector<QuadraturePoint> quadrature() const = 0;
};

// Gauss-Legendre points on `cells` equal cells of [0, L], `points` per cell.
std::vector<QuadraturePoint> cellQuadrature(double length, int cells, int points);

}  // namespace strand::ffr
