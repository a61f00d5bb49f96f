#include "strand/solvers/NewtonConvergence.hpp"

#include <algorithm>
#include <cmath>

namespace strand::solvers {

// SNESConvergedDefault, except that a small Newton correction counts only if |R| has not grown
// above its value at the first iterate, and "small" is measured against the coordinates:
//  - the residual of a position-based beam has a round-off floor: r'' = sum B2 q cancels terms of
//    size 1/l, so |R| stalls near EI eps_mach sqrt(N) / l^2 (7.6e-6 of the load for 1000
//    elements, docs/validation.md "Conditioning") and rtol 1e-10 is unreachable; there the Newton
//    correction no longer changes u, which is what the step test detects;
//  - the residual is evaluated at q = q0 + u, so u is resolved only to eps |q|: when u is still
//    small (the first steps of a dynamic run) |du| < stol |u| is unreachable, and the joint rows
//    s g(q) (s = 1/(beta h^2), Multibody.hpp) stall at s eps |q|. So the step test is
//    |du| < stol max(|u|, |q0|);
//  - the step test measures the error left after the correction, not the correction: with the
//    contraction theta = |du_k| / |du_{k-1}| < 1/2 of the last two corrections that error is
//    about theta / (1 - theta) |du_k| (Deuflhard, "Newton Methods for Nonlinear Problems" 2004,
//    sec. 2.1; Hairer & Wanner, "Solving ODEs II", IV.8 Eq. 8.17). For quadratic convergence
//    this saves the last iteration, which only confirms; for a kept Newton matrix
//    (NewtonMatrixReuse) theta is its linear rate;
//  - with a singular tangent the iterates run away, |u| grows and |du|/|u| shrinks while |R| is
//    1e28 (seen with an unsupported cable): the residual test rejects that;
//  - a correction from a kept Newton matrix (NewtonMatrixReuse) must itself be at most
//    keptTolerance |du_1| (or at round-off), a fraction of the step's first correction, i.e. of the predictor's error,
//    which is of the order of the scheme's local error. Full Newton stops far below stol |q|
//    (its error is quadratic), a kept matrix just below it, and in the same direction at every
//    step: the error then adds up over the T/h steps (spin-up at h = 62.5 us: 7.3e-7 m against
//    3.9e-9 m with full Newton), and on index-3 multipliers, which are positions times
//    s = 1/(beta h^2), it is amplified by s and fed back through the predictor into the scheme's
//    spurious root -rho_inf (distance joint: a tension error alternating from step to step, 2e-3 of
//    3 m g at h = 0.5 ms, proportional to stol). Measured against |du_1| the Newton error stays a
//    fixed fraction of the discretization error at every h. The ratio theta of the corrections
//    cannot be trusted for this: du_1 is dominated by components the kept matrix removes at once,
//    so theta = |du_2|/|du_1| was 0.003 while the slowest component contracted at 0.28.
//
// Statics (NewtonFloor::energyTest) stops on the energy of the correction instead, e_k =
// |du_k . R_{k-1}| = du_k^T J du_k (Bathe, "Finite Element Procedures" 1996, sec. 8.4.4, the energy
// criterion), relative to the first, e_1 = the linear work of the load increment, or to the strain
// energy U when that is larger (a load step that hardly changes the state, a sweep point started
// from a good predictor: e_1 is then round-off itself, and relative to it nothing converges). e is the squared
// error of q_{k-1} in the tangent's energy norm, which weighs a stiff direction by its stiffness:
// for a cantilever elastica with EA L^2/EI = 1e10 the step test accepted an iterate 2.4e-4 L from
// the converged tip after a tiny axial correction (|du| 1e-9) that followed a bending correction
// with e = 5e-5 J; the residual there was 1e3 N from axial strain alone. Newton on such a beam
// alternates bending corrections (which stretch it, e up) and axial ones (e down), so neither |R| nor
// |du| nor their ratio falls monotonically, while e_k falls quadratically once the iterate is close:
// e_k / e_1 = 1e-5, 1e-12, 1e-17 at EA L^2/EI = 1e10. Its round-off floor, where R is the noise of
// the internal forces and du = J^-1 R, was 1e-22 e_1 there (64 elements); energyTolerance 1e-20
// asks for an error 1e-10 of the increment's displacement. When e stalls above that (more
// elements, a worse-conditioned tangent), e_k > e_{k-1} / 4 with e_k <= floorTolerance e_ref (1e-12,
// an error 1e-6 of the increment) is taken as the floor. Either way the achieved e_k / e_1 is
// reported (StaticStep::energyRatio, e_k / e_ref).
namespace {

// For a correction du_it (|du_it| = snorm) from a kept matrix: is it at most keptTolerance |du_1|?
// (Its own size, not theta/(1 - theta) of it: theta is not trustworthy here.) A correction at the
// round-off of the coordinates, 10 eps max(|u|, |q0|), is accepted too: a step at rest has a first
// correction of that size, which a kept matrix cannot reduce 1000x (it would be rebuilt instead).
// The reference of a solve whose first correction is du_1: |du_1|, or the local-error estimate
// |X_k - X_a| of the current iterate when smaller (NewtonFloor::offset).
PetscReal firstStepReference(const NewtonFloor& floor, PetscReal firstStep) {
  return floor.offsetStep >= 0.0 ? std::min(firstStep, floor.offsetStep) : firstStep;
}

bool keptMatrixConverged(const NewtonFloor& floor, PetscInt it, PetscReal snorm, PetscReal xnorm) {
  const PetscReal firstStep = firstStepReference(floor, it == 1 ? snorm : floor.firstStep);
  const PetscReal roundoff = 10.0 * PETSC_MACHINE_EPSILON * std::max(xnorm, floor.coordinateNorm);
  return !floor.keptMatrix || floor.keptTolerance <= 0.0 || snorm <= std::max(floor.keptTolerance * firstStep, roundoff);
}

// The energy test (statics) after the correction of iteration it.
bool energyConverged(const NewtonFloor& floor, PetscInt it) {
  const PetscReal reference = floor.energyReference();
  if (floor.energyIteration != it || it < 1 || reference <= 0.0) return false;
  if (floor.energy <= floor.energyTolerance * reference) return true;
  return it >= 2 && floor.energy <= floor.floorTolerance * reference && floor.energy > 0.25 * floor.previousEnergy;
}

// The step test: after the correction du_it (|du_it| = snorm, the one before: previousStep), is the
// error left below stol max(|u|, |q0|), and, for a kept matrix, is keptMatrixConverged?
bool stepConverged(const NewtonFloor& floor, PetscInt it, PetscReal previousStep, PetscReal snorm, PetscReal xnorm,
                   PetscReal stol) {
  const PetscReal theta = it >= 2 && previousStep > 0.0 ? snorm / previousStep : 0.0;
  const PetscReal error = theta > 0.0 && theta < 0.5 ? theta / (1.0 - theta) * snorm : snorm;
  return it > 0 && keptMatrixConverged(floor, it, snorm, xnorm) && error < stol * std::max(xnorm, floor.coordinateNorm);
}

// u -= lambda du and the sums of squares of both; with an offset p (NewtonFloor::offset, X_a - u
// before the correction) also p += lambda du and its sum of squares; with a residual r (the energy
// test of statics: r at u before the step) also du . r. restrict (distinct vectors) lets the
// compiler vectorize it.
template <bool withOffset, bool withEnergy>
void stepLoop(PetscInt n, PetscReal lambda, PetscScalar* PETSC_RESTRICT u, const PetscScalar* PETSC_RESTRICT du,
              const PetscScalar* PETSC_RESTRICT r, PetscScalar* PETSC_RESTRICT p, PetscReal sums[4]) {
  PetscReal uu = 0.0, dd = 0.0, pp = 0.0, dr = 0.0;
  for (PetscInt i = 0; i < n; ++i) {
    u[i] -= lambda * du[i];
    uu += PetscRealPart(u[i] * PetscConj(u[i]));
    dd += PetscRealPart(du[i] * PetscConj(du[i]));
    if constexpr (withEnergy) dr += PetscRealPart(du[i] * PetscConj(r[i]));
    if constexpr (withOffset) {
      p[i] += lambda * du[i];
      pp += PetscRealPart(p[i] * PetscConj(p[i]));
    }
  }
  sums[0] = uu;
  sums[1] = dd;
  sums[2] = pp;
  sums[3] = dr;
}

// X -= lambda Y in place, and |X|, |Y| (2-norms) from the same pass (memory-bound: SNES's basic
// line search writes W = X - lambda Y, reads both for the norms and copies W back to X). With an
// offset (X_a - X before the step; null: none) also offset += lambda Y and *offsetNorm = |offset|,
// |X_a - X| of the new iterate; with F (the residual before the step; null: none) also
// *energy = lambda |Y . F|; all in that pass and one reduction.
PetscErrorCode updateInPlace(Vec X, Vec Y, Vec F, PetscReal lambda, Vec offset, PetscReal* xnorm, PetscReal* ynorm,
                             PetscReal* offsetNorm, PetscReal* energy) {
  PetscInt n;
  PetscScalar *x, *p = nullptr;
  const PetscScalar *y, *f = nullptr;
  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(X, &n));
  PetscCall(VecGetArray(X, &x));
  PetscCall(VecGetArrayRead(Y, &y));
  if (F) PetscCall(VecGetArrayRead(F, &f));
  if (offset) PetscCall(VecGetArray(offset, &p));
  PetscReal sums[4], global[4];
  if (offset && F) stepLoop<true, true>(n, lambda, x, y, f, p, sums);
  else if (offset) stepLoop<true, false>(n, lambda, x, y, f, p, sums);
  else if (F) stepLoop<false, true>(n, lambda, x, y, f, p, sums);
  else stepLoop<false, false>(n, lambda, x, y, f, p, sums);
  PetscCall(PetscLogFlops((6.0 + (offset ? 3.0 : 0.0) + (F ? 2.0 : 0.0)) * n));
  if (offset) PetscCall(VecRestoreArray(offset, &p));
  if (F) PetscCall(VecRestoreArrayRead(F, &f));
  PetscCall(VecRestoreArrayRead(Y, &y));
  PetscCall(VecRestoreArray(X, &x));
  PetscCallMPI(MPI_Allreduce(sums, global, 4, MPIU_REAL, MPIU_SUM, PetscObjectComm(reinterpret_cast<PetscObject>(X))));
  *xnorm = std::sqrt(global[0]);
  *ynorm = std::sqrt(global[1]);
  if (offset) *offsetNorm = std::sqrt(global[2]);
  *energy = std::abs(lambda * global[3]);
  PetscFunctionReturn(0);
}

// SNESLINESEARCHBASIC (the full step X - lambda Y, here in place) without the residual at the new
// iterate when the test below will accept it on its step alone: the residual would only be
// discarded.
PetscErrorCode fullStep(SNESLineSearch ls, void* ctx) {
  auto* floor = static_cast<NewtonFloor*>(ctx);
  SNES snes;
  Vec X, F, Y;
  PetscReal xnorm, fnorm, ynorm, lambda, stol;
  PetscInt it;
  PetscFunctionBeginUser;
  PetscCall(SNESLineSearchGetSNES(ls, &snes));
  PetscCall(SNESLineSearchGetVecs(ls, &X, &F, &Y, nullptr, nullptr));
  PetscCall(SNESLineSearchGetNorms(ls, &xnorm, &fnorm, &ynorm));
  PetscCall(SNESLineSearchGetLambda(ls, &lambda));
  PetscCall(SNESLineSearchSetReason(ls, SNES_LINESEARCH_SUCCEEDED));
  PetscReal energy = 0.0;
  PetscCall(updateInPlace(X, Y, floor->energyTest ? F : nullptr, lambda, floor->offset, &xnorm, &ynorm,
                          &floor->offsetStep, &energy));
  PetscCall(SNESGetIterationNumber(snes, &it));
  PetscCall(SNESGetTolerances(snes, nullptr, nullptr, &stol, nullptr, nullptr));
  if (floor->energyTest) {  // the correction of iteration it + 1
    floor->previousEnergy = it == 0 ? 0.0 : floor->energy;
    floor->energy = energy;
    if (it == 0) floor->firstEnergy = energy;
    floor->energyIteration = it + 1;
  }
  // the test of iteration it + 1 sees |R| of this iterate (fnorm <= fnorm0 lets it accept)
  const bool accepted = floor->energyTest
                            ? energyConverged(*floor, it + 1)
                            : floor->iteration == it && floor->fnorm <= floor->fnorm0 &&
                                  stepConverged(*floor, it + 1, floor->step, ynorm, xnorm, stol);
  if (!accepted) {
    PetscBool domainError;
    PetscCall(SNESComputeFunction(snes, X, F));
    PetscCall(SNESGetFunctionDomainError(snes, &domainError));
    if (domainError) {  // back to the last iterate (to round-off), as a failed line search leaves it
      PetscCall(VecAXPY(X, lambda, Y));
      if (floor->offset) PetscCall(VecAXPY(floor->offset, -lambda, Y));
      PetscCall(SNESLineSearchSetReason(ls, SNES_LINESEARCH_FAILED_DOMAIN));
      PetscFunctionReturn(0);
    }
    PetscCall(VecNorm(F, NORM_2, &fnorm));
  }
  PetscCall(SNESLineSearchSetNorms(ls, xnorm, fnorm, ynorm));
  PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode useFullNewtonStep(SNES snes, NewtonFloor* floor) {
  SNESLineSearch ls;
  PetscFunctionBeginUser;
  PetscCall(SNESGetLineSearch(snes, &ls));
  PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHSHELL));
  PetscCall(SNESLineSearchShellSetUserFunc(ls, fullStep, floor));
  PetscFunctionReturn(0);
}

