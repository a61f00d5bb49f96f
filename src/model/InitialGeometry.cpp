#include "strand/model/InitialGeometry.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "strand/core/Error.hpp"

namespace strand::model {
namespace {

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 add(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec3 scale(double s, const Vec3& a) { return {s * a[0], s * a[1], s * a[2]}; }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3 unit(const Vec3& a) { return scale(1.0 / norm(a), a); }

}  // namespace

// The path from start around each circle to end. Circle i (centre c_i, radius rho_i, sense
// sigma_i) has its centre at c_i - T = sigma_i rho_i n_L from a point T where the path touches it
// (n_L: the left normal of the direction of travel). A tangent line from circle 1 to circle 2
// (start and end are circles of radius 0) therefore has, with d = c_2 - c_1 = D (cos a, sin a) and
// e = sigma_2 rho_2 - sigma_1 rho_1: direction angle a - asin(e / D), length sqrt(D^2 - e^2), and
// it leaves circle 1 at T_1 = c_1 - sigma_1 rho_1 n_L.
void InitialGeometry::buildWrap() {
  auto fail = [&](const std::string& why) { throw InputError(_d.mark.where() + ": " + why); };
  struct Circle {
    Vec3 c;
    double rho;
    int sense, turns;
    std::string name;
  };
  // open: start, the circles, end (points are circles of radius 0); closed: the circles, then the
  // first again
  std::vector<Circle> circles;
  if (!_d.closed) circles.push_back({_d.start, 0.0, 1, 0, "start"});
  for (size_t k = 0; k < _d.wrap.size(); ++k)
    circles.push_back({_d.wrap[k].center, _d.wrap[k].radius, _d.wrap[k].sense, _d.wrap[k].turns,
                       "around[" + std::to_string(k) + "]"});
  if (_d.closed) circles.push_back(circles.front());
  else circles.push_back({_d.end, 0.0, 1, 0, "end"});
  const size_t m = circles.size();
  std::vector<Vec3> leave(m), arrive(m), lineDir(m);
  std::vector<double> lineLength(m, 0.0);
  for (size_t i = 0; i + 1 < m; ++i) {
    const Circle& a = circles[i];
    const Circle& b = circles[i + 1];
    const Vec3 d = sub(b.c, a.c);
    const double D = norm(d), e = b.sense * b.rho - a.sense * a.rho;
    if (!(std::fabs(e) < D))
      fail("no tangent line from " + a.name + " to " + b.name + " in the given senses (one lies inside or on the other)");
    const double phi = std::atan2(d[1], d[0]) - std::asin(e / D);
    lineDir[i] = {std::cos(phi), std::sin(phi), 0.0};
    const Vec3 left{-std::sin(phi), std::cos(phi), 0.0};
    leave[i] = sub(a.c, scale(a.sense * a.rho, left));
    lineLength[i] = std::sqrt(D * D - e * e);
    arrive[i + 1] = add(leave[i], scale(lineLength[i], lineDir[i]));
  }
  if (_d.closed) arrive[0] = arrive[m - 1];  // the last line comes back to the first circle
  const double twoPi = 2.0 * std::acos(-1.0);
  _cumulative.assign(1, 0.0);
  auto addArc = [&](size_t i) {  // on circle i, from where the line arrives to where the next leaves
    const Circle& c = circles[i];
    const double in = std::atan2(arrive[i][1] - c.c[1], arrive[i][0] - c.c[0]);
    const double out = std::atan2(leave[i][1] - c.c[1], leave[i][0] - c.c[0]);
    double sweep = std::fmod(c.sense * (out - in) + 2.0 * twoPi, twoPi);
    if (sweep > twoPi * (1.0 - 1e-12)) sweep = 0.0;  // touching: round-off below a full turn
    sweep += twoPi * c.turns;
    if (!(sweep > 0.0)) return;
    WrapPiece arc;
    arc.arc = true;
    arc.center = c.c;
    arc.radius = c.rho;
    arc.angle0 = in;
    arc.sense = c.sense;
    _pieces.push_back(arc);
    _cumulative.push_back(_cumulative.back() + c.rho * sweep);
  };
  auto addLine = [&](const Vec3& from, const Vec3& direction, double length) {
    WrapPiece line;
    line.start = from;
    line.direction = direction;
    _pieces.push_back(line);
    _cumulative.push_back(_cumulative.back() + length);
  };
  if (!_d.closed) {
    for (size_t i = 0; i + 1 < m; ++i) {
      if (i > 0) addArc(i);
      addLine(leave[i], lineDir[i], lineLength[i]);
    }
  } else {
    // a closed path starts (and ends) halfway along the line from the first pulley to the second:
    // a two-pulley loop is then symmetric about its first node
    const double half = 0.5 * lineLength[0];
    const Vec3 middle = add(leave[0], scale(half, lineDir[0]));
    addLine(middle, lineDir[0], half);
    for (size_t i = 1; i + 1 < m; ++i) {
      addArc(i);
      addLine(leave[i], lineDir[i], lineLength[i]);
    }
    addArc(0);
    addLine(leave[0], lineDir[0], half);
  }
  _length = _cumulative.back();
  if (!(_length > 0.0)) fail("the wrap path has zero length");
}

InitialGeometry::InitialGeometry(const GeometryDesc& desc, int dimension, const Vec3& gravity) : _d(desc) {
  auto fail = [&](const std::string& why) { throw InputError(desc.mark.where() + ": " + why); };
  if (dimension == 2) {
    _d.start[2] = _d.end[2] = _d.center[2] = 0.0;
    for (auto& p : _d.points) p[2] = 0.0;
    for (auto& w : _d.wrap) w.center[2] = 0.0;
    _d.normal = {0.0, 0.0, 1.0};
  }
  switch (_d.kind) {
    case GeometryKind::Wrap:
      if (dimension != 2) fail("a wrap path lies in the xy plane: only when dimension is 2");
      buildWrap();
      break;
    case GeometryKind::Line:
      _length = norm(sub(_d.end, _d.start));
      if (!(_length > 0.0)) fail("line has zero length");
      break;
    case GeometryKind::Arc: {
      const Vec3 n = unit(_d.normal);
      Vec3 u = sub(Vec3{1, 0, 0}, scale(n[0], n));
      if (norm(u) < 1e-8) u = sub(Vec3{0, 1, 0}, scale(n[1], n));
      _u = unit(u);
      _v = cross(n, _u);
      _length = _d.radius * std::fabs(_d.endAngle - _d.startAngle);
      if (!(_length > 0.0)) fail("arc has zero length");
      break;
    }
    case GeometryKind::Polyline:
      _cumulative.push_back(0.0);
      for (size_t k = 1; k < _d.points.size(); ++k) {
        const double s = norm(sub(_d.points[k], _d.points[k - 1]));
        if (!(s > 0.0)) fail("polyline has a zero-length segment at point " + std::to_string(k));
        _cumulative.push_back(_cumulative.back() + s);
      }
      if (_cumulative.size() < 2) fail("polyline needs at least 2 points");
      _length = _cumulative.back();
      break;
    case GeometryKind::Catenary: {
      // Inextensible catenary of length S through start and end, sagging along g:
      //   eta(xi) = a cosh((xi - xi0)/a) - a cosh(xi0/a),  sqrt(S^2 - v^2) = 2 a sinh(H / (2a)).
      Vec3 g = _d.sagDirection;
      if (norm(g) == 0.0) g = norm(gravity) > 0.0 ? gravity : (dimension == 2 ? Vec3{0, -1, 0} : Vec3{0, 0, -1});
      g = unit(g);
      const Vec3 up = scale(-1.0, g);
      const Vec3 d = sub(_d.end, _d.start);
      const double v = dot(d, up);  // rise of the end point
      const Vec3 horizontal = sub(d, scale(v, up));
      const double H = norm(horizontal);
      if (!(H > 1e-12)) fail("catenary end points lie on one vertical: no horizontal span");
      _u = unit(horizontal);
      _v = up;
      const double S = _d.length;
      if (!(S * S > v * v + H * H)) fail("catenary length must exceed the distance between its end points");
      const double target = std::sqrt(S * S - v * v);
      // Solve 2 a sinh(H/(2a)) = target for a by bisection on log(a) (monotone decreasing in a).
      double lo = 1e-6 * H, hi = 1e6 * H;
      for (int it = 0; it < 200; ++it) {
        const double mid = std::sqrt(lo * hi);
        const double z = H / (2.0 * mid);
        const double val = (z > 300.0) ? INFINITY : 2.0 * mid * std::sinh(z);
        if (val > target) lo = mid; else hi = mid;
      }
      _a = std::sqrt(lo * hi);
      _xi0 = 0.5 * H - _a * std::atanh(v / S);
      _s0 = _a * std::sinh(-_xi0 / _a);
      _length = S;
      break;
    }
  }
}

CurvePoint InitialGeometry::at(double x) const {
  CurvePoint p{};
  switch (_d.kind) {
    case GeometryKind::Wrap: {
      size_t k = 0;
      while (k + 1 < _pieces.size() && x > _cumulative[k + 1]) ++k;
      const WrapPiece& w = _pieces[k];
      const double s = x - _cumulative[k];
      if (!w.arc) {
        p.t = w.direction;
        p.r = add(w.start, scale(s, w.direction));
        break;
      }
      const double th = w.angle0 + w.sense * s / w.radius;
      p.r = add(w.center, Vec3{w.radius * std::cos(th), w.radius * std::sin(th), 0.0});
      p.t = {-w.sense * std::sin(th), w.sense * std::cos(th), 0.0};
      break;
    }
    case GeometryKind::Line: {
      p.t = unit(sub(_d.end, _d.start));
      p.r = add(_d.start, scale(x, p.t));
      break;
    }
    case GeometryKind::Arc: {
      const double sgn = (_d.endAngle >= _d.startAngle) ? 1.0 : -1.0;
      const double th = _d.startAngle + sgn * x / _d.radius;
      p.r = add(_d.center, add(scale(_d.radius * std::cos(th), _u), scale(_d.radius * std::sin(th), _v)));
      p.t = add(scale(-sgn * std::sin(th), _u), scale(sgn * std::cos(th), _v));
      break;
    }
    case GeometryKind::Polyline: {
      size_t k = 1;
      while (k + 1 < _cumulative.size() && x > _cumulative[k]) ++k;
      const Vec3 seg = sub(_d.points[k], _d.points[k - 1]);
      const double len = _cumulative[k] - _cumulative[k - 1];
      p.t = scale(1.0 / len, seg);
      p.r = add(_d.points[k - 1], scale(x - _cumulative[k - 1], p.t));
      // Exactly at an interior corner: bisect the two segment directions.
      if (k + 1 < _cumulative.size() && std::fabs(x - _cumulative[k]) < 1e-12 * _length)
        p.t = unit(add(p.t, unit(sub(_d.points[k + 1], _d.points[k]))));
      break;
    }
    case GeometryKind::Catenary: {
      const double xi = _xi0 + _a * std::asinh((x + _s0) / _a);
      const double w = (xi - _xi0) / _a;
      const double eta = _a * std::cosh(w) - _a * std::cosh(_xi0 / _a);
      p.r = add(_d.start, add(scale(xi, _u), scale(eta, _v)));
      p.t = add(scale(1.0 / std::cosh(w), _u), scale(std::tanh(w), _v));
      break;
    }
  }
  return p;
}

}  // namespace strand::model
