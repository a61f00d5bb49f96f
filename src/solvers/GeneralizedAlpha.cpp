// The "strand_alpha" TS: generalized-alpha for second-order systems in the form of Arnold & Bruls
// (GeneralizedAlpha.hpp).
// Uses PETSc's private TS header the way PETSc's own implementations do (ts->ops, ts->data).
#include "strand/solvers/GeneralizedAlpha.hpp"

#include <petsc/private/tsimpl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace strand::solvers {

namespace {

// The Newton starts by number (AlphaData::predictor): the option's values and the names reported.
const char* const kPredictorNames[] = {"displacement", "velocity", "acceleration"};

struct AlphaData {
  PetscReal alphaM = 0.0, alphaF = 0.0, gamma = 0.5, beta = 0.25;  // Newmark until set
  PetscReal stageTime = 0.0, shiftV = 0.0, shiftA = 0.0;
  Vec X0 = nullptr, V0 = nullptr, A0 = nullptr, a0 = nullptr;  // start of the step
  Vec V1 = nullptr, A1 = nullptr, a1 = nullptr;                // end of the step (X1 is the SNES iterate)
  Vec A = nullptr, a = nullptr;  // state at ts->ptime: acceleration and acceleration-like variable
  bool inStep = false;           // within step(): the state at ts->ptime is in A0, a0
  PrescribeFn prescribe = nullptr;
  void* prescribeCtx = nullptr;
  Vec startOffset = nullptr;   // added to V0 in the next step only (perturbed starting values)
  Vec differential = nullptr;  // 0 on algebraic entries (multipliers), 1 elsewhere; null: none
  int predictor = 2;           // X1 = X0 (0), + h V0 (1), + h^2/2 A0 (2)
  Vec offset = nullptr;        // X0 + h V0 + h^2/2 A0 minus the predictor used (when not that one)
  bool checkPredictor = true;  // at the first step of a start: weigh the predictor against X0
  int preferred = -1;          // after a fall-back to X0: the predictor to try again (-1: none)
  int recheckIn = 0;           // ... in this many steps
  int recheckEvery = 16;       // ... doubled after each Newton failure from it (at most 1024)
  bool predictorCheck = true;  // -ts_strand_alpha_predictor_check
  PetscReal coordinateNorm = 0.0;  // |q0| when X holds displacements from q0 (round-off scale)
  RetryFn retry = nullptr;
  void* retryCtx = nullptr;
  SettleFn settle = nullptr;
  void* settleCtx = nullptr;
  int maxCuts = 0;             // GeneralizedAlphaSetStepCuts: halvings of the step a failed Newton may take
  int cuts = 0;                // the step is nominal / 2^cuts
  PetscReal nominal = 0.0;     // the step before the first cut
};

AlphaData* dataOf(TS ts) { return static_cast<AlphaData*>(ts->data); }

constexpr int kSettleRounds = 6;  // rounds of held states before the law decides within Newton

// *to = a copy of from, created on first use
PetscErrorCode copyInto(Vec from, Vec* to) {
  PetscFunctionBeginUser;
  if (!*to) PetscCall(VecDuplicate(from, to));
  PetscCall(VecCopy(from, *to));
  PetscFunctionReturn(0);
}

PetscErrorCode checkType(TS ts) {
  PetscBool match;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(ts), kTsGeneralizedAlpha, &match));
  PetscCheck(match, PetscObjectComm(reinterpret_cast<PetscObject>(ts)), PETSC_ERR_ARG_WRONG,
             "TS is not of type %s", kTsGeneralizedAlpha);
  PetscFunctionReturn(0);
}

struct StageCoefficients {
  PetscReal s, h, ca, g, am, af, cA;
};

// The loop of stageVectors; restrict (distinct vectors) lets the compiler vectorize it.
void stageLoop(PetscInt n, StageCoefficients c, const PetscScalar* PETSC_RESTRICT X, const PetscScalar* PETSC_RESTRICT Xn,
               const PetscScalar* PETSC_RESTRICT Vn, const PetscScalar* PETSC_RESTRICT an,
               const PetscScalar* PETSC_RESTRICT An, PetscScalar* PETSC_RESTRICT a, PetscScalar* PETSC_RESTRICT V,
               PetscScalar* PETSC_RESTRICT A) {
  for (PetscInt i = 0; i < n; ++i) {
    a[i] = c.s * (X[i] - Xn[i] - c.h * Vn[i]) - c.ca * an[i];
    V[i] = Vn[i] + c.h * ((1.0 - c.g) * an[i] + c.g * a[i]);
    A[i] = c.cA * ((1.0 - c.am) * a[i] + c.am * an[i] - c.af * An[i]);
  }
}

