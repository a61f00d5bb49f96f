// Step cuts of the generalized-alpha TS (GeneralizedAlphaSetStepCuts, docs/user-guide.md, "Newton
// start"): a step whose Newton fails after every retry is halved and tried again, at most
// maxCuts times in a row, and the steps after it double back to the nominal one.
//
// The problem: the undamped oscillator x'' + w^2 x = 0, x(0) = 1, v(0) = 0 (exact: cos w t), whose
// residual reports a domain error (Newton fails) for any step longer than kHardFraction dt that ends
// inside a window [kHardFrom, kHardTo]. Steps of dt / 4 pass there: two cuts are needed.
//
// requirement: without cuts the run stops at the window; with one cut too; with two it runs through,
//   the steps ending inside the window are dt / 4, each step is at most twice the last (back to
//   dt by doubling, dt / 4, dt / 2, dt), dt again after the window, the run ends at t_end, and x(t_end) keeps the
//   accuracy of the nominal step: below twice the error of the same run without the window
//   (measured 5.7e-6 against 3.4e-6: a change of step costs generalized-alpha a little, its
//   acceleration-like variable a assumes a constant one);
// requirement: a cut near t_end still ends at t_end;
// requirement: GeneralizedAlphaGetStepCuts reports the cuts in force (the next step is
//   nominal / 2^cuts) and ResumeStepCuts puts them back with that next step.
#include <gtest/gtest.h>
#include <petscts.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "strand/solvers/GeneralizedAlpha.hpp"

using namespace strand::solvers;

