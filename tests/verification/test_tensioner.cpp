// A tensioner: a free pulley whose centre slides on a spring-damper with a preload (issue 34;
// docs/contact.md, "Tensioners"; docs/validation.md, "Tensioner").
//
// The loop: a closed frictionless belt (EA = 1e4 N, rho A = 1e-3 kg/m, EI = 1e-5 N m^2) around a
// fixed pulley "a" at the origin and the tensioner "b" at D = 0.4 m on x, both of radius
// R = 0.1 m, laid with the stretch lambda0 = 1.01; b slides along +x with mass m = 1 kg, spring
// k = 1e4 N/m and preload F. Statics of the loop (closed form): both spans carry T, so
//   F - k x = 2 T,   T = EA (lambda^2 - 1) lambda / 2,   lambda = (2 (D + x) + 2 pi rho) / L_ref,
// with L_ref = (2 D + 2 pi R) / lambda0 and rho = R - T lambda / (rho k_c) the radius the belt sinks
// to under the contact penalty k_c (docs/validation.md, "Belt at rest").
//
// requirement: with slide damping the tensioner settles where the closed form puts it: x within
//   1e-3 and the span tension within 1e-4 (160 elements: measured 1.0e-4 and 1e-6);
// requirement: undamped, it oscillates about that point at omega = sqrt(K / m), K = k + 2 dT/dx the
//   loop's slide stiffness (the closed form's derivative): the period within 1e-3 (measured 5e-4;
//   the belt's own mass, about 5e-4 of m, is left out of m); the energy balance (kinetic + strain
//   + spring + contact penalty - the preload's work) closes, from 20 ms on, to 1e-3 of the energy
//   moved (measured 5e-4: rho_inf = 0.8's damping of the belt's high modes);
// requirement: the Newton matrix's couplings of the slide (belt rows x the pulley's columns, its
//   rows x the belt's, its own 2 x 2) equal the residual's central differences, in X and in V, on a
//   turning loop with friction (regularized Coulomb) and a moving slide;
// requirement: in the running two-pulley drive of Pechstein & Gerstmayr (docs/validation.md,
//   "Two-pulley drive") with a tensioner pressing on its slack span, the tensioner holds that span's
//   tension: in the steady state the slide's balance F - k x = T_s (u_1 - u_2) . e (u_1, u_2 the
//   directions of the span arriving at it and leaving it, the tangent lines between the circles
//   the belt's centerline follows) gives T_s within 1 % of the belt's stretch (measured 0.3 %),
//   and the torque balance (T_t - T_s) r = c omega_2 + 25 N m holds within 2e-3 (measured 7e-4);
// requirement: -n 1 and -n 2 give the same (this test runs on both).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "strand/solvers/Dynamics.hpp"
#include "strand/solvers/Problem.hpp"
#include "support/Belts.hpp"
#include "support/DynamicRun.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

constexpr double kDampingOfDrive = 2.0;  // the two-pulley drive's driven pulley [N m s]
constexpr double kR = 0.1, kD = 0.4, kEA = 1e4, kLambda0 = 1.01, kContact = 1e8, kMass = 1.0, kSpring = 1e4;

// The loop with b on its slide (preload F(t) a cosine ramp over [0, ramp], or constant at ramp 0).
model::SceneDescription tensionedLoop(double F, double ramp, double damping, int elements = 80) {
  BeltLoop spec;
  spec.radius = kR;
  spec.distance = kD;
  spec.elements = elements;
  spec.EA = kEA;
  spec.stretch = kLambda0;
  spec.stiffness = kContact;
  model::SceneDescription sc = closedBelt(spec);
  sc.analysis = model::Analysis::Dynamic;
  sc.bodies[0].section.set("rho", 100.0);  // rho A = 1e-3 kg/m
  sc.bodies[0].section.set("I", 1e-14);    // EI = 1e-5 N m^2: the spans' bending boundary layers below 1e-5 of T
  model::PulleyDesc& b = sc.pulleys[1];
  b.inertia = 1e-4;
  b.hasSlide = true;
  b.slide.direction = {1.0, 0.0, 0.0};
  b.slide.mass = kMass;
  b.slide.stiffness = kSpring;
  b.slide.damping = damping;
  b.slide.preload.value = F;
  if (ramp > 0.0) {
    b.slide.preload.kind = model::TimeFunction::Kind::CosineRamp;
    b.slide.preload.start = 0.0;
    b.slide.preload.end = ramp;
  }
  return sc;
}