// Arnold & Bruls (2007) Eqs. 9-11: from X1, the acceleration-like a1, the velocity V1 and the
// acceleration A1 at t_{n+1} (V1, A1 exact on prescribed entries, GeneralizedAlpha.hpp):
//   a1 = (X1 - X0 - h V0 - h^2 (1/2 - beta) a0) / (beta h^2),   V1 = V0 + h ((1 - gamma) a0 + gamma a1),
//   (1 - alpha_m) a1 + alpha_m a0 = (1 - alpha_f) A1 + alpha_f A0.
// One loop over the entries: it reads five vectors and writes three once, where a chain of PETSc
// vector operations made six passes (memory-bound; docs/performance.md, "10^5 elements on two ranks").
PetscErrorCode stageVectors(TS ts, Vec X1) {
  AlphaData* d = dataOf(ts);
  const PetscReal h = ts->time_step, b = d->beta, g = d->gamma, am = d->alphaM, af = d->alphaF;
  const PetscReal s = 1.0 / (b * h * h), ca = (0.5 - b) / b, cA = 1.0 / (1.0 - af);  // alpha_f < 1 (setUp)
  const std::array<Vec, 5> in{X1, d->X0, d->V0, d->a0, d->A0};
  const std::array<Vec, 3> out{d->a1, d->V1, d->A1};
  std::array<const PetscScalar*, 5> r;
  std::array<PetscScalar*, 3> w;
  PetscInt n;
  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(X1, &n));
  for (size_t k = 0; k < in.size(); ++k) PetscCall(VecGetArrayRead(in[k], &r[k]));
  for (size_t k = 0; k < out.size(); ++k) PetscCall(VecGetArrayWrite(out[k], &w[k]));
  stageLoop(n, {s, h, ca, g, am, af, cA}, r[0], r[1], r[2], r[3], r[4], w[0], w[1], w[2]);
  PetscCall(PetscLogFlops(17.0 * n));
  for (size_t k = 0; k < out.size(); ++k) PetscCall(VecRestoreArrayWrite(out[k], &w[k]));
  for (size_t k = 0; k < in.size(); ++k) PetscCall(VecRestoreArrayRead(in[k], &r[k]));
  if (d->prescribe) PetscCall(d->prescribe(d->stageTime, nullptr, d->V1, d->A1, d->prescribeCtx));  // exact rates
  PetscFunctionReturn(0);
}

PetscErrorCode snesFunction(SNES, Vec X1, Vec F, TS ts) {
  AlphaData* d = dataOf(ts);
  PetscFunctionBeginUser;
  PetscCall(stageVectors(ts, X1));
  PetscCall(TSComputeI2Function(ts, d->stageTime, X1, d->V1, d->A1, F));
  PetscFunctionReturn(0);
}

PetscErrorCode snesJacobian(SNES, Vec, Mat J, Mat P, TS ts) {
  AlphaData* d = dataOf(ts);
  PetscFunctionBeginUser;
  PetscCall(TSComputeI2Jacobian(ts, d->stageTime, ts->vec_sol, d->V1, d->A1, d->shiftV, d->shiftA, J, P));
  PetscFunctionReturn(0);
}

// X, holding X0, becomes the Newton start `which`: X0 (0), + h V0 (1), + h^2/2 A0 (2), with the
// prescribed entries at t_{n+1}.
PetscErrorCode addPredictor(TS ts, int which, PetscReal h, Vec X) {
  AlphaData* d = dataOf(ts);
  PetscFunctionBeginUser;
  if (which >= 1) PetscCall(VecAXPY(X, h, d->V0));
  if (which >= 2) PetscCall(VecAXPY(X, 0.5 * h * h, d->A0));
  if (d->prescribe) PetscCall(d->prescribe(ts->ptime + h, X, nullptr, nullptr, d->prescribeCtx));
  PetscFunctionReturn(0);
}

