// The Newton stopping test shared by statics and dynamics, and the iteration history it keeps
// (NewtonMatrixReuse reads it to decide when the Newton matrix is stale).
#pragma once
#include <petscsnes.h>

#include <algorithm>

namespace strand::solvers {

// Context of roundoffFloorConvergence: |R| at the first iterate, |q0| (the norm of the reference
// coordinates, which set the round-off of q = q0 + u), and the last two iterates' history.
struct NewtonFloor {
  PetscReal fnorm0 = 0.0, coordinateNorm = 0.0;
  PetscInt iteration = -1;                        // of the last test
  PetscReal step = 0.0, previousStep = 0.0;       // |du| of the last two Newton corrections
  PetscReal fnorm = 0.0;                          // |R| after the last one
  PetscReal firstStep = 0.0;                      // |du_1| (see offset), the first correction of this solve
  // Set by the dynamic Jacobian callback at every iterate (NewtonMatrixReuse's decision): the next
  // correction comes from a kept matrix. Such a correction is accepted only if it is itself at most
  // keptTolerance |du_1| or at round-off (the .cpp says why).
  bool keptMatrix = false;
  PetscReal keptTolerance = 0.0;  // 0 switches that rule off (statics)
  // When Newton starts elsewhere than at the constant-acceleration predictor X_a (a dynamic step from
  // X0 or X0 + h V0): X_a minus the start, set by the Jacobian callback at every iterate
  // (GeneralizedAlphaGetPredictorOffset); null otherwise. The line search advances it to X_a - X_k
  // for the current iterate X_k. The reference of that rule is then min(|du_1|, |X_k - X_a|):
  // |X_k - X_a| tends to the local error, where |du_1| is the start's error, O(h) from X0.
  // (offsetStep: |X_k - X_a|, -1 if there is none or another line search runs.)
  Vec offset = nullptr;
  PetscReal offsetStep = -1.0;
  // Statics (energyTest): the error of an iterate is measured by the energy of the Newton correction
  // that follows it, e_k = |du_k . R(q_{k-1})| = du_k^T J du_k (the squared Newton decrement), which
  // does not depend on how stiff a direction is (|R| and |du| each do: an axial residual of 1e3 N
  // with a tip error of 1e-8, or a step of 1e-9 with a bending error of 1e-5). The test, instead of
  // the step test: e_k <= energyTolerance e_ref, or, at the round-off floor, e_k <= floorTolerance e_ref
  // while e no longer falls (the .cpp says why). The line search (useFullNewtonStep) computes e_k.
  bool energyTest = false;
  PetscReal energyTolerance = 1e-20, floorTolerance = 1e-12;
  PetscInt energyIteration = -1;                           // the iteration whose correction e is
  PetscReal energy = 0.0, previousEnergy = 0.0, firstEnergy = 0.0;
  PetscReal energyScale = 0.0;  // the strain energy at the start of the solve (set by the caller)
  // The reference of the energy test: e_1, or the strain energy when larger (a solve whose load
  // hardly changes, a sweep point from a good predictor: e_1 is then round-off itself).
  PetscReal energyReference() const { return std::max(firstEnergy, energyScale); }
  PetscReal energyRatio() const { return energyReference() > 0.0 ? energy / energyReference() : 0.0; }
  // The contraction of the last two corrections, theta = |du_k| / |du_{k-1}| (0 before two are known).
  PetscReal contraction() const { return iteration >= 2 && previousStep > 0.0 ? step / previousStep : 0.0; }
};

// SNES convergence test (ctx: a NewtonFloor): SNESConvergedDefault, plus a test on the Newton
// correction against the coordinates that stops at the residual's round-off floor, and for a
// correction from a kept matrix the test against the first correction (the .cpp says why).
PetscErrorCode roundoffFloorConvergence(SNES snes, PetscInt it, PetscReal xnorm, PetscReal snorm, PetscReal fnorm,
                                        SNESConvergedReason* reason, void* ctx);

// The full Newton step of SNESLINESEARCHBASIC as a shell line search that skips the residual at
// the new iterate when roundoffFloorConvergence (ctx floor) will accept that iterate on its step
// test alone: the accepted solution is the same, one residual per solve cheaper (the last
// iteration's reported |R| is then the one before it). -<prefix>snes_linesearch_type overrides it.
PetscErrorCode useFullNewtonStep(SNES snes, NewtonFloor* floor);

}  // namespace strand::solvers
