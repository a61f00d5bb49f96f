// The axially moving string of seed 000 sec. 4.1 (Wickert & Mote 1990) as the ALE tests and the
// moving-string study run it: its parameters, its scene, and its first frequency measured from
// the zero crossings of the midpoint's motion (tests/verification/test_ale.cpp,
// tests/benchmarks/study_moving_string.cpp).
#pragma once
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "strand/elements/ElementRegistry.hpp"
#include "strand/solvers/Dynamics.hpp"
#include "strand/solvers/Problem.hpp"
#include "support/Scenes.hpp"

namespace strand::testing {

struct MovingString {
  double l = 1.0, rho = 7800.0, E = 2e11, radius = 1e-3, v = 10.0, f1 = 22.6857;
  double A() const { return M_PI * radius * radius; }
  // the wave speed for f1, the Green strain eps with c^2 = EA eps lambda^2 / rho A (tension
  // EA eps lambda, mass per spatial length rho A / lambda), and the stretch lambda = sqrt(1 + 2 eps)
  double c() const { return l * f1 + std::sqrt(l * f1 * l * f1 + v * v); }
  double eps() const {
    const double k = rho * A() * c() * c() / (E * A());  // eps (1 + 2 eps) = k
    return (-1.0 + std::sqrt(1.0 + 8.0 * k)) / 4.0;
  }
  double lambda() const { return std::sqrt(1.0 + 2.0 * eps()); }
};

inline model::SceneDescription stringScene(const MovingString& s, int elements, double dt, double tEnd,
                                           const char* kind = "AleCable2d") {
  model::SceneDescription sc;
  sc.file = "(test)";
  sc.dimension = elements::kindInfo(elements::findKind(kind)).dim;
  sc.analysis = model::Analysis::Dynamic;
  model::BodyDesc b;
  b.name = "string";
  b.kind = elements::findKind(kind);
  b.elements = elements;
  b.geometry.kind = model::GeometryKind::Line;
  b.geometry.start = {0, 0, 0};
  b.geometry.end = {s.l, 0, 0};
  b.section.numbers = {{"E", s.E}, {"A", s.A()}, {"I", 1e-18}, {"rho", s.rho}};  // EI 2e-7 N m^2: a string
  b.initialStretch = s.lambda();
  b.hasMaterialMotion = true;
  b.materialMotion.kind = model::TimeFunction::Kind::Linear;
  b.materialMotion.rate = -s.v / s.lambda();  // p rises at a node as material leaves towards +x
  sc.bodies.push_back(b);
  pinEnds(sc, "string");
  sc.dynamics.integrator = model::Integrator::Newmark;
  sc.dynamics.dt = dt;
  sc.dynamics.tEnd = tEnd;
  return sc;
}

// The frequency [Hz] of a sampled sinusoid w(t): upward zero crossings by cubic interpolation
// through four samples, counted over the record.
inline double crossingFrequency(const std::vector<double>& times, const std::vector<double>& w) {
  std::vector<double> up;
  for (size_t i = 2; i + 1 < w.size(); ++i)
    if (w[i - 1] < 0.0 && w[i] >= 0.0) {
      double a = times[i - 1], b = times[i];
      auto value = [&](double t) {  // Lagrange cubic through samples i-2 .. i+1
        double sum = 0.0;
        for (int j = -2; j <= 1; ++j) {
          double term = w[i + j];
          for (int m = -2; m <= 1; ++m)
            if (m != j) term *= (t - times[i + m]) / (times[i + j] - times[i + m]);
          sum += term;
        }
        return sum;
      };
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (a + b);
        if (value(mid) < 0.0) a = mid;
        else b = mid;
      }
      up.push_back(0.5 * (a + b));
    }
  if (up.size() < 4) return std::nan("");  // too short a record
  return (up.size() - 1) / (up.back() - up.front());
}