// offset = X0 + h V0 + h^2/2 A0 - X1 for the predictor X1 (0 on prescribed entries): the
// constant-acceleration predictor's distance, which the Newton test uses to measure the local error
// when Newton starts elsewhere (GeneralizedAlphaGetPredictorOffset).
PetscErrorCode predictorOffset(TS ts, Vec X1, PetscReal h) {
  AlphaData* d = dataOf(ts);
  PetscFunctionBeginUser;
  PetscCall(VecCopy(d->X0, d->offset));
  PetscCall(addPredictor(ts, 2, h, d->offset));
  PetscCall(VecAXPY(d->offset, -1.0, X1));
  PetscFunctionReturn(0);
}

// At the first step after a start (GeneralizedAlphaSetAcceleration): is X0 + h V0 (+ h^2/2 A0) a
// better Newton start than X0? The one with the smaller residual |R| is kept for the whole run.
// A suddenly applied load on a fine mesh has a consistent A0 that jumps at a support (the clamped
// node does not move, the next one falls at g); the predictor moves every node but the clamped
// one by h^2 g / 2 and so kinks the first element: a curvature 6 (h^2 g / 2) / l_e^2, a residual
// EI 6 (h^2 g/2) / l_e^3 that grows as N^3 (10,000-element steel cantilever: 7.8e9 N against
// 0.12 N at X0, and Newton diverges from it, docs/performance.md). That roughness stays in V and A
// (the scheme damps it only like rho_inf^n), so the next steps' predictors kink alike: the choice
// holds while the transient lasts: X0 is kept, and the two starts are weighed again every
// recheckEvery steps (two residuals), as after a failed step. A belt running over pulleys needs
// the predictor back once its start-up ringing has decayed: from X0 every sticking point starts
// one step's travel off its pulley's (2.4e-4 m at 1.2 m/s and h = 2e-4 s), and Newton took
// 14 iterations per step against 4 from the velocity predictor. On a smooth start the predictor's
// residual is O(h) of X0's (pendulum released under gravity), and when h V0 + h^2/2 A0 is at
// round-off both are X0.
void fallBack(AlphaData* d) {  // start from X0 for a while (choosePredictor)
  d->preferred = d->predictor;
  d->predictor = 0;
  d->recheckIn = d->recheckEvery;
}

PetscErrorCode choosePredictor(TS ts, Vec X1, PetscReal h) {
  AlphaData* d = dataOf(ts);
  Vec F;
  PetscReal predicted = 0.0, still = 0.0;
  PetscFunctionBeginUser;
  d->checkPredictor = false;
  if (!d->predictorCheck || d->predictor == 0) PetscFunctionReturn(0);
  // both starts are X0 when the predictor moves no coordinate beyond round-off (a start at rest
  // through joints has an A0 of round-off size; X holds displacements from coordinates of size
  // coordinateNorm)
  PetscReal moved, size;
  PetscCall(VecDuplicate(X1, &F));
  PetscCall(VecAXPBY(F, h, 0.0, d->V0));
  if (d->predictor >= 2) PetscCall(VecAXPY(F, 0.5 * h * h, d->A0));
  PetscCall(VecNorm(F, NORM_2, &moved));
  PetscCall(VecNorm(d->X0, NORM_2, &size));
  if (moved <= 10.0 * PETSC_MACHINE_EPSILON * std::max(size, d->coordinateNorm)) {
    PetscCall(VecDestroy(&F));
    PetscFunctionReturn(0);
  }
  for (int which : {0, d->predictor}) {
    PetscCall(VecCopy(d->X0, X1));
    PetscCall(addPredictor(ts, which, h, X1));
    PetscCall(SNESComputeFunction(ts->snes, X1, F));
    PetscBool domainError;  // set per rank: the same decision on every rank
    PetscCall(SNESGetFunctionDomainError(ts->snes, &domainError));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &domainError, 1, MPIU_BOOL, MPI_LOR, PetscObjectComm(reinterpret_cast<PetscObject>(ts))));
    PetscReal norm;
    PetscCall(VecNorm(F, NORM_2, &norm));
    if (domainError || !std::isfinite(norm)) norm = PETSC_MAX_REAL;
    (which == 0 ? still : predicted) = norm;
  }
  PetscCall(VecDestroy(&F));
  PetscCall(VecCopy(d->X0, X1));  // as step() expects it
  PetscCall(PetscInfo(ts, "first step: residual %g from the %s predictor, %g from X0: from %s for this run\n",
                      static_cast<double>(predicted), kPredictorNames[d->predictor],
                      static_cast<double>(still), still < predicted ? "X0" : "the predictor"));
  if (still < predicted) fallBack(d);
  PetscFunctionReturn(0);
}