namespace {

constexpr double kOmega = 2.0 * 3.141592653589793, kDt = 0.01, kEnd = 1.0;
constexpr double kHardFrom = 0.3, kHardTo = 0.34, kHardFraction = 0.3;

struct Oscillator {
  bool hard = true;  // the window where long steps fail
};

PetscErrorCode residual(TS ts, PetscReal t, Vec X, Vec, Vec A, Vec F, void* ctx) {
  PetscFunctionBeginUser;
  const auto* o = static_cast<const Oscillator*>(ctx);
  PetscReal h;
  PetscCall(TSGetTimeStep(ts, &h));
  if (o->hard && t >= kHardFrom && t <= kHardTo && h > kHardFraction * kDt) {
    SNES snes;
    PetscCall(TSGetSNES(ts, &snes));
    PetscCall(SNESSetFunctionDomainError(snes));
  }
  PetscCall(VecWAXPY(F, kOmega * kOmega, X, A));  // F = A + w^2 X
  PetscFunctionReturn(0);
}

PetscErrorCode jacobian(TS, PetscReal, Vec, Vec, Vec, PetscReal, PetscReal shiftA, Mat J, Mat, void*) {
  PetscFunctionBeginUser;
  PetscCall(MatZeroEntries(J));
  PetscCall(MatShift(J, shiftA + kOmega * kOmega));
  PetscFunctionReturn(0);
}

struct Trajectory {
  TSConvergedReason reason = TS_CONVERGED_ITERATING;
  double t = 0.0, x = 0.0;
  std::vector<double> steps;  // accepted steps' lengths
  std::vector<int> cuts;      // cuts in force after each accepted step
};

PetscErrorCode record(TS ts, PetscInt, PetscReal t, Vec, void* ctx) {
  PetscFunctionBeginUser;
  auto* r = static_cast<Trajectory*>(ctx);
  if (t > 0.0) {
    r->steps.push_back(t - r->t);
    PetscInt cuts;
    PetscReal nominal;
    PetscCall(GeneralizedAlphaGetStepCuts(ts, &cuts, &nominal));
    r->cuts.push_back(static_cast<int>(cuts));
  }
  r->t = t;
  PetscFunctionReturn(0);
}

Trajectory integrate(bool hard, int maxCuts, double tEnd = kEnd) {
  MPI_Comm comm = PETSC_COMM_SELF;
  Oscillator o{hard};
  Trajectory r;
  TS ts;
  Vec X, V, A;
  Mat J;
  PetscCallAbort(comm, GeneralizedAlphaRegister());
  PetscCallAbort(comm, VecCreateSeq(comm, 1, &X));
  PetscCallAbort(comm, VecDuplicate(X, &V));
  PetscCallAbort(comm, VecDuplicate(X, &A));
  PetscCallAbort(comm, VecSet(X, 1.0));
  PetscCallAbort(comm, VecSet(V, 0.0));
  PetscCallAbort(comm, VecSet(A, -kOmega * kOmega));  // the consistent start
  PetscCallAbort(comm, MatCreateSeqDense(comm, 1, 1, nullptr, &J));
  PetscCallAbort(comm, TSCreate(comm, &ts));
  PetscCallAbort(comm, TSSetType(ts, kTsGeneralizedAlpha));
  PetscCallAbort(comm, GeneralizedAlphaSetRadius(ts, 0.8));
  PetscCallAbort(comm, GeneralizedAlphaSetStepCuts(ts, maxCuts));
  PetscCallAbort(comm, TSSetI2Function(ts, nullptr, residual, &o));
  PetscCallAbort(comm, TSSetI2Jacobian(ts, J, J, jacobian, nullptr));
  PetscCallAbort(comm, TSSetTimeStep(ts, kDt));
  PetscCallAbort(comm, TSSetMaxTime(ts, tEnd));
  PetscCallAbort(comm, TSSetMaxSteps(ts, 100000));
  PetscCallAbort(comm, TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCallAbort(comm, TSSetMaxSNESFailures(ts, 1));
  PetscCallAbort(comm, TSSetErrorIfStepFails(ts, PETSC_FALSE));
  PetscCallAbort(comm, TSMonitorSet(ts, record, &r, nullptr));
  PetscCallAbort(comm, TS2SetSolution(ts, X, V));
  PetscCallAbort(comm, GeneralizedAlphaSetAcceleration(ts, A));
  PetscCallAbort(comm, TSSolve(ts, nullptr));
  PetscCallAbort(comm, TSGetConvergedReason(ts, &r.reason));
  Vec sol;
  PetscCallAbort(comm, TSGetSolution(ts, &sol));
  const PetscScalar* x;
  PetscCallAbort(comm, VecGetArrayRead(sol, &x));
  r.x = x[0];
  PetscCallAbort(comm, VecRestoreArrayRead(sol, &x));
  TSDestroy(&ts);
  MatDestroy(&J);
  VecDestroy(&X);
  VecDestroy(&V);
  VecDestroy(&A);
  return r;
}

}  // namespace

TEST(StepCuts, AFailedNewtonHalvesTheStepAndTheNextStepsDoubleBack) {
  const Trajectory easy = integrate(false, 0);
  ASSERT_GT(easy.reason, 0);
  const double reference = std::abs(easy.x - std::cos(kOmega * kEnd));
  std::printf("without the hard window: x(1) error %.3e in %zu steps\n", reference, easy.steps.size());

  for (int maxCuts : {0, 1}) {  // not enough cuts: the run stops inside the window
    const Trajectory r = integrate(true, maxCuts);
    EXPECT_LT(r.reason, 0) << maxCuts;
    EXPECT_GE(r.t, kHardFrom - kDt);
    EXPECT_LT(r.t, kHardTo);
  }

  const Trajectory r = integrate(true, 2);
  ASSERT_GT(r.reason, 0);
  EXPECT_NEAR(r.t, kEnd, 1e-12);
  const double error = std::abs(r.x - std::cos(kOmega * kEnd));
  std::printf("with it and 2 cuts: x(1) error %.3e in %zu steps\n", error, r.steps.size());
  EXPECT_LT(error, 2.0 * reference);
  // the steps: dt until a step would end in the window; those that end in it dt / 4 (dt and dt / 2
  // fail there); each step at most twice the last (back to dt by doubling); dt again from two
  // nominal steps after the window; the last one lands on t_end
  double t = 0.0, shortest = kDt;
  for (size_t i = 0; i + 1 < r.steps.size(); ++i) {
    const double h = r.steps[i];
    t += h;
    shortest = std::min(shortest, h);
    if (t < kHardFrom - kDt || t > kHardTo + 2.0 * kDt) {
      EXPECT_NEAR(h, kDt, 1e-12) << "step " << i << " to t = " << t;
    }
    if (t > kHardFrom + 1e-12 && t < kHardTo - 1e-12) {
      EXPECT_NEAR(h, 0.25 * kDt, 1e-12) << "step " << i;
    }
    if (i > 0) {
      EXPECT_LE(h, 2.0 * r.steps[i - 1] + 1e-12) << "step " << i;
    }
  }
  EXPECT_NEAR(shortest, 0.25 * kDt, 1e-12);
}

// requirement: a cut just before t_end does not carry the run past it: the doubled step is cut to
// land on t_end (t_end = 0.345 s, 5 ms after the window).
TEST(StepCuts, TheStepsAfterACutLandOnTheFinalTime) {
  const Trajectory r = integrate(true, 2, 0.345);
  ASSERT_GT(r.reason, 0);
  EXPECT_NEAR(r.t, 0.345, 1e-14);
}

TEST(StepCuts, ResumeRestoresTheCutsAndTheNextStep) {
  MPI_Comm comm = PETSC_COMM_SELF;
  TS ts;
  PetscCallAbort(comm, GeneralizedAlphaRegister());
  PetscCallAbort(comm, TSCreate(comm, &ts));
  PetscCallAbort(comm, TSSetType(ts, kTsGeneralizedAlpha));
  PetscCallAbort(comm, TSSetTimeStep(ts, kDt));
  PetscCallAbort(comm, GeneralizedAlphaResumeStepCuts(ts, 2, kDt));
  PetscInt cuts;
  PetscReal nominal, h;
  PetscCallAbort(comm, GeneralizedAlphaGetStepCuts(ts, &cuts, &nominal));
  PetscCallAbort(comm, TSGetTimeStep(ts, &h));
  EXPECT_EQ(cuts, 2);
  EXPECT_DOUBLE_EQ(nominal, kDt);
  EXPECT_DOUBLE_EQ(h, 0.25 * kDt);
  TSDestroy(&ts);
}