// w, w_x, w_t, w_xt of the initial motion at x (t = 0).
using InitialMotion = std::function<void(double x, double* w, double* wx, double* wt, double* wxt)>;

// The frequency [Hz] of the midpoint's transverse motion of the span `sc` (node positions on a
// straight line along x, `elements` elements), started in the motion `start` (positions w, w_t;
// slopes lambda w_x, lambda w_xt; the material coordinates at their prescribed rate), integrated
// to sc.dynamics.tEnd.
inline double spanFrequency(const model::SceneDescription& sc, int elements, double length, const InitialMotion& start) {
  solvers::Problem p(PETSC_COMM_WORLD, sc);
  Vec X, V;
  PetscCallAbort(PETSC_COMM_WORLD, p.createInitialState(&X, &V));
  const model::Body& body = p.model().bodies()[0];
  const int D = sc.dimension;
  const double lam = sc.bodies[0].initialStretch;
  std::vector<double> u(p.model().numDofs(), 0.0), vel(p.model().numDofs(), 0.0);
  for (int n = 0; n <= elements; ++n) {
    double w, wx, wt, wxt;
    start(n * length / elements, &w, &wx, &wt, &wxt);
    u[body.block(n, 0) * D + 1] = w;
    vel[body.block(n, 0) * D + 1] = wt;
    u[body.block(n, 1) * D + 1] = lam * wx;
    vel[body.block(n, 1) * D + 1] = lam * wxt;
    vel[body.block(n, 2) * D] = sc.bodies[0].materialMotion.rate;
  }
  PetscCallAbort(PETSC_COMM_WORLD, p.assembler().fromModelOrder(u, X));
  PetscCallAbort(PETSC_COMM_WORLD, p.assembler().fromModelOrder(vel, V));
  solvers::Dynamics dyn(p.assembler(), sc.dynamics);
  const int mid = body.block(elements / 2, 0);
  std::vector<double> times, w;
  solvers::Dynamics::StepCallback cb = [&](const solvers::DynamicsStep& st, Vec Xs, Vec) -> PetscErrorCode {
    std::vector<double> q;
    PetscCall(p.assembler().gatherToRoot(Xs, q));
    double y = q.empty() ? 0.0 : q[mid * D + 1];
    MPI_Bcast(&y, 1, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
    times.push_back(st.time);
    w.push_back(y);
    return 0;
  };
  std::string failure;
  PetscCallAbort(PETSC_COMM_WORLD, dyn.run(X, V, cb, &failure));
  VecDestroy(&X);
  VecDestroy(&V);
  if (!failure.empty()) {
    std::fprintf(stderr, "spanFrequency: %s\n", failure.c_str());
    return std::nan("");
  }
  return crossingFrequency(times, w);
}

// The first natural frequency [Hz] of the moving string with `elements` elements, started in its
// exact first mode w = A sin(pi x / l) cos(omega t + beta x), beta = omega v / (c^2 - v^2).
inline double firstFrequency(const MovingString& s, int elements, double stepsPerPeriod = 2000.0,
                             const char* kind = "AleCable2d") {
  const double omega = 2.0 * M_PI * s.f1, period = 1.0 / s.f1;
  const double beta = omega * s.v / (s.c() * s.c() - s.v * s.v), amp = 1e-5 * s.l, k = M_PI / s.l;
  const auto sc = stringScene(s, elements, period / stepsPerPeriod, 5.2 * period, kind);
  return spanFrequency(sc, elements, s.l, [&](double x, double* w, double* wx, double* wt, double* wxt) {
    const double sn = std::sin(k * x), cn = std::cos(k * x), sb = std::sin(beta * x), cb = std::cos(beta * x);
    *w = amp * sn * cb;
    *wt = -amp * omega * sn * sb;
    *wx = amp * (k * cn * cb - beta * sn * sb);
    *wxt = -amp * omega * (k * cn * sb + beta * sn * cb);
  });
}

}  // namespace strand::testing
