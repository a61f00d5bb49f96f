// Our generalized-alpha TS for second-order systems, registered with PETSc as "strand_alpha".
//
// The form of Arnold & Bruls, Multibody Syst. Dyn. 18 (2007) 185, Eqs. 9-11: equilibrium holds at
// the end of the step with the true acceleration A, and an acceleration-like variable a carries the
// alpha weights. With h the step, given X1 (the Newton unknown):
//   a1 = (X1 - X0 - h V0 - h^2 (1/2 - beta) a0) / (beta h^2),   V1 = V0 + h ((1 - gamma) a0 + gamma a1),
//   (1 - alpha_m) a1 + alpha_m a0 = (1 - alpha_f) A1 + alpha_f A0,
// and Newton solves F(t_{n+1}, X1, V1, A1) = 0 (the TS's I2Function; the I2Jacobian gets
// shiftV = gamma / (beta h), shiftA = (1 - alpha_m) / ((1 - alpha_f) beta h^2)). Second order for
// gamma = 1/2 + alpha_f - alpha_m, with a0 = A0 the true initial acceleration. Parameters
// (alpha_m, alpha_f weight the START of the step, Chung & Hulbert's convention):
//   rho_inf:  alpha_m = (2 rho - 1)/(rho + 1), alpha_f = rho/(rho + 1), beta = (gamma + 1/2)^2 / 4;
//   Newmark:  alpha_m = alpha_f = 0, gamma = 1/2, beta = 1/4;
//   HHT:      alpha_m = 0, alpha_f = alpha, gamma = 1/2 + alpha, beta = (1 + alpha)^2 / 4.
// For linear systems this is Chung & Hulbert's method; for large rotations it differs, and the
// difference matters (measured, docs/validation.md "Spin-up"): evaluating the internal forces at
// the interpolated configuration X0 + (1 - alpha_f)(X1 - X0), as Chung & Hulbert and PETSc's
// TSALPHA2 do, shortens a turning beam by the chord of its rotation, a strain
// alpha_f (1 - alpha_f) (Omega h)^2 / 2 that the elastic force answers with a spurious stretch (three
// times the true centrifugal stretch of the seed 001 spin-up at h = 5 ms).
//
// Why not TSALPHA2: besides the above, PETSc 3.18 starts from an acceleration estimated by two
// backward-Euler half steps, an O(h) error that drops Newmark, HHT and rho_inf < 1 to first order.
// Here the caller supplies the consistent A0 (M A0 = -R(X0, V0)), and the accelerations are part of
// the state. Also:
//   - prescribed motion: a callback overwrites the prescribed entries of X1 at t_{n+1} after the
//     predictor, so rheonomic supports hold exactly at the end of the step (the residual rows of
//     those entries must be zero, the Jacobian rows unit), and those of V1 and A1 at every stage:
//     left to the recursions above, V and A of a prescribed coordinate would carry an O(h)
//     transient (a1 - A(t1 + (alpha_m - alpha_f) h) = O(h psi''') from Newmark's formula fitted to
//     exact positions), damped only like rho_inf^n, into the mass-coupled loads of the free rows and
//     into the support force (measured: the drive torque of a hub started by a sine, 0.6 % off at
//     h = 1 ms and first order; tests/verification/test_multibody.cpp);
//   - predictor X1 = X0 + h V0 + h^2/2 A0 (constant acceleration) instead of X1 = X0
//     (-ts_strand_alpha_predictor displacement | velocity | acceleration; displacement is the
//     robust start for fine, stiff meshes under suddenly applied loads, docs/performance.md).
//     At the first step after a start (GeneralizedAlphaSetAcceleration) the residual at the
//     predictor is compared with that at X0, and X0 is kept for the run if its residual is
//     smaller (-ts_strand_alpha_predictor_check false skips that): a load applied suddenly to a
//     fine mesh gives an A0 that jumps at a support, and the predictor kinks the elements there.
//     When Newton fails anyway, the step is tried once more from X1 = X0 (counted as a rejected
//     step), and the displacement predictor is kept from then on;
//   - index-3 constraints (Arnold & Bruls 2007, Sec. 4): Lagrange multipliers are entries of X
//     marked algebraic; their rows hold s g(q1) at t_{n+1}, so the position constraints hold to
//     Newton tolerance at every step (no drift).
#pragma once
#include <petscts.h>

