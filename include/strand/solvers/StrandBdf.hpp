// BDF of order 1-5 on F(t, y, y') = 0, fixed or adaptive step, registered with PETSc as the TS type
// "strand_bdf": PETSc's TSBDF step by step (the same start, coefficients, predictor, error estimate
// and use of TSAdapt), with its history readable and settable, so that a checkpoint continues the
// trajectory exactly (TSBDF keeps its history private: a restart would begin its start-up again).
//
// The scheme (Hairer & Wanner, Solving ODEs II, Sec. III.1 and V.1, on a non-uniform history):
// y' at t_{n+1} is the derivative of the Lagrange polynomial through y_{n+1} and the last k states,
//   y'_{n+1} = sigma y_{n+1} + sum_{j>=1} l_j'(t_{n+1}) y_{n+1-j},   sigma = l_0'(t_{n+1}),
// and Newton solves F(t_{n+1}, y, sigma y + ...) = 0 from the polynomial through the last k + 1
// states extrapolated to t_{n+1}. Start, as TSBDF_Restart (PETSc 3.18 src/ts/impls/bdf/bdf.c): a
// backward-Euler half step to t_0 + h/2 joins the history, then the order rises by one per step up
// to k. The half step's O(h^2) local error stays in the global error, so orders 3-5 converge at
// order 2 at fixed step (docs/validation.md).
// Adaptive step (TSAdapt other than none), as TSStep_BDF and TSEvaluateWLTE_BDF: the local error
// estimate is y_{n+1} minus the order-(k+1) BDF solution implied by the same history,
//   lte = sum_i (a_i - b_i) / a_0 y_i  (a, b: the derivative weights of the Lagrange polynomials
//   through k + 1 and k + 2 nodes at t_{n+1}, a_{k+1} = 0),
// weighed by TSErrorWeightedNorm; a rejected step is retried with the adaptor's step and a
// predictor of one order less.
#pragma once
#include <petscts.h>

#include <vector>

namespace strand::solvers {

inline constexpr const char* kTsStrandBdf = "strand_bdf";

// Registers the TS type (idempotent; call after PetscInitialize).
PetscErrorCode StrandBdfRegister();
PetscErrorCode StrandBdfSetOrder(TS ts, PetscInt order);

// The history at the current TS time: the current order k, the steps since the start, and the
// states with their times, most recent first (borrowed; valid until the next step). With the
// TS's next step size (TSGetTimeStep) it is all the state of the scheme.
struct BdfHistory {
  PetscInt order = 1, steps = 0;
  std::vector<PetscReal> times;
  std::vector<Vec> states;
};
PetscErrorCode StrandBdfGetHistory(TS ts, BdfHistory* h);
// A history to continue from (copied; the next step uses it instead of starting).
PetscErrorCode StrandBdfSetHistory(TS ts, const BdfHistory& h);
// y' at the current TS time as the last accepted step solved for it: the derivative of the
// Lagrange polynomial through that step's k + 1 nodes (StrandBdf.hpp's formula), so that
// F(t, y, y') = 0 holds to the Newton tolerance. *known is false before the first step.
PetscErrorCode StrandBdfGetDerivative(TS ts, Vec ydot, PetscBool* known);

}  // namespace strand::solvers
