// Dynamics: what a failed run's message says to try, and the highest frequency behind an explicit
// scheme's stability limit.
#include <cmath>

#include "strand/solvers/Dynamics.hpp"
#include "strand/solvers/InterfaceSchur.hpp"
#include "strand/solvers/Schemes.hpp"

namespace strand::solvers {

std::string Dynamics::failureHint(const DynamicsStep&) const {
  if (!_explicit) {  // the interface Schur PC's saddle-point probe (InterfaceSchur.hpp)
    SNES snes;
    KSP ksp;
    PC pc;
    PetscBool probeFailed = PETSC_FALSE;
    if (TSGetSNES(_ts, &snes) == 0 && SNESGetKSP(snes, &ksp) == 0 && KSPGetPC(ksp, &pc) == 0 &&
        InterfaceSchurProbeFailed(pc, &probeFailed) == 0 && probeFailed)
      return "The Newton matrix without its multiplier rows is nearly singular, so the banded solve with the "
             "multipliers on its interface is inexact (docs/architecture.md, decision 18). Factor it with MUMPS: "
             "-dyn_pc_type lu -dyn_pc_factor_mat_solver_type mumps.";
  }
  const bool undamped = _desc.integrator == model::Integrator::Newmark ||
                        (_desc.integrator == model::Integrator::GeneralizedAlpha && _desc.rhoInf >= 0.99);
  if (_constrained && undamped)
    return "Joints are index-3 constraints, and this member has no high-frequency damping (rho_inf = 1, like "
           "the trapezoidal rule): the error of the multipliers is not damped and grows (Arnold & Bruls 2007). "
           "Use rho_inf <= 0.9 (docs/user-guide.md, \"Joints\").";
  if (_constrained && _desc.integrator == model::Integrator::Bdf &&
      _desc.constraintForm == model::DynamicsDesc::ConstraintForm::Index3)
    return "constraint_form: index3 integrates the joints as index-3 constraints with the multipliers in the "
           "error norm: on index 3 the BDF error estimate of the multipliers does not fall with the step (Brenan, "
           "Campbell & Petzold 1996, Sec. 5.4), so the step controller shrinks the step without end. Use "
           "constraint_form: ggl (the default: the stabilized index-2 form, multipliers out of the error norm; "
           "docs/user-guide.md, \"Joints\").";
  if (_desc.integrator == model::Integrator::Bdf)
    return stabilityNote(_desc) + (_desc.adaptive ? "Try tighter rtol/atol, a smaller first dynamics.dt, or -dyn_snes_monitor."
                                                  : "Try a smaller dynamics.dt, adaptive: true, or -dyn_snes_monitor.");
  // (BDF returned above; the explicit schemes have no Newton)
  const std::string cuts = _desc.stepCuts >= 10 ? " (10 step cuts did not help)"
                           : _desc.stepCuts > 0 ? ", more dynamics.step_cuts (" + std::to_string(_desc.stepCuts) + " were allowed)"
                                                : ", dynamics.step_cuts: 3 (halve the step where Newton fails)";
  return "Try a smaller dynamics.dt" + cuts + ", rho_inf < 1 to damp the highest modes, "
         "-dyn_ts_strand_alpha_predictor displacement (fine, stiff meshes under suddenly applied loads; "
         "docs/performance.md), or -dyn_snes_monitor.";
}

// omega_max^2 = the largest eigenvalue of M^{-1} K at state X (free DOFs), by power iteration with
// the factored mass: a lower bound that the iteration approaches from below (an estimate for the
// failure message of an explicit scheme, not a verified number).
PetscErrorCode Dynamics::highestFrequency(Vec X, PetscReal* omega) {
  PetscFunctionBeginUser;
  PetscCall(_asm.dynamicJacobian(X, nullptr, 0.0, 0.0, 0.0, _J));  // K at the initial loads (unit rows at supports)
  Vec z, w;
  PetscCall(VecDuplicate(X, &z));
  PetscCall(VecDuplicate(X, &w));
  PetscCall(VecSetRandom(z, nullptr));
  PetscCall(_asm.zeroSupportedRows(z));
  PetscReal lambda = 0.0, norm;
  for (int k = 0; k < 200; ++k) {
    PetscCall(VecNormalize(z, &norm));
    PetscCall(MatMult(_J, z, w));
    PetscCall(_asm.zeroSupportedRows(w));
    PetscCall(KSPSolve(_massSolver, w, z));
    PetscCall(VecNorm(z, NORM_2, &lambda));
  }
  *omega = std::sqrt(lambda);
  PetscCall(VecDestroy(&z));
  PetscCall(VecDestroy(&w));
  PetscFunctionReturn(0);
}

}  // namespace strand::solvers