// The closed form: the span tension at slide displacement x.
double loopTension(double x) {
  const double pi = std::acos(-1.0), reference = (2.0 * kD + 2.0 * pi * kR) / kLambda0;
  double rho = kR, T = 0.0;
  for (int it = 0; it < 60; ++it) {
    const double lambda = (2.0 * (kD + x) + 2.0 * pi * rho) / reference;
    T = cableTension(kEA, lambda);
    rho = kR - T * lambda / (rho * kContact);
  }
  return T;
}

// Where the closed form puts the slide under the preload F (F - k x = 2 T(x), by Newton).
double equilibrium(double F) {
  double x = 0.0;
  for (int it = 0; it < 50; ++it) {
    const double h = 1e-7, g = F - kSpring * x - 2.0 * loopTension(x);
    const double dg = -kSpring - (loopTension(x + h) - loopTension(x - h)) / h;
    x -= g / dg;
  }
  return x;
}

struct SlideRun {
  DynamicRun run;
  std::vector<double> t, x;  // the slide's displacement per step
  double tension = 0.0;      // at the middle of the lower span, at the end
};

SlideRun runLoop(const model::SceneDescription& sc, double dt, double tEnd, double rhoInf) {
  SlideRun r;
  const StepHook slide = [&](solvers::Problem& p, const solvers::DynamicsStep& st, Vec X, Vec V) -> PetscErrorCode {
    std::vector<assembly::Assembler::PulleyLoad> load;
    PetscCall(p.assembler().pulleyLoads(X, V, st.time, load));
    r.t.push_back(st.time);
    r.x.push_back(load[1].slide);
    return 0;
  };
  r.run = runDynamics(sc, dt, tEnd, rhoInf, model::Integrator::GeneralizedAlpha, 2, slide);
  if (r.run.failure.empty()) {
    solvers::Problem p(PETSC_COMM_WORLD, sc);
    r.tension = cableTension(kEA, nodeStretch(p.model().bodies()[0], r.run.q, 0));
  }
  return r;
}

int rank() {
  int r;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}

}  // namespace

TEST(Tensioner, SettlesWhereTheLoopsStaticsPutIt) {
  const double F = 300.0, omega = std::sqrt((kSpring + 2.8e4) / kMass);
  // 160 elements: at 80 the wraps' discretization puts x 2.4e-3 off (the span tension still 3e-4);
  // 160: 1.0e-4 and 1e-6, 320: 5.6e-5 and 3e-6
  const SlideRun r = runLoop(tensionedLoop(F, 0.02, 2.0 * kMass * omega, 160), 2e-4, 0.12, 0.8);
  ASSERT_TRUE(r.run.failure.empty()) << r.run.failure;
  const double x = equilibrium(F), T = loopTension(x);
  if (rank() == 0)
    std::printf("tensioner at rest: x = %.6e m (closed form %.6e), T = %.5f N (%.5f; (F - k x) / 2 = %.5f)\n",
                r.x.back(), x, r.tension, T, 0.5 * (F - kSpring * r.x.back()));
  EXPECT_NEAR(r.x.back() / x, 1.0, 1e-3);
  EXPECT_NEAR(r.tension / T, 1.0, 1e-4);
}

TEST(Tensioner, OscillatesAtTheLoopsSlideFrequencyAndConservesEnergy) {
  const double F = 300.0, pi = std::acos(-1.0);
  const SlideRun r = runLoop(tensionedLoop(F, 4e-3, 0.0), 1e-4, 0.2, 0.8);
  ASSERT_TRUE(r.run.failure.empty()) << r.run.failure;
  const double x0 = equilibrium(F), h = 1e-7;
  const double K = kSpring + (loopTension(x0 + h) - loopTension(x0 - h)) / h;  // k + 2 dT/dx
  const double period = 2.0 * pi * std::sqrt(kMass / K);
  std::vector<double> up;  // upward crossings of x0, interpolated
  for (size_t i = 1; i < r.x.size(); ++i)
    if (r.x[i - 1] < x0 && r.x[i] >= x0) up.push_back(r.t[i - 1] + (x0 - r.x[i - 1]) / (r.x[i] - r.x[i - 1]) * (r.t[i] - r.t[i - 1]));
  ASSERT_GE(up.size(), 4u);
  const double measured = (up.back() - up.front()) / static_cast<double>(up.size() - 1);
  // the balance from 20 ms on: at the start the belt, laid on the pulleys at zero gap with its
  // pretension, sinks into them through a contact mode far beyond 1 / dt (an impact: the scheme's
  // error, 0.065 J in the first step, damped out over about 20 ms)
  double scale = 0.0, drift = 0.0, start = 0.0;
  for (const solvers::DynamicsStep& st : r.run.steps) {
    scale = std::max({scale, st.kinetic, std::abs(st.loadWork)});
    if (st.time <= 0.02 + 1e-9) start = st.energy();
    else drift = std::max(drift, std::abs(st.energy() - start));
  }
  if (rank() == 0)
    std::printf("tensioner undamped: period %.7f s over %zu cycles (sqrt(m / K) closed form %.7f s, K = %.1f N/m); "
                "energy drift %.2e J of %.3f J\n",
                measured, up.size() - 1, period, K, drift, scale);
  EXPECT_NEAR(measured / period, 1.0, 1e-3);
  EXPECT_LT(drift, 1e-3 * scale);
}

