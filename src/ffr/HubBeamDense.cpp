// The small-system path of HubBeamDynamics (HubBeamDynamics.hpp): every fixed-step scheme of the
// PETSc TS path as a plain loop on Eigen matrices, with the same start, the same Newton tolerances
// (at least one Newton step) and the same answers to solver tolerance. Measured
// (tests/benchmarks/bench_hub_beam.cpp, docs/performance.md): PETSc's TS, SNES, KSP and Mat layers
// make a step several times dearer at a few unknowns and about as dear at a hundred.
#include <cmath>
#include <sstream>
#include <vector>

#include "strand/ffr/HubBeamDynamics.hpp"
#include "strand/math/Lagrange.hpp"
#include "strand/solvers/Schemes.hpp"

namespace strand::ffr {

namespace {

// Newton on G(x) = 0 with the TS path's SNES settings: converged when |G| <= atol or |G| <= 1e-10
// |G(x0)|, at least one step, at most 25. Returns the iterations; *converged and *norm report.
template <class Residual, class Jacobian>
int newton(Eigen::VectorXd& x, Residual&& residual, Jacobian&& jacobian, double atol, bool* converged, double* norm) {
  Eigen::VectorXd G;
  Eigen::MatrixXd J;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  residual(x, G);
  const double g0 = G.norm();
  *converged = false;
  int its = 0;
  while (its < 25 && !*converged) {
    jacobian(x, J);
    lu.compute(J);
    x -= lu.solve(G);
    ++its;
    residual(x, G);
    *norm = G.norm();
    if (!std::isfinite(*norm)) break;
    *converged = *norm <= atol || *norm <= 1e-10 * g0;
  }
  return its;
}

// The TS's step sequence (PETSc 3.18, TSAdaptChoose with TS_EXACTFINALTIME_MATCHSTEP and a fixed
// step h): the step that would pass t_end is cut to land on it, and a remainder between 1.01 h and
// 2 h is split into two equal steps, so no step is tiny.
double nextStep(double t, double h, double tEnd) {
  const double rest = tEnd - t;
  if (t + h > tEnd) return rest;
  if (t + h < tEnd && 1.01 * h > rest) return rest;
  if (t + h < tEnd && 2.0 * h > rest) return 0.5 * rest;
  return h;
}

}  // namespace

PetscErrorCode HubBeamDynamics::runDense() {
  PetscFunctionBeginUser;
  if (_explicit) PetscCall(runDenseExplicit());
  else if (_firstOrder) PetscCall(runDenseBdf());
  else PetscCall(runDenseAlpha());
  PetscFunctionReturn(0);
}

double HubBeamDynamics::newtonTolerance() const {
  // a residual of the size the stiffness gives a displacement error of 1e-13 L is converged
  return 1e-13 * _model.matrices().K.lpNorm<Eigen::Infinity>() * _model.desc().length;
}

Eigen::VectorXd HubBeamDynamics::initialRate() const {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(_n);
  if (!_model.driven()) v[0] = _model.desc().initialRate;
  return v;
}

// The generalized-alpha step of our TS (GeneralizedAlpha.hpp, Arnold & Bruls 2007 Eq. 9-11; same
// predictor q + h v + h^2/2 A).
PetscErrorCode HubBeamDynamics::runDenseAlpha() {
  PetscFunctionBeginUser;
  const solvers::AlphaParams& p = _params;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(_n), v = initialRate(), A;
  acceleration(0.0, q, v, A);
  Eigen::VectorXd a = A;
  record(0, 0.0, q, v, 0, 0, &A);
  double t = 0.0, h = 0.0;
  for (int step = 1; t < _desc.tEnd * (1 - 1e-12); ++step) {
    h = step == 1 ? std::min(_desc.dt, _desc.tEnd) : nextStep(t, h, _desc.tEnd);
    const double t1 = t + h;
    const double sV = p.gamma / (p.beta * h), sA = (1 - p.alphaM) / ((1 - p.alphaF) * p.beta * h * h);
    Eigen::VectorXd a1, v1, A1;
    auto update = [&](const Eigen::VectorXd& q1) {
      a1 = (q1 - q - h * v - h * h * (0.5 - p.beta) * a) / (p.beta * h * h);
      v1 = v + h * ((1 - p.gamma) * a + p.gamma * a1);
      A1 = ((1 - p.alphaM) * a1 + p.alphaM * a - p.alphaF * A) / (1 - p.alphaF);
    };
    Eigen::VectorXd q1 = q + h * v + 0.5 * h * h * A;
    bool converged;
    double norm = 0.0;
    const int its = newton(
        q1,
        [&](const Eigen::VectorXd& x, Eigen::VectorXd& F) {
          update(x);
          _model.residual(t1, x, v1, A1, F);
        },
        [&](const Eigen::VectorXd& x, Eigen::MatrixXd& J) {
          update(x);
          _model.jacobian(t1, x, v1, A1, sV, sA, J);
        },
        newtonTolerance(), &converged, &norm);
    if (!converged) {
      _stop = newtonFailure(t1, step, its, norm);
      break;
    }
    update(q1);
    q = q1, v = v1, a = a1, A = A1, t = t1;
    record(step, t, q, v, its, 0, &A);
    _stop = divergence(t, step, q.allFinite() && v.allFinite(), _last.obs);  // recorded just above
    if (!_stop.empty()) break;
    if (stopRequested()) {  // a batch job's stop signal: end after this step
      _stopped = true;
      break;
    }
  }
  PetscFunctionReturn(0);
}

// TSBDF's fixed-step scheme on y = (q, v) and F(y, y') = (q' - v, F(t, q, v, v')) (iFunction):
// y' at t_{n+1} is the derivative of the Lagrange polynomial through y_{n+1} and the last k states;
// TSBDF starts with a backward-Euler half step and raises the order by one per step up to k, and
// keeps the half-step state in its history; the predictor extrapolates the history.
PetscErrorCode HubBeamDynamics::runDenseBdf() {
  PetscFunctionBeginUser;
  const int n = _n, order = _desc.bdfOrder;
  Eigen::VectorXd y0(2 * n);
  y0 << Eigen::VectorXd::Zero(n), initialRate();
  Eigen::VectorXd a0;
  acceleration(0.0, y0.head(n), y0.tail(n), a0);
  record(0, 0.0, y0.head(n), y0.tail(n), 0, 0, &a0);
  std::vector<double> times{0.0};  // most recent first
  std::vector<Eigen::VectorXd> states{y0};
  const double atol = newtonTolerance();
  // One BDF step to t1 on the nodes t1, times[0..k-1], from the prediction y: Newton on
  // G(y) = (q' - v, F(t, q, v, v')) with y' = s y + V0, the TS's 2n x 2n system [s I, -I; D_q, D_va]
  // (D_q = dF/dq, D_va = dF/dv + s dF/da) solved by its Schur complement, one n x n factorization:
  //   (D_q + s D_va) dq = -F - D_va G1,   dv = s dq + G1.
  // After the first iteration G1 = 0 (linear), and D_q + s D_va = jacobian(s, s^2) alone. The same
  // iterates as the TS (an n x n reduced Newton from v = s q + V0 instead starts farther out: 40x
  // looser solves and 8e-9 m of tip drift in 1000 BDF1 steps of a free hub, measured).
  auto solve = [&](double t1, int k, Eigen::VectorXd& y, Eigen::VectorXd& ydot, bool* converged) {
    std::vector<double> T{t1};
    for (int j = 0; j < k && j < static_cast<int>(times.size()); ++j) T.push_back(times[j]);
    const std::vector<double> c = math::lagrangeDerivativeAtFirst(T);
    Eigen::VectorXd V0 = Eigen::VectorXd::Zero(2 * n);
    for (size_t j = 1; j < T.size(); ++j) V0 += c[j] * states[j - 1];
    const double s = c[0];
    Eigen::VectorXd q = y.head(n), v = y.tail(n), a, G1, F;
    Eigen::MatrixXd Jq, Jva, J;
    Eigen::PartialPivLU<Eigen::MatrixXd> lu;
    auto residual = [&] {
      a = s * v + V0.tail(n);
      G1 = s * q + V0.head(n) - v;
      _model.residual(t1, q, v, a, F);
      return std::sqrt(G1.squaredNorm() + F.squaredNorm());
    };
    const double g0 = residual();
    double norm = g0;
    *converged = false;
    int its = 0;
    while (its < 25 && !*converged) {
      Eigen::VectorXd rhs = -F;
      if (its == 0) {
        _model.jacobian(t1, q, v, a, 0.0, 0.0, Jq);
        _model.jacobian(t1, q, v, a, 1.0, s, Jva);
        Jva -= Jq;
        rhs -= Jva * G1;
        J = Jq + s * Jva;
      } else {
        _model.jacobian(t1, q, v, a, s, s * s, J);
      }
      lu.compute(J);
      const Eigen::VectorXd dq = lu.solve(rhs);
      q += dq;
      v += s * dq + G1;
      ++its;
      norm = residual();
      if (!std::isfinite(norm)) break;
      *converged = norm <= atol || norm <= 1e-10 * g0;
    }
    y << q, v;
    ydot << s * q + V0.head(n), a;
    return std::make_pair(its, norm);
  };
  double t = 0.0, h = 0.0;
  int k = 1;
  for (int step = 1; t < _desc.tEnd * (1 - 1e-12); ++step) {
    h = step == 1 ? std::min(_desc.dt, _desc.tEnd) : nextStep(t, h, _desc.tEnd);
    const double t1 = t + h;
    int its = 0;
    bool converged = true;
    Eigen::VectorXd y(2 * n), ydot(2 * n);
    std::pair<int, double> r{0, 0.0};
    if (step == 1 && order > 1) {  // TSBDF_Restart: backward Euler to t + h/2, kept as a history point
      y = states[0];
      r = solve(t + 0.5 * h, 1, y, ydot, &converged);
      its += r.first;
      if (!converged) {
        _stop = newtonFailure(t + 0.5 * h, step, its, r.second);
        break;
      }
      times.push_back(t + 0.5 * h);
      states.push_back(y);
      k = 2;
    } else if (step > 1) {
      k = std::min(k + 1, order);
    }
    {  // predictor: the polynomial through the last min(k + 1, history) states, at t1
      const int m = std::min<int>(k + 1, static_cast<int>(times.size()));
      const std::vector<double> T(times.begin(), times.begin() + m);
      const std::vector<double> c = math::lagrangeValues(T, t1);
      y = Eigen::VectorXd::Zero(2 * n);
      for (int j = 0; j < m; ++j) y += c[j] * states[j];
    }
    r = solve(t1, k, y, ydot, &converged);
    its += r.first;
    if (!converged) {
      _stop = newtonFailure(t1, step, its, r.second);
      break;
    }
    times.insert(times.begin(), t1);
    states.insert(states.begin(), y);
    if (times.size() > 7) times.pop_back(), states.pop_back();
    t = t1;
    const Eigen::VectorXd a = ydot.tail(n);
    record(step, t, y.head(n), y.tail(n), its, 0, &a);
    _stop = divergence(t, step, y.allFinite(), _last.obs);  // recorded just above
    if (!_stop.empty()) break;
    if (stopRequested()) {  // a batch job's stop signal: end after this step
      _stopped = true;
      break;
    }
  }
  PetscFunctionReturn(0);
}

// RK4 and Adams-Bashforth-Moulton 4 (PECE) on y' = f(t, y) = (v, M(q)^{-1} Q(t, q, v)), as the TS
// types TSRK4 and strand_abm4 (solvers/AdamsBashforthMoulton.hpp: RK4 for the first three steps and
// after a change of h, Adams-Bashforth predictor, Adams-Moulton corrector, f evaluated at both).
PetscErrorCode HubBeamDynamics::runDenseExplicit() {
  PetscFunctionBeginUser;
  const int n = _n;
  const bool abm = _desc.integrator == model::Integrator::Abm4;
  auto f = [&](double t, const Eigen::VectorXd& y) {
    Eigen::VectorXd a, r(2 * n);
    acceleration(t, y.head(n), y.tail(n), a);
    r << y.tail(n), a;
    return r;
  };
  Eigen::VectorXd y(2 * n);
  y << Eigen::VectorXd::Zero(n), initialRate();
  std::vector<Eigen::VectorXd> hist;  // f_n, f_{n-1}, ... (ABM4)
  double hHist = 0.0, t = 0.0, h = 0.0;
  Eigen::VectorXd fn = f(0.0, y);
  Eigen::VectorXd an = fn.tail(n);
  record(0, 0.0, y.head(n), y.tail(n), 0, 0, &an);
  for (int step = 1; t < _desc.tEnd * (1 - 1e-12); ++step) {
    h = step == 1 ? std::min(_desc.dt, _desc.tEnd) : nextStep(t, h, _desc.tEnd);
    const double t1 = t + h;
    if (h != hHist) hist.assign(1, fn), hHist = h;
    if (!abm || hist.size() < 4) {
      const Eigen::VectorXd k1 = fn, k2 = f(t + 0.5 * h, y + 0.5 * h * k1), k3 = f(t + 0.5 * h, y + 0.5 * h * k2),
                            k4 = f(t1, y + h * k3);
      y += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    } else {
      const Eigen::VectorXd yp = y + h / 24.0 * (55.0 * hist[0] - 59.0 * hist[1] + 37.0 * hist[2] - 9.0 * hist[3]);
      const Eigen::VectorXd fp = f(t1, yp);
      y += h / 24.0 * (9.0 * fp + 19.0 * hist[0] - 5.0 * hist[1] + hist[2]);
    }
    t = t1;
    fn = f(t, y);
    hist.insert(hist.begin(), fn);
    if (hist.size() > 4) hist.pop_back();
    an = fn.tail(n);
    record(step, t, y.head(n), y.tail(n), 0, 0, &an);
    _stop = divergence(t, step, y.allFinite(), _last.obs);  // recorded just above
    if (!_stop.empty()) break;
    if (stopRequested()) {  // a batch job's stop signal: end after this step
      _stopped = true;
      break;
    }
  }
  PetscFunctionReturn(0);
}

std::string HubBeamDynamics::newtonFailure(double t, int step, int its, double norm) const {
  std::ostringstream m;
  m.precision(6);
  m << _schemeName << ": Newton failed at t = " << t << " s (step " << step << ", " << its << " iterations, |F| ";
  m.precision(3);
  m << norm << "). " << solvers::stabilityNote(_desc) << "Try a smaller dt";
  return m.str();
}

}  // namespace strand::ffr