// One Newton solve of the stage from X1, its iterations counted.
PetscErrorCode solveStage(TS ts, Vec X1, SNESConvergedReason* reason) {
  PetscFunctionBeginUser;
  PetscCall(SNESSolve(ts->snes, nullptr, X1));
  PetscInt nits, lits;
  PetscCall(SNESGetIterationNumber(ts->snes, &nits));
  PetscCall(SNESGetLinearSolveIterations(ts->snes, &lits));
  ts->snes_its += nits;
  ts->ksp_its += lits;
  PetscCall(SNESGetConvergedReason(ts->snes, reason));
  PetscFunctionReturn(0);
}

PetscErrorCode step(TS ts) {
  AlphaData* d = dataOf(ts);
  PetscFunctionBeginUser;
  PetscCheck(d->A, PetscObjectComm(reinterpret_cast<PetscObject>(ts)), PETSC_ERR_ORDER,
             "%s needs the initial acceleration: call GeneralizedAlphaSetAcceleration() before TSSolve()",
             kTsGeneralizedAlpha);
  PetscCall(VecCopy(ts->vec_sol, d->X0));
  PetscCall(VecCopy(ts->vec_dot, d->V0));
  if (d->startOffset) {
    PetscCall(VecAXPY(d->V0, 1.0, d->startOffset));
    PetscCall(VecDestroy(&d->startOffset));
  }
  // A0, a0 = A, a by exchange, not copy: A and a are rewritten on acceptance (the Get functions
  // give A0, a0 meanwhile)
  std::swap(d->A0, d->A);
  std::swap(d->a0, d->a);
  d->inStep = true;
  PetscBool accept = PETSC_FALSE, fresh = PETSC_TRUE;  // fresh: X1 still equals X0
  PetscInt rejections = 0;
  for (;;) {
    const PetscReal h = ts->time_step;
    d->stageTime = ts->ptime + h;  // equilibrium at t_{n+1}
    d->shiftV = d->gamma / (d->beta * h);
    d->shiftA = (1.0 - d->alphaM) / ((1.0 - d->alphaF) * d->beta * h * h);
    Vec X1 = ts->vec_sol;
    if (fresh && d->predictor == 0 && d->preferred > 0 && --d->recheckIn <= 0) {  // X0 since a fall-back
      d->predictor = d->preferred;
      d->checkPredictor = true;
    }
    if (d->checkPredictor && fresh) PetscCall(choosePredictor(ts, X1, h));
    bool released = false;    // held states (SettleFn) released after a failure
    bool retriedAll = false;  // Newton failed after every retry at this step size
    for (PetscBool again = PETSC_TRUE; again;) {
      again = PETSC_FALSE;
      // predictor: constant acceleration (or velocity, or displacement)
      if (!fresh) PetscCall(VecCopy(d->X0, X1));
      fresh = PETSC_FALSE;
      PetscCall(addPredictor(ts, d->predictor, h, X1));
      if (d->predictor < 2) PetscCall(predictorOffset(ts, X1, h));
      PetscCall(TSPreStage(ts, d->stageTime));
      SNESConvergedReason reason;
      PetscCall(solveStage(ts, X1, &reason));
      // held states (SettleFn): solve again while the solution's differ from those held
      for (int round = 0; reason >= 0 && d->settle; ++round) {
        PetscInt changed;
        PetscCall(stageVectors(ts, X1));  // V1 of X1
        // round kSettleRounds: the law decides at the points still changing; after that solve the
        // states it found are held for the next step
        PetscCall(d->settle(d->settleCtx, d->stageTime, X1, d->V1, round == kSettleRounds ? PETSC_TRUE : PETSC_FALSE,
                            &changed));
        if (round > kSettleRounds || (!changed && round < kSettleRounds)) break;
        PetscCall(solveStage(ts, X1, &reason));
      }
      if (reason >= 0) break;
      // Newton failed: once more from X0 with full Newton, and keep X0 as the start for a while
      // (a suddenly loaded fine mesh: the extrapolated acceleration kinks the elements at a
      // support and starts Newton outside its basin, docs/performance.md); the predictor is
      // weighed again after recheckEvery steps, twice as many after each failure from it
      if (d->retry) PetscCall(d->retry(d->retryCtx, &again));
      if (d->settle && !released) {  // held states may be what failed: let the law decide, once more
        PetscInt changed;
        PetscCall(d->settle(d->settleCtx, d->stageTime, X1, d->V1, PETSC_TRUE, &changed));
        released = true;
        again = PETSC_TRUE;
      }
      if (d->predictor > 0) {
        PetscCall(PetscInfo(ts, "Newton failed at t = %g from the %s predictor; from X0 for %d steps\n",
                            static_cast<double>(ts->ptime + h), kPredictorNames[d->predictor], d->recheckEvery));
        fallBack(d);
        d->recheckEvery = std::min(2 * d->recheckEvery, 1024);
        again = PETSC_TRUE;
      }
      if (again) ts->reject++;
      else retriedAll = true;
    }
    if (retriedAll && d->cuts < d->maxCuts) {
      // Newton failed at this step size after every retry: halve it and try again from X0 (the
      // contact states as after a failure: released); later steps double back to the nominal one
      if (d->cuts == 0) d->nominal = h;
      ++d->cuts;
      ts->time_step = 0.5 * h;
      PetscCall(PetscInfo(ts, "Newton failed at t = %g with every retry; the step cut to %g\n",
                          static_cast<double>(ts->ptime + h), static_cast<double>(ts->time_step)));
      PetscCall(VecCopy(d->X0, ts->vec_sol));
      if (d->settle) {  // a release right after the failure's releases them all
        PetscInt changed;
        PetscCall(d->settle(d->settleCtx, d->stageTime, X1, d->V1, PETSC_TRUE, &changed));
      }
      fresh = PETSC_TRUE;
      retriedAll = false;
      ts->reject++;
      continue;
    }
    PetscCall(TSAdaptCheckStage(ts->adapt, ts, ts->ptime + h, X1, &accept));
    // the next step (fixed unless an adaptor is chosen; stretched or cut to land on the final time);
    // an adaptor that rejects this one has the step retried with its size
    PetscReal next = h;
    if (accept) {
      PetscCall(TSAdaptChoose(ts->adapt, ts, h, nullptr, &next, &accept));
      if (!accept) ts->time_step = next;
    }
    if (accept) {
      PetscCall(stageVectors(ts, X1));  // V1, A1 of the converged X1
      if (d->differential)  // multipliers have no rate: the predictor keeps their last value
        for (Vec v : {d->V1, d->A1, d->a1}) PetscCall(VecPointwiseMult(v, v, d->differential));
      PetscCall(VecCopy(d->V1, ts->vec_dot));
      std::swap(d->A, d->A1);  // A1, a1 are rewritten by the next stageVectors
      std::swap(d->a, d->a1);
      ts->ptime += h;
      ts->time_step = next;
      if (d->cuts > 0) {  // after a cut: back towards the nominal step, doubling per accepted step,
        --d->cuts;        // and not beyond the final time
        const PetscReal back = d->cuts == 0 ? d->nominal : 2.0 * h, left = ts->max_time - ts->ptime;
        ts->time_step = left > 0.0 ? PetscMin(back, left) : back;
      }
      break;
    }
    PetscCall(VecCopy(d->X0, ts->vec_sol));  // reject: back to the start of the step
    fresh = PETSC_TRUE;
    ts->reject++;
    if (ts->reason) break;  // too many Newton failures (TSSetMaxSNESFailures)
    if (++rejections > ts->max_reject && ts->max_reject >= 0) {
      ts->reason = TS_DIVERGED_STEP_REJECTED;
      break;
    }
  }
  if (!accept) {  // the step failed: the state stays that of its start
    std::swap(d->A0, d->A);
    std::swap(d->a0, d->a);
  }
  d->inStep = false;
  PetscFunctionReturn(0);
}