// The Newton matrix at a state of a turning loop with friction, the pulley turning and the slide
// moving: K = dR/dX (no shifts) and D = dR/dV against central differences of the residual, column
// by column.
TEST(Tensioner, NewtonMatrixEqualsTheResidualsDifferences) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  model::SceneDescription sc = tensionedLoop(300.0, 0.02, 50.0);
  sc.supports.clear();  // the loop turns with the driver
  sc.pulleys[0].speed.value = 20.0;
  sc.pulleys[1].damping = 1e-3;
  sc.contacts[0].law.friction = contact::FrictionLaw::RegularizedCoulomb;
  sc.contacts[0].law.mu = 0.3;
  sc.contacts[0].law.slipVelocity = 0.05;
  solvers::Problem p(comm, sc);
  Vec X, V;
  PetscCallAbort(comm, p.createInitialState(&X, &V));
  {  // a state off the initial one: displacements of 1e-5 m (the belt presses into the pulleys by
     // up to that), velocities of 0.1 m/s, the slide at 1 mm moving at 0.05 m/s
    PetscInt lo, hi;
    PetscCallAbort(comm, VecGetOwnershipRange(X, &lo, &hi));
    for (PetscInt i = lo; i < hi; ++i) {
      PetscCallAbort(comm, VecSetValue(X, i, 1e-5 * std::sin(1.7 * i), INSERT_VALUES));
      PetscCallAbort(comm, VecSetValue(V, i, 0.1 * std::cos(0.9 * i), INSERT_VALUES));
    }
    const PetscInt slide = p.dofs().globalBlock()[p.model().pulleyBlock(1)] * 2 + 1;
    if (slide >= lo && slide < hi) {
      PetscCallAbort(comm, VecSetValue(X, slide, 1e-3, INSERT_VALUES));
      PetscCallAbort(comm, VecSetValue(V, slide, 0.05, INSERT_VALUES));
      PetscCallAbort(comm, VecSetValue(V, slide - 1, 15.0, INSERT_VALUES));  // the pulley turns
    }
    for (Vec v : {X, V}) {
      PetscCallAbort(comm, VecAssemblyBegin(v));
      PetscCallAbort(comm, VecAssemblyEnd(v));
    }
  }
  assembly::Assembler& a = p.assembler();
  const double t = 0.01;
  Mat K, D;
  PetscCallAbort(comm, p.dofs().createMatrix(&K, "fd_"));
  PetscCallAbort(comm, p.dofs().createMatrix(&D, "fd_"));
  PetscCallAbort(comm, a.dynamicJacobian(X, V, t, 0.0, 0.0, K, D));
  Vec Rp, Rm, col, W;
  PetscCallAbort(comm, VecDuplicate(X, &Rp));
  PetscCallAbort(comm, VecDuplicate(X, &Rm));
  PetscCallAbort(comm, VecDuplicate(X, &col));
  PetscCallAbort(comm, VecDuplicate(X, &W));
  PetscInt n;
  PetscCallAbort(comm, VecGetSize(X, &n));
  const PetscInt pulleyDof = p.dofs().globalBlock()[p.model().pulleyBlock(1)] * 2;
  double worst[2] = {0.0, 0.0}, worstSlide[2] = {0.0, 0.0};
  for (int which = 0; which < 2; ++which) {  // 0: columns in X, 1: in V
    Vec Y = which == 0 ? X : V;
    Mat M = which == 0 ? K : D;
    const double h = which == 0 ? 1e-8 : 1e-6;
    PetscInt lo, hi;
    PetscCallAbort(comm, VecGetOwnershipRange(X, &lo, &hi));
    for (PetscInt j = 0; j < n; ++j) {
      const bool mine = j >= lo && j < hi;  // the owner sets entry j
      PetscCallAbort(comm, VecCopy(Y, W));
      if (mine) PetscCallAbort(comm, VecSetValue(W, j, h, ADD_VALUES));
      PetscCallAbort(comm, VecAssemblyBegin(W));
      PetscCallAbort(comm, VecAssemblyEnd(W));
      PetscCallAbort(comm, a.residual(which == 0 ? W : X, which == 0 ? V : W, t, Rp));
      if (mine) PetscCallAbort(comm, VecSetValue(W, j, -2.0 * h, ADD_VALUES));
      PetscCallAbort(comm, VecAssemblyBegin(W));
      PetscCallAbort(comm, VecAssemblyEnd(W));
      PetscCallAbort(comm, a.residual(which == 0 ? W : X, which == 0 ? V : W, t, Rm));
      PetscCallAbort(comm, VecAXPY(Rp, -1.0, Rm));
      PetscCallAbort(comm, VecScale(Rp, 0.5 / h));  // the difference column
      PetscCallAbort(comm, VecSet(W, 0.0));
      if (mine) PetscCallAbort(comm, VecSetValue(W, j, 1.0, INSERT_VALUES));
      PetscCallAbort(comm, VecAssemblyBegin(W));
      PetscCallAbort(comm, VecAssemblyEnd(W));
      PetscCallAbort(comm, MatMult(M, W, col));
      PetscReal size, err;
      PetscCallAbort(comm, VecNorm(Rp, NORM_INFINITY, &size));
      PetscCallAbort(comm, VecAXPY(col, -1.0, Rp));
      PetscCallAbort(comm, VecNorm(col, NORM_INFINITY, &err));
      const double rel = err / std::max(size, 1.0);
      worst[which] = std::max(worst[which], rel);
      if (j == pulleyDof || j == pulleyDof + 1) worstSlide[which] = std::max(worstSlide[which], rel);
    }
  }
  // every column compared in full covers the pulley's rows too
  if (rank() == 0)
    std::printf("Newton matrix against differences: K %.2e (pulley columns %.2e), D %.2e (%.2e)\n", worst[0],
                worstSlide[0], worst[1], worstSlide[1]);
  EXPECT_LT(worst[0], 1e-5);
  EXPECT_LT(worst[1], 1e-5);
  for (Vec* v : {&Rp, &Rm, &col, &W, &X, &V}) VecDestroy(v);
  MatDestroy(&K);
  MatDestroy(&D);
}

