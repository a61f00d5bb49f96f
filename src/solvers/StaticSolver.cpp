#include "strand/solvers/StaticSolver.hpp"
#include "strand/solvers/InterfaceSchur.hpp"
#include "strand/solvers/ModalSolver.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>


namespace strand::solvers {

PetscErrorCode setDirectSolverDefaults(KSP ksp, bool saddlePoint, bool regularInterior) {
  PetscFunctionBeginUser;
  PC pc;
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(InterfaceSchurRegister());  // -<prefix>pc_type strand_interface_schur works everywhere
  if (!saddlePoint || regularInterior) {
    // Per-rank banded LU plus the interface Schur complement (InterfaceSchur.hpp): at 1e5 elements
    // on two ranks ~20 times faster solves than MUMPS; on one rank (no interface) the banded LU of
    // a chain, 5 % faster steps than PETSc's LU at 1e3 and 1e4 elements, and PETSc's LU with RCM
    // ordering for any other matrix (docs/performance.md).
    PetscCall(InterfaceSchurRegister());
    PetscCall(PCSetType(pc, kPcInterfaceSchur));
    PetscFunctionReturn(0);
  }
  PetscCall(PCSetType(pc, PCLU));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscFunctionReturn(0);
}

StaticSolver::StaticSolver(assembly::Assembler& assembler, int loadSteps) : _asm(assembler), _loadSteps(loadSteps) {
  const model::DofMap& dofs = assembler.dofs();
  PetscCallAbort(dofs.comm(), dofs.createMatrix(&_J, "static_"));
  PetscCallAbort(dofs.comm(), dofs.createVector(&_R));  // the assembler sums into it in place
  PetscCallAbort(dofs.comm(), SNESCreate(dofs.comm(), &_snes));
  PetscCallAbort(dofs.comm(), SNESSetOptionsPrefix(_snes, "static_"));
  PetscCallAbort(dofs.comm(), SNESSetFunction(_snes, _R, formFunction, this));
  PetscCallAbort(dofs.comm(), SNESSetJacobian(_snes, _J, _J, formJacobian, this));
  PetscCallAbort(dofs.comm(), SNESSetTolerances(_snes, PETSC_DEFAULT, 1e-10, PETSC_DEFAULT, 50, PETSC_DEFAULT));
  // Full Newton steps, no divergence test: the linear predictor of a position-based beam stretches
  // it, so the residual norm first grows; a backtracking line search on ||R|| then stalls at
  // steps of 1e-3 (measured on the elastica tests). Robustness comes from load-step cutbacks.
  PetscCallAbort(dofs.comm(), SNESSetDivergenceTolerance(_snes, -1.0));
  _floor.coordinateNorm = assembler.coordinateNorm();
  _floor.energyTest = true;  // converged means converged for any EA/EI (NewtonConvergence.cpp)
  PetscCallAbort(dofs.comm(), SNESSetConvergenceTest(_snes, roundoffFloorConvergence, &_floor, nullptr));
  PetscCallAbort(dofs.comm(), useFullNewtonStep(_snes, &_floor));  // no residual the step test discards
  KSP ksp;
  PetscCallAbort(dofs.comm(), SNESGetKSP(_snes, &ksp));
  PetscCallAbort(dofs.comm(), setDirectSolverDefaults(ksp, assembler.hasConstraints()));
  _flow = assembler.hasVariableMass() && ModalSolver::materialFlows(assembler);
  if (_flow) {
    PetscCallAbort(dofs.comm(), VecDuplicate(_R, &_V0));
    PetscCallAbort(dofs.comm(), VecDuplicate(_R, &_A0));
    PetscCallAbort(dofs.comm(), VecDuplicate(_R, &_F));
    PetscCallAbort(dofs.comm(), VecSet(_V0, 0.0));
    PetscCallAbort(dofs.comm(), VecSet(_A0, 0.0));
    PetscCallAbort(dofs.comm(), assembler.prescribedMotion(0.0, nullptr, _V0, nullptr));  // the material rates
    PetscCallAbort(dofs.comm(), dofs.createMatrix(&_Kq, "static_"));  // J's type: MatAXPY adds it fast
  }
}

StaticSolver::~StaticSolver() {
  SNESDestroy(&_snes);
  MatDestroy(&_J);
  MatDestroy(&_Kq);
  for (Vec* v : {&_R, &_V0, &_A0, &_F}) VecDestroy(v);
}

PetscErrorCode StaticSolver::setFromOptions() {
  PetscFunctionBeginUser;
  PetscCall(SNESSetFromOptions(_snes));
  PetscCall(PetscOptionsGetReal(nullptr, "static_", "-newton_energy_rtol", &_floor.energyTolerance, nullptr));
  PetscFunctionReturn(0);
}

PetscErrorCode StaticSolver::view(PetscViewer viewer) const {
  PetscFunctionBeginUser;
  PetscCall(SNESView(_snes, viewer));
  PetscFunctionReturn(0);
}

PetscErrorCode StaticSolver::formFunction(SNES, Vec X, Vec R, void* ctx) {
  PetscFunctionBeginUser;
  auto* self = static_cast<StaticSolver*>(ctx);
  PetscCall(self->_asm.staticResidual(X, self->_loadFactor, R));
  if (self->_flow) {  // the steady flow's inertia at full speed (not a load: not stepped)
    PetscCall(VecSet(self->_F, 0.0));
    PetscCall(self->_asm.addInertia(X, self->_V0, self->_A0, self->_F));
    PetscCall(self->_asm.zeroSupportedRows(self->_F));
    PetscCall(VecAXPY(R, 1.0, self->_F));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode StaticSolver::formJacobian(SNES, Vec X, Mat J, Mat, void* ctx) {
  PetscFunctionBeginUser;
  auto* self = static_cast<StaticSolver*>(ctx);
  PetscCall(self->_asm.staticJacobian(X, self->_loadFactor, J));
  if (self->_flow) {  // dF/dX at the flow's rates (supported rows and columns left out)
    PetscCall(self->_asm.inertiaJacobian(X, self->_V0, self->_A0, 0.0, 0.0, self->_Kq));
    PetscCall(MatAXPY(J, 1.0, self->_Kq, SUBSET_NONZERO_PATTERN));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode StaticSolver::solve(Vec X, const StepCallback& onStep, std::string* failure) {
  PetscFunctionBeginUser;
  Vec accepted;
  PetscCall(VecDuplicate(X, &accepted));
  PetscCall(VecCopy(X, accepted));
  const PetscReal nominal = 1.0 / _loadSteps;
  PetscReal increment = nominal, lambda = 0.0;
  int step = 0, cutbacks = 0;
  failure->clear();
  _stopped = false;
  while (lambda < 1.0 - 1e-14) {
    _loadFactor = std::min(1.0, lambda + increment);
    PetscCall(_asm.strainEnergy(X, &_floor.energyScale));  // the energy test's scale (NewtonFloor)
    PetscCall(SNESSolve(_snes, nullptr, X));
    SNESConvergedReason reason;
    PetscCall(SNESGetConvergedReason(_snes, &reason));
    if (reason > 0) {
      lambda = _loadFactor;
      StaticStep info;
      info.step = ++step;
      info.loadFactor = lambda;
      PetscCall(SNESGetIterationNumber(_snes, &info.newtonIterations));
      PetscCall(SNESGetFunctionNorm(_snes, &info.residualNorm));
      info.energyRatio = _floor.energyIteration >= 0 ? _floor.energyRatio() : -1.0;
      PetscCall(VecCopy(X, accepted));
      if (onStep) PetscCall(onStep(info, X));
      cutbacks = 0;
      increment = std::min(nominal, 2.0 * increment);
      if (_stopCheck && lambda < 1.0 - 1e-14) {  // every rank stops after the same load step
        int stop = _stopCheck() ? 1 : 0;
        PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &stop, 1, MPI_INT, MPI_MAX, _asm.dofs().comm()));
        if (stop) {
          _stopped = true;
          break;
        }
      }
      continue;
    }
    // failed: restore the last accepted state and halve the increment
    PetscCall(VecCopy(accepted, X));
    if (++cutbacks > kMaxCutbacks) {
      std::ostringstream msg;
      msg << "static solve diverged at load step " << step + 1 << " (load factor " << _loadFactor
          << ", last converged " << lambda << "): Newton " << SNESConvergedReasons[reason] << " after "
          << kMaxCutbacks << " halvings of the load increment. Try more `static: {load_steps: N}`, check"
          << " supports (a free rigid-body motion makes the tangent singular), or add -static_snes_monitor.";
      *failure = msg.str();
      break;
    }
    increment *= 0.5;
  }
  PetscCall(VecDestroy(&accepted));
  PetscFunctionReturn(0);
}

}  // namespace strand::solvers