PetscErrorCode rollBack(TS ts) {
  AlphaData* d = dataOf(ts);
  PetscFunctionBeginUser;
  PetscCall(VecCopy(d->X0, ts->vec_sol));
  PetscCall(VecCopy(d->V0, ts->vec_dot));
  PetscCall(VecCopy(d->A0, d->A));
  PetscCall(VecCopy(d->a0, d->a));
  PetscFunctionReturn(0);
}

PetscErrorCode setUp(TS ts) {
  AlphaData* d = dataOf(ts);
  PetscFunctionBeginUser;
  PetscCheck(ts->vec_dot, PetscObjectComm(reinterpret_cast<PetscObject>(ts)), PETSC_ERR_ORDER,
             "%s integrates second-order systems: call TS2SetSolution()", kTsGeneralizedAlpha);
  PetscCheck(d->alphaF < 1.0, PetscObjectComm(reinterpret_cast<PetscObject>(ts)),
             PETSC_ERR_ARG_OUTOFRANGE, "%s needs alpha_f < 1, not %g", kTsGeneralizedAlpha,
             static_cast<double>(d->alphaF));
  for (Vec* v : {&d->X0, &d->V0, &d->A0, &d->a0, &d->V1, &d->A1, &d->a1, &d->offset})
    if (!*v) PetscCall(VecDuplicate(ts->vec_sol, v));
  PetscCall(TSGetSNES(ts, &ts->snes));
  PetscFunctionReturn(0);
}