namespace strand::solvers {

inline constexpr const char* kTsGeneralizedAlpha = "strand_alpha";

// alpha_m, alpha_f (weights of the start of the step), gamma, beta.
struct AlphaParams {
  PetscReal alphaM, alphaF, gamma, beta;
};
// Chung & Hulbert 1993 Eq. 25 (Arnold & Bruls 2007 Eq. 17) for the spectral radius rho_inf.
AlphaParams GeneralizedAlphaParamsFromRadius(PetscReal rhoInf);

// Registers the TS type (idempotent; call after PetscInitialize).
PetscErrorCode GeneralizedAlphaRegister();
// Parameters in the convention above, or from the spectral radius rho_inf.
PetscErrorCode GeneralizedAlphaSetParams(TS ts, PetscReal alphaM, PetscReal alphaF, PetscReal gamma, PetscReal beta);
PetscErrorCode GeneralizedAlphaSetRadius(TS ts, PetscReal rhoInf);
// The acceleration at the current TS time (required before the first step; copied).
PetscErrorCode GeneralizedAlphaSetAcceleration(TS ts, Vec A);
// The acceleration at the current TS time (borrowed; valid until the next step).
PetscErrorCode GeneralizedAlphaGetAcceleration(TS ts, Vec* A);
// The acceleration-like variable a as well (borrowed), and both set together: a checkpoint of the
// scheme's state at the current TS time (X, V are the TS solution).
PetscErrorCode GeneralizedAlphaGetState(TS ts, Vec* A, Vec* a);
PetscErrorCode GeneralizedAlphaSetState(TS ts, Vec A, Vec a);
// A velocity offset added to the scheme's v at the start of the next step only (perturbed starting
// values, Dynamics::perturbedStart): the state at the current time stays as given (copied).
PetscErrorCode GeneralizedAlphaSetStartVelocityOffset(TS ts, Vec dv);
// Algebraic unknowns (mask 1: Lagrange multipliers of an index-3 system): their velocity and
// accelerations are held at zero, so the predictor keeps their last value (copied).
PetscErrorCode GeneralizedAlphaSetAlgebraic(TS ts, Vec mask);
// prescribe(t, X, V, A, ctx) sets the prescribed entries of the non-null ones among X, V, A to
// their values at time t.
using PrescribeFn = PetscErrorCode (*)(PetscReal t, Vec X, Vec V, Vec A, void* ctx);
PetscErrorCode GeneralizedAlphaSetPrescribedMotion(TS ts, PrescribeFn prescribe, void* ctx);
// When X holds displacements u from reference coordinates q0 (q = q0 + u): |q0|, the scale of
// their round-off (the first step's check ignores a predictor that moves X by round-off only).
PetscErrorCode GeneralizedAlphaSetCoordinateNorm(TS ts, PetscReal norm);
// The Newton start in use: which = 2, "acceleration" (X0 + h V0 + h^2/2 A0, the default), 1,
// "velocity", or 0, "displacement" (X0): set by -ts_strand_alpha_predictor, and changed to
// "displacement" for the rest of the run by the first step's check or by a Newton failure (see the
// top of this file). Either pointer may be null.
PetscErrorCode GeneralizedAlphaGetPredictor(TS ts, PetscInt* which, const char** name);
// Continues a run with the Newton start `which` (a checkpoint's), without the first-step check.
// Call after GeneralizedAlphaSetState.
PetscErrorCode GeneralizedAlphaSetPredictor(TS ts, PetscInt which);
// Within a step whose Newton starts from X0 or X0 + h V0: the constant-acceleration predictor
// X0 + h V0 + h^2/2 A0 minus that start (0 on prescribed entries); null otherwise. Its distance
// from the Newton iterate estimates the local error (NewtonConvergence.hpp, NewtonFloor::offset).
PetscErrorCode GeneralizedAlphaGetPredictorOffset(TS ts, Vec* offset);

// After a failed Newton solve, retry(ctx, &again) is told (e.g. to build a fresh Newton matrix,
// NewtonMatrixReuse) and may ask for one more attempt of the same step from X1 = X0 before the
// failure goes to TSAdaptCheckStage (the TS retries anyway after a failure from a predictor other
// than X0).
using RetryFn = PetscErrorCode (*)(void* ctx, PetscBool* again);
// Step cuts: when Newton fails at a step after every retry, the step is halved (at most maxCuts
// times in a row, so down to dt / 2^maxCuts) and tried again from X0; each accepted step after a
// cut doubles it back until it is the nominal one. 0 (the default): the failure ends the run.
PetscErrorCode GeneralizedAlphaSetNewtonRetry(TS ts, RetryFn retry, void* ctx);
PetscErrorCode GeneralizedAlphaSetStepCuts(TS ts, PetscInt maxCuts);
// The cuts in force (the next step is nominal / 2^cuts) and the nominal step, for checkpoints;
// Resume puts them back (and the next step) in a run that continues from one.
PetscErrorCode GeneralizedAlphaGetStepCuts(TS ts, PetscInt* cuts, PetscReal* nominal);
PetscErrorCode GeneralizedAlphaResumeStepCuts(TS ts, PetscInt cuts, PetscReal nominal);

// A residual with states held fixed while Newton solves (the stick/slip states of contact points,
// docs/contact.md): after each converged solve, settle(ctx, t, X1, V1, release, &changed) compares
// them with those of the solution and holds the new ones; while any changed, Newton solves again
// from X1. After kSettleRounds rounds it is called with release = true (hold none where states
// still changed: the law decides there within Newton), Newton solves once more, and settle holds
// the states of that solution for the next step; when a solve fails, the step is retried from X0
// with the states released (SettleFn decides which; a release right after another releases
// all, as before a step cut).
using SettleFn = PetscErrorCode (*)(void* ctx, PetscReal t, Vec X, Vec V, PetscBool release, PetscInt* changed);
PetscErrorCode GeneralizedAlphaSetSettle(TS ts, SettleFn settle, void* ctx);

}  // namespace strand::solvers
