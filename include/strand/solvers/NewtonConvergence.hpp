// The Newton stopping test shared by statics and dynamics, and the iteration history it keeps
// (NewtonMatrixReuse reads it to decide when the Newton matrix is stale).
#pragma once
#include <petscsnes.h>

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
