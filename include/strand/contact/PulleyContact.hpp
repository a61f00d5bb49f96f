// Distributed belt-pulley contact (issue 34, seed 004): the force per unit reference length that a
// rigid circular pulley exerts on one point of a belt's centerline, in 2D, and its exact tangents.
// Pure functions of the point's state and the pulley's; no PETSc (docs/contact.md).
//
// Kinematics (the penalty formulation of Kerkkänen, García-Vallejo & Mikkola, Nonlinear Dyn. 43
// (2006), with the relative velocity of the two material points that meet):
//   d = r - c,  rho = |d|,  n = d / rho (outward normal),  t = e_z x n (the pulley's positive sense)
//   gap        g = rho - (R + offset)        offset: the belt's contact surface from its centerline (h/2)
//   gap rate   gdot = n . (v - v_c)
//   slip       s = t . (v - v_c - omega e_z x d) = t . (v - v_c) - omega rho
//              (the belt point's velocity relative to the pulley's material point at the same place)
// Normal law: penalty with damping, compression positive, no adhesion,
//   p = max(0, -k g - c gdot) while g < 0, else 0                                  [N/m]
// Friction law (the scene's choice):
//   none                  f_t = 0
//   regularized Coulomb   f_t = -mu p tanh(s / v_s)  (|f_t| -> mu p for |s| >> v_s; "stick" is a
//                         creep |s| < v_s whose force grows with it)
//   creep rate            the tri-linear law of Leamy & Wasfy (ASME J. Appl. Mech. 69, 2002):
//                         f_t = -mu p s / v_s for |s| <= v_s (creep: friction proportional to the
//                         creep rate), -mu p sign(s) beyond (Coulomb sliding)
//   bristle (elastic stick, the return mapping of elastoplasticity applied to the tangential
//   deflection z of the contact point, dz/dt = s, integrated by backward Euler over the time dt
//   since the last accepted step, whose deflection is z_n):
//                         z_trial = z_n + dt s,  f_trial = -k_t z_trial
//                         stick  |f_trial| <= mu p:  f_t = f_trial                (df_t/ds = -k_t dt)
//                         slip   otherwise:          f_t = -mu p sign(z_trial)    (df_t/dp = -mu sign)
//                         and the accepted step's deflection is z = -f_t / k_t (0 off contact).
//                         A sticking point holds |f_t| < mu p with s -> 0: true stick, no creep.
// Force on the belt: f = p n + f_t t. The pulley takes -f, and about its centre the torque
// (d x (-f))_z = -rho f_t.
//
// Tangents, with P = I - n n^T, E = [e_z]x, u = v - v_c, phi = tanh(s / v_s), phi' = (1 - phi^2) / v_s:
//   dn/dd = P / rho,  dt/dd = E P / rho,  dgdot/dd = u^T P / rho,  ds/dd = u^T E P / rho - omega n^T,
//   dp/dd = -k n^T - c u^T P / rho,  dp/du = -c n^T,  ds/du = t^T,  ds/domega = -rho,
//   df/dd = n dp/dd + p P / rho + t df_t/dd + f_t E P / rho,   df_t/dd = f_p dp/dd + f_s ds/dd,
//   df/du = n dp/du + t df_t/du,   df_t/du = f_p dp/du + f_s t^T,   df/domega = -f_s rho t,
// with the law's partials f_p = df_t/dp, f_s = df_t/ds (regularized Coulomb: f_p = -mu phi,
// f_s = -mu p phi'; creep rate: f_p = -mu s / v_s, f_s = -mu p / v_s in creep, f_p = -mu sign(s),
// f_s = 0 sliding).
// d = r - c and u = v - v_c: derivatives in the belt's r and v are those in d and u, in the pulley's
// c and v_c their negatives.
#pragma once
#include <algorithm>
#include <cmath>

#include "strand/math/Dual.hpp"