PetscErrorCode roundoffFloorConvergence(SNES snes, PetscInt it, PetscReal xnorm, PetscReal snorm, PetscReal fnorm,
                                        SNESConvergedReason* reason, void* ctx) {
  PetscFunctionBeginUser;
  auto* floor = static_cast<NewtonFloor*>(ctx);
  if (it == 0) {
    floor->fnorm0 = fnorm;
    floor->step = floor->previousStep = floor->firstStep = 0.0;
    floor->offsetStep = -1.0;  // set by the line search (fullStep) if there is an offset
    floor->energyIteration = -1;  // set by the line search (fullStep) with the energy test
  } else {
    floor->previousStep = floor->step;
    floor->step = snorm;
    if (it == 1) floor->firstStep = snorm;
  }
  floor->fnorm = fnorm;
  floor->iteration = it;
  PetscCall(SNESConvergedDefault(snes, it, xnorm, snorm, fnorm, reason, nullptr));
  if (floor->energyTest && floor->energyIteration == it) {
    // statics with this file's line search: the residual tests, the energy test, never the step test
    if (*reason == SNES_CONVERGED_SNORM_RELATIVE) *reason = SNES_CONVERGED_ITERATING;
    if (*reason == SNES_CONVERGED_ITERATING && energyConverged(*floor, it)) *reason = SNES_CONVERGED_SNORM_RELATIVE;
    if (!std::isfinite(fnorm)) *reason = SNES_DIVERGED_FNORM_NAN;
    PetscFunctionReturn(0);
  }
  PetscReal stol;
  PetscCall(SNESGetTolerances(snes, nullptr, nullptr, &stol, nullptr, nullptr));
  if (*reason == SNES_CONVERGED_ITERATING && stepConverged(*floor, it, floor->previousStep, snorm, xnorm, stol))
    *reason = SNES_CONVERGED_SNORM_RELATIVE;
  // (SNESConvergedDefault's own |du| < stol |u| included)
  if (*reason == SNES_CONVERGED_SNORM_RELATIVE && fnorm > floor->fnorm0) *reason = SNES_CONVERGED_ITERATING;
  if (*reason > 0 && !keptMatrixConverged(*floor, it, snorm, xnorm))
    *reason = SNES_CONVERGED_ITERATING;
  if (!std::isfinite(fnorm)) *reason = SNES_DIVERGED_FNORM_NAN;
  PetscFunctionReturn(0);
}

}  // namespace strand::solvers
