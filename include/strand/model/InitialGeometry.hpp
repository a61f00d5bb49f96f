// Reference curves that place the nodes of a body: position and unit tangent at arc length x.
#pragma once
#include "strand/model/SceneDescription.hpp"

namespace strand::model {

struct CurvePoint {
  Vec3 r;  // position [m]
  Vec3 t;  // unit tangent dr/dx
};

class InitialGeometry {
public:
  // dimension 2 keeps z = 0. Throws InputError (with the geometry's mark) for impossible shapes.
  InitialGeometry(const GeometryDesc& desc, int dimension, const Vec3& gravity);
  double length() const { return _length; }
  CurvePoint at(double x) const;  // 0 <= x <= length()

private:
  GeometryDesc _d;
  double _length = 0.0;
  Vec3 _u{}, _v{};                   // arc plane basis; catenary: horizontal unit and "up" unit
  std::vector<double> _cumulative;   // polyline: arc length at each corner; wrap: at each piece's start
  // wrap: tangent lines and arcs (seed 004's belt drives: the belt's initial shape around pulleys)
  struct WrapPiece {
    bool arc = false;
    Vec3 start{}, direction{};  // line
    Vec3 center{};              // arc
    double radius = 0.0, angle0 = 0.0;
    int sense = 1;
  };
  std::vector<WrapPiece> _pieces;
  void buildWrap();
  double _a = 0.0, _xi0 = 0.0, _s0 = 0.0;  // catenary parameter, vertex abscissa, arc offset
};

}  // namespace strand::model
