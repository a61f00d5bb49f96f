#include "strand/model/HubMotion.hpp"

#include <cmath>

namespace strand::model {

namespace {
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
}  // namespace

Vec3 HubMotion::turn(const Vec3& w0, double t, Vec3* rate) const {
  const TimeValue psi = angle.at(t);
  const double turned = psi.f - angle.at(0.0).f;
  // Rodrigues: R w0 = w0 cos + (e x w0) sin + e (e . w0)(1 - cos)
  const double c = std::cos(turned), s = std::sin(turned);
  const Vec3 exw0 = cross(axis, w0);
  const double ew0 = axis[0] * w0[0] + axis[1] * w0[1] + axis[2] * w0[2];
  Vec3 w;
  for (int i = 0; i < 3; ++i) w[i] = w0[i] * c + exw0[i] * s + axis[i] * ew0 * (1.0 - c);
  if (rate) {
    const Vec3 exw = cross(axis, w);
    for (int i = 0; i < 3; ++i) (*rate)[i] = psi.df * exw[i];
  }
  return w;
}

void HubMotion::state(int k, const double* q0, int dim, double t, double* u, double* v, double* a) const {
  // the scene's geometry is the one at t = 0: the hub turns it by psi(t) - psi(0)
  Vec3 w0{};
  for (int i = 0; i < dim; ++i) w0[i] = q0[i] - (slope[k] ? 0.0 : center[i]);
  const Vec3 w = turn(w0, t);
  const TimeValue psi = angle.at(t);
  const Vec3 exw = cross(axis, w), exexw = cross(axis, exw);
  for (int i = 0; i < dim; ++i) {
    u[i] = w[i] - w0[i];
    v[i] = psi.df * exw[i];
    a[i] = psi.ddf * exw[i] + psi.df * psi.df * exexw[i];
  }
}

}  // namespace strand::model