PetscErrorCode reset(TS ts) {
  AlphaData* d = dataOf(ts);
  PetscFunctionBeginUser;
  for (Vec* v : {&d->X0, &d->V0, &d->A0, &d->a0, &d->V1, &d->A1, &d->a1, &d->A, &d->a, &d->differential, &d->startOffset,
                 &d->offset})
    PetscCall(VecDestroy(v));
  PetscFunctionReturn(0);
}

PetscErrorCode destroy(TS ts) {
  PetscFunctionBeginUser;
  PetscCall(reset(ts));
  delete dataOf(ts);
  ts->data = nullptr;
  PetscFunctionReturn(0);
}

PetscErrorCode setFromOptions(TS ts, PetscOptionItems* PetscOptionsObject) {
  AlphaData* d = dataOf(ts);
  PetscFunctionBeginUser;
  PetscOptionsHeadBegin(PetscOptionsObject, "Strand generalized-alpha options");
  PetscReal radius = 1.0;
  PetscBool set;
  PetscCall(PetscOptionsReal("-ts_strand_alpha_radius", "Spectral radius at infinite frequency", "GeneralizedAlphaSetRadius",
                             radius, &radius, &set));
  if (set) PetscCall(GeneralizedAlphaSetRadius(ts, radius));
  PetscCall(PetscOptionsReal("-ts_strand_alpha_alpha_m", "alpha_m", "GeneralizedAlphaSetParams", d->alphaM, &d->alphaM, nullptr));
  PetscCall(PetscOptionsReal("-ts_strand_alpha_alpha_f", "alpha_f", "GeneralizedAlphaSetParams", d->alphaF, &d->alphaF, nullptr));
  PetscCall(PetscOptionsReal("-ts_strand_alpha_gamma", "gamma", "GeneralizedAlphaSetParams", d->gamma, &d->gamma, nullptr));
  PetscCall(PetscOptionsReal("-ts_strand_alpha_beta", "beta", "GeneralizedAlphaSetParams", d->beta, &d->beta, nullptr));
  PetscInt which = d->predictor;
  PetscCall(PetscOptionsEList("-ts_strand_alpha_predictor", "Newton start: X0, X0 + h V0, or X0 + h V0 + h^2/2 A0",
                              "", kPredictorNames, 3, kPredictorNames[which], &which, &set));
  d->predictor = static_cast<int>(which);
  // a start named on the command line is the start used: no check, unless also asked for
  PetscBool check = d->predictorCheck && !set ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(PetscOptionsBool("-ts_strand_alpha_predictor_check",
                             "At the first step, start from X0 for the run if its residual is smaller than the predictor's "
                             "(default: true, false when -ts_strand_alpha_predictor is given)", "",
                             check, &check, nullptr));
  d->predictorCheck = check == PETSC_TRUE;
  PetscOptionsHeadEnd();
  PetscFunctionReturn(0);
}