namespace strand::contact {

enum class FrictionLaw { None, RegularizedCoulomb, CreepRate, Bristle };

struct ContactLaw {
  double stiffness = 0.0;     // k: normal penalty per unit reference length of belt [N/m^2]
  double damping = 0.0;       // c: normal damping [N s/m^2]
  FrictionLaw friction = FrictionLaw::None;
  double mu = 0.0;            // Coulomb coefficient
  double slipVelocity = 1e-3; // v_s: the regularization, the creep law's creep limit [m/s]
  double tangentialStiffness = 0.0;  // k_t: the bristle's stiffness per unit reference length [N/m^2]
  double offset = 0.0;        // the belt's contact surface from its centerline (h/2) [m]
};

// A rigid circular pulley's state: centre, its velocity, angular speed (counterclockwise), radius.
struct PulleyState {
  double c[2] = {0.0, 0.0};
  double vc[2] = {0.0, 0.0};
  double omega = 0.0;
  double radius = 0.0;
};

// The bristle law's history at one point: its deflection at the last accepted step and the time
// since then (null or default: none, e.g. at the first step).
// state: the stick/slip state held fixed while Newton solves a step (the frozen-state iteration of
// docs/contact.md): 0 as the law decides, 1 stick (f_t = f_trial even beyond the cone),
// 2 slip with f_t = +mu p, 3 slip with f_t = -mu p.
struct BristleHistory {
  double z = 0.0;   // z_n [m]
  double dt = 0.0;  // t - t_n [s]
  int state = 0;
};
// The state the law takes for a trial force against the cone mu p (1, 2 or 3 as above).
inline int bristleState(double trial, double limit) { return std::fabs(trial) <= limit ? 1 : (trial > 0.0 ? 2 : 3); }

// What the law found at a point (for output and the tangents).
struct ContactPoint {
  bool touching = false;  // p > 0
  bool closed = false;    // the tangents are those of a closed contact (touching, or at the surface)
  bool sticking = false;  // bristle: inside the friction cone; regularized Coulomb, creep rate: |s| < v_s
  double pressure = 0.0;  // p [N/m]
  double slip = 0.0;      // s [m/s]
  double friction = 0.0;  // f_t [N/m]
  double trial = 0.0;     // bristle: the trial force -k_t (z_n + dt s) [N/m]
};

namespace detail {
// f_t(p, s) of the scene's law.
template <class S>
S frictionForce(const ContactLaw& law, const S& p, const S& s, const BristleHistory* h) {
  using std::tanh;
  using math::tanh;
  switch (law.friction) {
    case FrictionLaw::None: return S(0.0);
    case FrictionLaw::RegularizedCoulomb: return -law.mu * p * tanh(s / law.slipVelocity);
    case FrictionLaw::CreepRate:
      if (std::fabs(math::value(s)) <= law.slipVelocity) return -law.mu * p * s / law.slipVelocity;
      return math::value(s) > 0.0 ? -law.mu * p : law.mu * p;
    case FrictionLaw::Bristle: {
      const BristleHistory none;
      const BristleHistory& hh = h ? *h : none;
      const S trial = -law.tangentialStiffness * (hh.z + hh.dt * s);
      const int state = hh.state ? hh.state : bristleState(math::value(trial), law.mu * math::value(p));
      if (state == 1) return trial;
      return state == 2 ? law.mu * p : -law.mu * p;
    }
  }
  return S(0.0);
}

// f_t and its partials f_p = df_t/dp, f_s = df_t/ds.
struct FrictionTangent {
  double ft = 0.0, fp = 0.0, fs = 0.0;
  bool sticking = false;
  double trial = 0.0;  // bristle: f_trial
};
inline FrictionTangent frictionTangent(const ContactLaw& law, double p, double s, const BristleHistory* h) {
  FrictionTangent out;
  switch (law.friction) {
    case FrictionLaw::None: break;
    case FrictionLaw::RegularizedCoulomb: {
      const double phi = std::tanh(s / law.slipVelocity);
      out = {-law.mu * p * phi, -law.mu * phi, -law.mu * p * (1.0 - phi * phi) / law.slipVelocity,
             std::fabs(s) < law.slipVelocity};
      break;
    }
    case FrictionLaw::CreepRate: {
      const double vs = law.slipVelocity;
      if (std::fabs(s) <= vs) {
        out = {-law.mu * p * s / vs, -law.mu * s / vs, -law.mu * p / vs, true};
      } else {
        const double sign = s > 0.0 ? 1.0 : -1.0;
        out = {-sign * law.mu * p, -sign * law.mu, 0.0, false};
      }
      break;
    }
    case FrictionLaw::Bristle: {
      const BristleHistory none;
      const BristleHistory& hh = h ? *h : none;
      const double trial = -law.tangentialStiffness * (hh.z + hh.dt * s);
      const int state = hh.state && p > 0.0 ? hh.state : bristleState(trial, law.mu * p);
      if (state == 1) {
        out = {trial, 0.0, -law.tangentialStiffness * hh.dt, p > 0.0, trial};
      } else {
        const double sign = state == 2 ? 1.0 : -1.0;
        out = {sign * law.mu * p, sign * law.mu, 0.0, false, trial};
      }
      break;
    }
  }
  return out;
}
}  // namespace detail

// f (2) at a belt point r with velocity v; returns whether the point touches (p > 0). S = double,
// or a dual number for the tests.
// h: the bristle law's history at this point (null: none).
template <class S>
bool pointForce(const ContactLaw& law, const PulleyState& pl, const S* r, const S* v, S* f,
                const BristleHistory* h = nullptr) {
  using std::sqrt;
  using math::sqrt;
  f[0] = f[1] = S(0.0);
  const S d[2] = {r[0] - pl.c[0], r[1] - pl.c[1]};
  const S rho = sqrt(d[0] * d[0] + d[1] * d[1]);
  const S g = rho - (pl.radius + law.offset);
  if (!(math::value(g) < 0.0) || !(math::value(rho) > 0.0)) return false;
  const S n[2] = {d[0] / rho, d[1] / rho}, t[2] = {-n[1], n[0]};
  const S u[2] = {v[0] - pl.vc[0], v[1] - pl.vc[1]};
  const S p = -law.stiffness * g - law.damping * (n[0] * u[0] + n[1] * u[1]);
  if (!(math::value(p) > 0.0)) return false;
  const S s = t[0] * u[0] + t[1] * u[1] - pl.omega * rho;
  const S ft = detail::frictionForce(law, p, s, h);
  for (int i = 0; i < 2; ++i) f[i] = p * n[i] + ft * t[i];
  return true;
}

// f, df/dr and df/dv (2 x 2, row-major; = df/dd and df/du), df/domega (2), and the point's state.
inline ContactPoint pointTangent(const ContactLaw& law, const PulleyState& pl, const double* r, const double* v,
                                 double* f, double* dfdr, double* dfdv, double* dfdomega,
                                 const BristleHistory* h = nullptr) {
  ContactPoint out;
  for (int i = 0; i < 4; ++i) dfdr[i] = dfdv[i] = 0.0;
  f[0] = f[1] = dfdomega[0] = dfdomega[1] = 0.0;
  const double d[2] = {r[0] - pl.c[0], r[1] - pl.c[1]};
  const double rho = std::hypot(d[0], d[1]);
  const double g = rho - (pl.radius + law.offset);
  // The force is zero at g >= 0; its derivative there is taken from the closed side for points
  // within round-off of the surface (|g| <= 1e-10 (R + offset)), so that a belt laid exactly on a
  // pulley starts with the contact's stiffness in the Newton matrix instead of none.
  const double closedBand = 1e-10 * (pl.radius + law.offset);
  if (!(g < closedBand) || !(rho > 0.0)) return out;
  const double n[2] = {d[0] / rho, d[1] / rho}, t[2] = {-n[1], n[0]};
  const double u[2] = {v[0] - pl.vc[0], v[1] - pl.vc[1]};
  const double gdot = n[0] * u[0] + n[1] * u[1];
  const double pTrial = -law.stiffness * g - law.damping * gdot;
  if (!(pTrial > 0.0) && !(g > -closedBand)) return out;  // separating: no force, no stiffness
  const double p = std::max(pTrial, 0.0);
  const double s = t[0] * u[0] + t[1] * u[1] - pl.omega * rho;
  const detail::FrictionTangent fr = detail::frictionTangent(law, p, s, h);
  const double ft = fr.ft;
  out = {p > 0.0, true, p > 0.0 && fr.sticking, p, s, ft, fr.trial};
  for (int i = 0; i < 2; ++i) f[i] = p * n[i] + ft * t[i];

  double P[4], EP[4];  // P = I - n n^T, E P (E = [[0, -1], [1, 0]])
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) P[i * 2 + j] = (i == j ? 1.0 : 0.0) - n[i] * n[j];
  for (int j = 0; j < 2; ++j) {
    EP[0 * 2 + j] = -P[1 * 2 + j];
    EP[1 * 2 + j] = P[0 * 2 + j];
  }
  double dp_dd[2], ds_dd[2], dft_dd[2], dp_du[2], dft_du[2];
  for (int j = 0; j < 2; ++j) {
    const double uP = (u[0] * P[0 * 2 + j] + u[1] * P[1 * 2 + j]) / rho;
    const double uEP = (u[0] * EP[0 * 2 + j] + u[1] * EP[1 * 2 + j]) / rho;
    dp_dd[j] = -law.stiffness * n[j] - law.damping * uP;
    ds_dd[j] = uEP - pl.omega * n[j];
    dft_dd[j] = fr.fp * dp_dd[j] + fr.fs * ds_dd[j];
    dp_du[j] = -law.damping * n[j];
    dft_du[j] = fr.fp * dp_du[j] + fr.fs * t[j];
  }
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      dfdr[i * 2 + j] = n[i] * dp_dd[j] + p * P[i * 2 + j] / rho + t[i] * dft_dd[j] + ft * EP[i * 2 + j] / rho;
      dfdv[i * 2 + j] = n[i] * dp_du[j] + t[i] * dft_du[j];
    }
  for (int i = 0; i < 2; ++i) dfdomega[i] = -fr.fs * rho * t[i];
  return out;
}