namespace {

// The direction of the line tangent to circles a and b (centres, signed radii s rho: + for a
// counterclockwise wrap) that the belt follows from a to b.
std::array<double, 2> tangentDirection(const double* ca, double sa, const double* cb, double sb) {
  const double d[2] = {cb[0] - ca[0], cb[1] - ca[1]}, D = std::hypot(d[0], d[1]);
  const double phi = std::atan2(d[1], d[0]) - std::asin((sb - sa) / D);
  return {std::cos(phi), std::sin(phi)};
}

}  // namespace

// The two-pulley drive (100 elements, bristle law) with a tensioner t of radius 0.03 m under the
// middle of the slack (lower) span, pushing it 3 cm up into the loop (slide along +y: m = 0.2 kg,
// k = 2000 N/m, c = 40 N s/m) with the preload that balances the pretension at x = 0. The driver
// ramps to 12 rad/s over 0.05 .. 0.3 s, the load torque to 25 N m over 0.3 .. 0.5 s; read at
// 1.5 s (at 1 s the driven pulley still speeds up: the torque balance is 0.7 % off).
// Measured: the slide's balance 3.0e-3 below the stretch's T_s at 100 elements, 4.0e-3 at 200; with
// EI 10 or 100 times smaller 1.8e-3 and 1.7e-3 (the bending boundary layers at the 3 cm pulley move
// the spans off the circles' tangent lines). At 50 elements (26 mm, more than the 12 mm the belt
// wraps the tensioner) Newton fails at 1.09 s.
TEST(Tensioner, HoldsTheSlackSpanTensionOfARunningDrive) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  const double pi = std::acos(-1.0), r = 0.1, offset = 5e-5, Rt = 0.03, push = 0.03, kt = 2000.0;
  model::SceneDescription sc = twoPulleyDrive(100);
  sc.pulleys[0].speed.start = 0.05;
  sc.pulleys[0].speed.end = 0.3;
  sc.pulleys[1].torque.start = 0.3;
  sc.pulleys[1].torque.end = 0.5;
  const double ct[2] = {0.05 * pi, -r + push - (Rt + offset)};
  model::PulleyDesc t;
  t.name = "t";
  t.center = {ct[0], ct[1], 0.0};
  t.radius = Rt;
  t.inertia = 1e-5;
  t.hasSlide = true;
  t.slide.direction = {0.0, 1.0, 0.0};
  t.slide.mass = 0.2;
  t.slide.stiffness = kt;
  t.slide.damping = 40.0;
  // the preload: the pretension T0 = EA (lambda0^2 - 1) lambda0 / 2 on both spans at t
  const double ca[2] = {0.0, 0.0}, cb[2] = {0.1 * pi, 0.0};
  auto pull = [&](double y, double rhoA, double rhoT) {  // (u1 - u2) . e with t's centre at height y
    const double c[2] = {ct[0], y};
    return tangentDirection(ca, rhoA, c, -rhoT)[1] - tangentDirection(c, -rhoT, cb, rhoA)[1];
  };
  const double T0 = cableTension(8000.0, 1.0 / 0.95);
  t.slide.preload.value = T0 * pull(ct[1], r, Rt + offset);
  sc.pulleys.push_back(t);
  model::WrapTurn w;
  w.center = t.center;
  w.radius = Rt + offset;
  w.sense = -1;
  model::BodyDesc& belt = sc.bodies[0];
  belt.geometry.wrap.insert(belt.geometry.wrap.begin() + 1, w);  // a, then t on the lower span, then b
  sc.contacts[0].pulleys.push_back("t");

  const DynamicRun run = runDynamics(sc, 2e-4, 1.5, 0.8);
  ASSERT_TRUE(run.failure.empty()) << run.failure;
  solvers::Problem p(comm, sc);
  const std::vector<double>& q = run.q;
  const int driven = p.model().pulleyBlock(1), tensioner = p.model().pulleyBlock(2);
  const double omega2 = run.v[2 * driven], omegaT = run.v[2 * tensioner];
  // the span tensions at the nodes nearest the middles of the three free spans
  const model::Body& b = p.model().bodies()[0];
  const double x = q[2 * tensioner + 1], y = ct[1] + x;  // the slide (its block starts at 0)
  const double middles[3][2] = {{0.5 * ct[0], -r}, {0.5 * (ct[0] + cb[0]), -r}, {0.5 * cb[0], r}};
  double T[3];
  for (int m = 0; m < 3; ++m) {
    int best = 0;
    double dist = 1e300;
    for (int n = 0; n < b.elements; ++n) {
      const int blk = b.block(n, 0);
      const double dd2 = std::hypot(q[2 * blk] - middles[m][0], q[2 * blk + 1] - middles[m][1]);
      if (dd2 < dist) dist = dd2, best = n;
    }
    T[m] = cableTension(8000.0, nodeStretch(b, q, best));
  }
  const double Ts = 0.5 * (T[0] + T[1]), Tt = T[2];
  // the circles the centerline follows, each sunk by p / k = T / (rho k) under its pressure
  const double rhoA = r - Ts / (r * 1e8), rhoT = Rt + offset - Ts / ((Rt + offset) * 1e8);
  const double predicted = (t.slide.preload.value - kt * x) / pull(y, rhoA, rhoT);
  const double torque = kDampingOfDrive * omega2 + 25.0;
  if (rank() == 0)
    std::printf("running drive with a tensioner: x = %.3e m, slack spans %.3f / %.3f N, tight %.3f N; the slide's "
                "balance gives %.3f N (%.2e); (T_t - T_s) r = %.4f N m, c omega2 + 25 = %.4f N m; driven %.4f, "
                "tensioner %.4f rad/s\n",
                x, T[0], T[1], Tt, predicted, Ts / predicted - 1.0, (Tt - Ts) * r, torque, omega2, omegaT);
  EXPECT_NEAR(Ts / predicted, 1.0, 1e-2);
  EXPECT_NEAR((Tt - Ts) * r / torque, 1.0, 2e-3);
}