PetscErrorCode view(TS ts, PetscViewer viewer) {
  AlphaData* d = dataOf(ts);
  PetscBool ascii;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(viewer), PETSCVIEWERASCII, &ascii));
  if (ascii)
    PetscCall(PetscViewerASCIIPrintf(viewer, "  alpha_m=%g alpha_f=%g gamma=%g beta=%g (consistent start)\n",
                                     static_cast<double>(d->alphaM), static_cast<double>(d->alphaF),
                                     static_cast<double>(d->gamma), static_cast<double>(d->beta)));
  PetscFunctionReturn(0);
}

PetscErrorCode create(TS ts) {
  PetscFunctionBeginUser;
  ts->ops->reset = reset;
  ts->ops->destroy = destroy;
  ts->ops->view = view;
  ts->ops->setup = setUp;
  ts->ops->setfromoptions = setFromOptions;
  ts->ops->step = step;
  ts->ops->rollback = rollBack;
  ts->ops->snesfunction = snesFunction;
  ts->ops->snesjacobian = snesJacobian;
  ts->default_adapt_type = TSADAPTNONE;
  ts->usessnes = PETSC_TRUE;
  ts->data = new AlphaData();
  PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode GeneralizedAlphaRegister() {
  static bool registered = false;
  PetscFunctionBeginUser;
  if (!registered) PetscCall(TSRegister(kTsGeneralizedAlpha, create));
  registered = true;
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlphaSetParams(TS ts, PetscReal alphaM, PetscReal alphaF, PetscReal gamma, PetscReal beta) {
  PetscFunctionBeginUser;
  PetscCall(checkType(ts));
  AlphaData* d = dataOf(ts);
  d->alphaM = alphaM;
  d->alphaF = alphaF;
  d->gamma = gamma;
  d->beta = beta;
  PetscFunctionReturn(0);
}

AlphaParams GeneralizedAlphaParamsFromRadius(PetscReal rho) {
  const PetscReal am = (2.0 * rho - 1.0) / (rho + 1.0), af = rho / (rho + 1.0), g = 0.5 + af - am;
  return {am, af, g, 0.25 * (g + 0.5) * (g + 0.5)};
}

PetscErrorCode GeneralizedAlphaSetRadius(TS ts, PetscReal rho) {
  PetscFunctionBeginUser;
  PetscCheck(rho >= 0.0 && rho <= 1.0, PetscObjectComm(reinterpret_cast<PetscObject>(ts)), PETSC_ERR_ARG_OUTOFRANGE,
             "spectral radius %g not in [0, 1]", static_cast<double>(rho));
  const AlphaParams p = GeneralizedAlphaParamsFromRadius(rho);
  PetscCall(GeneralizedAlphaSetParams(ts, p.alphaM, p.alphaF, p.gamma, p.beta));
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlphaSetAcceleration(TS ts, Vec A) {
  PetscFunctionBeginUser;
  PetscCall(checkType(ts));
  AlphaData* d = dataOf(ts);
  PetscCall(copyInto(A, &d->A));
  PetscCall(copyInto(A, &d->a));  // a_0 = A_0 (Arnold & Bruls 2007, Sec. 3)
  d->checkPredictor = true;       // a new start
  d->cuts = 0;                    // ... at the nominal step (a resumed run: GeneralizedAlphaResumeStepCuts)
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlphaGetAcceleration(TS ts, Vec* A) {
  PetscFunctionBeginUser;
  PetscCall(checkType(ts));
  const AlphaData* d = dataOf(ts);
  *A = d->inStep ? d->A0 : d->A;
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlphaGetState(TS ts, Vec* A, Vec* a) {
  PetscFunctionBeginUser;
  PetscCall(checkType(ts));
  const AlphaData* d = dataOf(ts);
  *A = d->inStep ? d->A0 : d->A;
  *a = d->inStep ? d->a0 : d->a;
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlphaSetState(TS ts, Vec A, Vec a) {
  PetscFunctionBeginUser;
  PetscCall(GeneralizedAlphaSetAcceleration(ts, A));
  PetscCall(VecCopy(a, dataOf(ts)->a));
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlphaSetStartVelocityOffset(TS ts, Vec dv) {
  PetscFunctionBeginUser;
  PetscCall(checkType(ts));
  AlphaData* d = dataOf(ts);
  PetscCall(copyInto(dv, &d->startOffset));
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlphaSetAlgebraic(TS ts, Vec mask) {
  PetscFunctionBeginUser;
  PetscCall(checkType(ts));
  AlphaData* d = dataOf(ts);
  PetscCall(copyInto(mask, &d->differential));
  PetscCall(VecShift(d->differential, -1.0));
  PetscCall(VecScale(d->differential, -1.0));
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlphaSetPrescribedMotion(TS ts, PrescribeFn prescribe, void* ctx) {
  PetscFunctionBeginUser;
  PetscCall(checkType(ts));
  dataOf(ts)->prescribe = prescribe;
  dataOf(ts)->prescribeCtx = ctx;
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlphaSetCoordinateNorm(TS ts, PetscReal norm) {
  PetscFunctionBeginUser;
  PetscCall(checkType(ts));
  dataOf(ts)->coordinateNorm = norm;
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlphaGetPredictor(TS ts, PetscInt* which, const char** name) {
  PetscFunctionBeginUser;
  PetscCall(checkType(ts));
  if (which) *which = dataOf(ts)->predictor;
  if (name) *name = kPredictorNames[dataOf(ts)->predictor];
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlphaSetPredictor(TS ts, PetscInt which) {
  PetscFunctionBeginUser;
  PetscCall(checkType(ts));
  PetscCheck(which >= 0 && which <= 2, PetscObjectComm(reinterpret_cast<PetscObject>(ts)), PETSC_ERR_ARG_OUTOFRANGE,
             "predictor %d not in 0..2", static_cast<int>(which));
  dataOf(ts)->predictor = static_cast<int>(which);
  dataOf(ts)->checkPredictor = false;
  dataOf(ts)->preferred = -1;
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlphaGetPredictorOffset(TS ts, Vec* offset) {
  PetscFunctionBeginUser;
  PetscCall(checkType(ts));
  const AlphaData* d = dataOf(ts);
  *offset = d->inStep && d->predictor < 2 ? d->offset : nullptr;
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlphaSetSettle(TS ts, SettleFn settle, void* ctx) {
  PetscFunctionBeginUser;
  PetscCall(checkType(ts));
  dataOf(ts)->settle = settle;
  dataOf(ts)->settleCtx = ctx;
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlphaSetStepCuts(TS ts, PetscInt maxCuts) {
  PetscFunctionBeginUser;
  PetscCall(checkType(ts));
  dataOf(ts)->maxCuts = static_cast<int>(maxCuts);
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlphaGetStepCuts(TS ts, PetscInt* cuts, PetscReal* nominal) {
  PetscFunctionBeginUser;
  PetscCall(checkType(ts));
  *cuts = dataOf(ts)->cuts;
  *nominal = dataOf(ts)->nominal;
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlphaResumeStepCuts(TS ts, PetscInt cuts, PetscReal nominal) {
  PetscFunctionBeginUser;
  PetscCall(checkType(ts));
  if (cuts <= 0) PetscFunctionReturn(0);
  dataOf(ts)->cuts = static_cast<int>(cuts);
  dataOf(ts)->nominal = nominal;
  PetscCall(TSSetTimeStep(ts, std::ldexp(nominal, -static_cast<int>(cuts))));
  PetscFunctionReturn(0);
}

PetscErrorCode GeneralizedAlphaSetNewtonRetry(TS ts, RetryFn retry, void* ctx) {
  PetscFunctionBeginUser;
  PetscCall(checkType(ts));
  dataOf(ts)->retry = retry;
  dataOf(ts)->retryCtx = ctx;
  PetscFunctionReturn(0);
}

}  // namespace strand::solvers
