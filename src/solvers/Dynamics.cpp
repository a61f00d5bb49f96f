#include "strand/solvers/Dynamics.hpp"

#include <cmath>
#include <sstream>

#include "strand/solvers/StaticSolver.hpp"

namespace strand::solvers {


Dynamics::Dynamics(assembly::Assembler& assembler, const model::DynamicsDesc& desc) : _asm(assembler), _desc(desc) {
  const model::DofMap& dofs = assembler.dofs();
  MPI_Comm comm = dofs.comm();
  for (const model::Body& b : assembler.model().bodies())
    _damped = _damped || b.section.dampAxial != 0.0 || b.section.dampBending != 0.0;
  PetscCallAbort(comm, dofs.createMatrix(&_M, "dyn_mass_"));
  PetscCallAbort(comm, dofs.createMatrix(&_J, "dyn_"));
  PetscCallAbort(comm, assembler.massMatrix(_M));
  PetscCallAbort(comm, MatCreateVecs(_M, nullptr, &_fext));
  PetscCallAbort(comm, VecDuplicate(_fext, &_w1));
  PetscCallAbort(comm, VecDuplicate(_fext, &_w2));
  PetscCallAbort(comm, assembler.externalForce(_fext));

  PetscCallAbort(comm, TSCreate(comm, &_ts));
  PetscCallAbort(comm, TSSetOptionsPrefix(_ts, "dyn_"));
  PetscCallAbort(comm, TSSetType(_ts, TSALPHA2));
  PetscCallAbort(comm, TSSetI2Function(_ts, nullptr, formFunction, this));
  PetscCallAbort(comm, TSSetI2Jacobian(_ts, _J, _J, formJacobian, this));
  switch (desc.integrator) {
    case model::Integrator::Newmark: PetscCallAbort(comm, TSAlpha2SetParams(_ts, 1.0, 1.0, 0.5, 0.25)); break;
    case model::Integrator::Hht: {
      const double a = desc.hhtAlpha;
      PetscCallAbort(comm, TSAlpha2SetParams(_ts, 1.0, 1.0 - a, 0.5 + a, 0.25 * (1.0 + a) * (1.0 + a)));
      break;
    }
    default: PetscCallAbort(comm, TSAlpha2SetRadius(_ts, desc.rhoInf)); break;
  }
  PetscCallAbort(comm, TSSetTimeStep(_ts, desc.dt));
  PetscCallAbort(comm, TSSetMaxTime(_ts, desc.tEnd));
  PetscCallAbort(comm, TSSetMaxSteps(_ts, static_cast<PetscInt>(std::ceil(desc.tEnd / desc.dt - 1e-9)) + 1));
  PetscCallAbort(comm, TSSetExactFinalTime(_ts, TS_EXACTFINALTIME_MATCHSTEP));
  // fixed step: the first Newton failure ends the run with a message instead of a silent cut
  PetscCallAbort(comm, TSSetMaxSNESFailures(_ts, 1));
  PetscCallAbort(comm, TSSetErrorIfStepFails(_ts, PETSC_FALSE));
  TSAdapt adapt;
  PetscCallAbort(comm, TSGetAdapt(_ts, &adapt));
  PetscCallAbort(comm, TSAdaptSetType(adapt, TSADAPTNONE));
  PetscCallAbort(comm, TSMonitorSet(_ts, monitor, this, nullptr));

  SNES snes;
  SNESLineSearch ls;
  KSP ksp;
  PetscCallAbort(comm, TSGetSNES(_ts, &snes));
  PetscCallAbort(comm, SNESSetTolerances(snes, 0.0, 1e-10, 1e-12, 25, PETSC_DEFAULT));
  // as in statics: the residual has a round-off floor (StaticSolver.cpp)
  PetscCallAbort(comm, SNESSetConvergenceTest(snes, roundoffFloorConvergence, &_fnorm0, nullptr));
  PetscCallAbort(comm, SNESGetLineSearch(snes, &ls));
  PetscCallAbort(comm, SNESLineSearchSetType(ls, SNESLINESEARCHBASIC));
  PetscCallAbort(comm, SNESGetKSP(snes, &ksp));
  PetscCallAbort(comm, setDirectSolverDefaults(ksp, comm));
}

Dynamics::~Dynamics() {
  TSDestroy(&_ts);
  MatDestroy(&_M);
  MatDestroy(&_J);
  VecDestroy(&_fext);
  VecDestroy(&_w1);
  VecDestroy(&_w2);
}

const char* Dynamics::schemeName() const {
  switch (_desc.integrator) {
    case model::Integrator::Newmark: return "Newmark (average acceleration)";
    case model::Integrator::Hht: return "HHT-alpha";
    default: return "generalized-alpha";
  }
}

PetscErrorCode Dynamics::setFromOptions() {
  PetscFunctionBeginUser;
  PetscCall(TSSetFromOptions(_ts));
  PetscFunctionReturn(0);
}

// F = M A + f_int(U, V) - f_ext at the alpha point (supported rows: U).
PetscErrorCode Dynamics::formFunction(TS, PetscReal, Vec U, Vec V, Vec A, Vec F, void* ctx) {
  PetscFunctionBeginUser;
  auto* self = static_cast<Dynamics*>(ctx);
  PetscCall(self->_asm.residual(U, self->_damped ? V : nullptr, F));
  PetscCall(MatMultAdd(self->_M, A, F, F));
  PetscFunctionReturn(0);
}

PetscErrorCode Dynamics::formJacobian(TS, PetscReal, Vec U, Vec V, Vec, PetscReal shiftV, PetscReal shiftA, Mat J, Mat,
                                      void* ctx) {
  PetscFunctionBeginUser;
  auto* self = static_cast<Dynamics*>(ctx);
  PetscCall(self->_asm.dynamicJacobian(U, self->_damped ? V : nullptr, shiftV, shiftA, J));
  PetscFunctionReturn(0);
}

// v . f_d with the Kelvin-Voigt force f_d = f_int(u, v) - f_int(u, 0).
PetscErrorCode Dynamics::dampingPower(Vec X, Vec V, PetscReal* power) {
  PetscFunctionBeginUser;
  *power = 0.0;
  if (!_damped) PetscFunctionReturn(0);
  PetscCall(_asm.residual(X, V, _w1));
  PetscCall(_asm.residual(X, nullptr, _w2));
  PetscCall(VecAXPY(_w1, -1.0, _w2));
  PetscCall(VecDot(_w1, V, power));
  PetscFunctionReturn(0);
}

PetscErrorCode Dynamics::energies(Vec X, Vec V, DynamicsStep* s) {
  PetscFunctionBeginUser;
  PetscScalar vmv, fu;
  PetscCall(MatMult(_M, V, _w1));
  PetscCall(VecDot(_w1, V, &vmv));
  s->kinetic = 0.5 * vmv;
  PetscCall(_asm.strainEnergy(X, &s->strain));
  PetscCall(VecDot(_fext, X, &fu));
  s->potential = -fu;
  PetscFunctionReturn(0);
}

PetscErrorCode Dynamics::monitor(TS ts, PetscInt step, PetscReal t, Vec X, void* ctx) {
  PetscFunctionBeginUser;
  auto* self = static_cast<Dynamics*>(ctx);
  Vec V;
  PetscCall(TS2GetSolution(ts, nullptr, &V));
  DynamicsStep s;
  s.step = static_cast<int>(step);
  s.time = t;
  if (step > 0) {
    SNES snes;
    PetscCall(TSGetSNES(ts, &snes));
    PetscCall(SNESGetIterationNumber(snes, &s.newtonIterations));
  }
  PetscCall(self->energies(X, V, &s));
  PetscReal power;
  PetscCall(self->dampingPower(X, V, &power));
  s.dissipated = step > 0 ? self->_last.dissipated + 0.5 * (t - self->_last.time) * (power + self->_lastPower) : 0.0;
  self->_last = s;
  self->_lastPower = power;
  if (self->_onStep && *self->_onStep) PetscCall((*self->_onStep)(s, X, V));
  PetscFunctionReturn(0);
}

PetscErrorCode Dynamics::run(Vec X, Vec V, const StepCallback& onStep, std::string* failure) {
  PetscFunctionBeginUser;
  failure->clear();
  _onStep = &onStep;
  PetscCall(TSSetTime(_ts, 0.0));
  PetscCall(TSSetStepNumber(_ts, 0));
  PetscCall(TSSetTimeStep(_ts, _desc.dt));
  PetscCall(TS2SetSolution(_ts, X, V));
  PetscCall(TSSolve(_ts, X));
  TSConvergedReason reason;
  PetscCall(TSGetConvergedReason(_ts, &reason));
  if (reason < 0) {
    SNES snes;
    SNESConvergedReason sr;
    PetscCall(TSGetSNES(_ts, &snes));
    PetscCall(SNESGetConvergedReason(snes, &sr));
    std::ostringstream msg;
    msg << schemeName() << " stopped at t = " << _last.time << " s after step " << _last.step << " (dt " << _desc.dt
        << " s): Newton " << SNESConvergedReasons[sr] << " in the next step (" << TSConvergedReasons[reason]
        << "). Try a smaller dynamics.dt, rho_inf < 1 to damp the highest modes, or -dyn_snes_monitor.";
    *failure = msg.str();
  }
  _onStep = nullptr;
  PetscFunctionReturn(0);
}

}  // namespace strand::solvers
