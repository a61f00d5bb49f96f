// Our generalized-alpha TS for second-order systems, registered with PETSc as "strand_alpha".
//
// Chung & Hulbert, J. Appl. Mech. 60 (1993) 371, in PETSc's TSALPHA2 parameterization (alpha_m and
// alpha_f weight the end of the step; Chung-Hulbert's are 1 - these): with h the step,
//   A1 = (X1 - X0 - h V0) / (beta h^2) - (1 - 2 beta) / (2 beta) A0,   V1 = V0 + h ((1 - gamma) A0 + gamma A1),
//   Xa = X0 + alpha_f (X1 - X0),  Va = V0 + alpha_f (V1 - V0),  Aa = A0 + alpha_m (A1 - A0),
// and Newton solves F(t_n + alpha_f h, Xa, Va, Aa) = 0 for X1 (the TS's I2Function/I2Jacobian, the
// latter with shiftV = gamma / (beta h), shiftA = alpha_m / (alpha_f beta h^2)). It is second order
// when gamma = 1/2 + alpha_m - alpha_f, PROVIDED A0 is the true initial acceleration.
//
// Why not TSALPHA2 (measured, docs/validation.md "Time integration"): PETSc 3.18 starts from an
// acceleration estimated by two backward-Euler half steps, an O(h) error that drops Newmark, HHT and
// rho_inf < 1 to first order. Here the caller supplies the consistent A0 (M A0 = -R(X0, V0)), and the
// acceleration is part of the state (restartable). Two more things this TS does that TSALPHA2 cannot:
//   - prescribed motion: a callback overwrites the prescribed entries of X1 at t_{n+1} after the
//     predictor, so rheonomic supports hold exactly at the end of the step (the residual rows of
//     those entries must be zero, the Jacobian rows unit);
//   - predictor X1 = X0 + h V0 + h^2/2 A0 (constant acceleration) instead of X1 = X0.
#pragma once
#include <petscts.h>

namespace strand::solvers {

inline constexpr const char* kTsGeneralizedAlpha = "strand_alpha";

// Registers the TS type (idempotent; call after PetscInitialize).
PetscErrorCode GeneralizedAlphaRegister();
// Parameters as TSAlpha2SetParams, or from the spectral radius as TSAlpha2SetRadius.
PetscErrorCode GeneralizedAlphaSetParams(TS ts, PetscReal alphaM, PetscReal alphaF, PetscReal gamma, PetscReal beta);
PetscErrorCode GeneralizedAlphaSetRadius(TS ts, PetscReal rhoInf);
// The acceleration at the current TS time (required before the first step; copied).
PetscErrorCode GeneralizedAlphaSetAcceleration(TS ts, Vec A);
// The acceleration at the current TS time (borrowed; valid until the next step).
PetscErrorCode GeneralizedAlphaGetAcceleration(TS ts, Vec* A);
// prescribe(t, X, ctx) sets the prescribed entries of X to their values at time t.
using PrescribeFn = PetscErrorCode (*)(PetscReal t, Vec X, void* ctx);
PetscErrorCode GeneralizedAlphaSetPrescribedMotion(TS ts, PrescribeFn prescribe, void* ctx);

}  // namespace strand::solvers