// The contact's energy at a point (docs/contact.md, "Energy"): the normal penalty's potential
// phi = k g^2 / 2 (g < 0), and the power of the rest of the force into the belt and a free pulley,
//   P = (p + k g) gdot + f_t s  (+ omega rho f_t on a driven pulley: its drive's input),
// so that the contact's whole power f . v - f . (v_c + omega e_z x d) = p gdot + f_t s = -dphi/dt + P
// (a driven pulley's material point moves on its own: f . v = p gdot + f_t (s + omega rho)).
// P holds the normal damping's -c gdot^2, the friction's work and the drive's: smooth in time,
// where p gdot itself swings with the belt's radial contact mode, which the time step does not
// resolve (the trapezoidal rule made energy out of it).
struct PointEnergy {
  double stored = 0.0;  // phi [J/m]
  double power = 0.0;   // P [W/m]
};
inline PointEnergy pointEnergy(const ContactLaw& law, const PulleyState& pl, const double* r, const double* v,
                               bool driven, const BristleHistory* h = nullptr) {
  PointEnergy out;
  const double d[2] = {r[0] - pl.c[0], r[1] - pl.c[1]};
  const double rho = std::hypot(d[0], d[1]);
  const double g = rho - (pl.radius + law.offset);
  if (!(g < 0.0) || !(rho > 0.0)) return out;
  const double n[2] = {d[0] / rho, d[1] / rho}, t[2] = {-n[1], n[0]};
  const double u[2] = {v[0] - pl.vc[0], v[1] - pl.vc[1]};
  const double gdot = n[0] * u[0] + n[1] * u[1];
  const double p = std::max(-law.stiffness * g - law.damping * gdot, 0.0);
  const double s = t[0] * u[0] + t[1] * u[1] - pl.omega * rho;
  const double ft = p > 0.0 ? detail::frictionTangent(law, p, s, h).ft : 0.0;
  out.stored = 0.5 * law.stiffness * g * g;
  out.power = (p + law.stiffness * g) * gdot + ft * s + (driven ? pl.omega * rho * ft : 0.0);
  return out;
}

}  // namespace strand::contact
