// Dynamics: the state a checkpoint needs to continue a run (Dynamics.hpp, ResumeState).
#include "strand/solvers/AdamsBashforthMoulton.hpp"
#include "strand/solvers/Dynamics.hpp"
#include "strand/solvers/StrandBdf.hpp"
#include "strand/solvers/GeneralizedAlpha.hpp"

#include <sstream>

namespace strand::solvers {

PetscErrorCode Dynamics::saveState(ResumeState* s) {
  PetscFunctionBeginUser;
  PetscReal t;
  PetscInt step;
  PetscCall(TSGetTime(_ts, &t));
  PetscCall(TSGetStepNumber(_ts, &step));
  s->time = t;
  s->step = static_cast<int>(step);
  s->last = _last;
  s->e0 = _e0;
  s->energyScale = _energyScale;
  s->lastDampingPower = _lastDampingPower;
  s->lastSupportPower = _lastSupportPower;
  s->lastLoadPower = _lastLoadPower;
  s->A = s->a = nullptr;
  PetscCall(_asm.contactHistory(s->contactHistory, &s->contactTime));
  PetscBool ours = PETSC_FALSE;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(_ts), kTsGeneralizedAlpha, &ours));
  s->newtonStart = -1;
  if (ours) {
    PetscInt which;
    PetscCall(GeneralizedAlphaGetState(_ts, &s->A, &s->a));
    PetscCall(GeneralizedAlphaGetPredictor(_ts, &which, nullptr));
    s->newtonStart = static_cast<int>(which);
    PetscInt cuts;
    PetscCall(GeneralizedAlphaGetStepCuts(_ts, &cuts, &s->nominalStep));
    s->stepCuts = static_cast<int>(cuts);
  }
  s->historyCount = 0;
  PetscBool abm = PETSC_FALSE;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(_ts), kTsAdamsBashforthMoulton, &abm));
  if (abm) {
    PetscInt count;
    PetscReal h;
    PetscCall(AdamsBashforthMoultonGetHistory(_ts, &count, &h, s->history.data()));
    s->historyCount = static_cast<int>(count);
    s->historyStep = h;
  }
  s->historyTimes.clear();
  PetscBool bdf = PETSC_FALSE;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(_ts), kTsStrandBdf, &bdf));
  if (bdf) {
    BdfHistory h;
    PetscCall(StrandBdfGetHistory(_ts, &h));
    s->historyCount = static_cast<int>(h.states.size());
    for (int i = 0; i < s->historyCount; ++i) s->history[i] = h.states[i];
    s->historyTimes = h.times;
    s->bdfOrder = static_cast<int>(h.order);
    s->bdfSteps = static_cast<int>(h.steps);
    PetscCall(TSGetTimeStep(_ts, &s->historyStep));  // adaptive: the controller's next step
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Dynamics::resumeFrom(const ResumeState& s) {
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&_resume.A));
  PetscCall(VecDestroy(&_resume.a));
  for (Vec& v : _resume.history) PetscCall(VecDestroy(&v));
  _resume = s;
  _resume.A = _resume.a = nullptr;
  for (int i = 0; i < static_cast<int>(_resume.history.size()); ++i) {
    _resume.history[i] = nullptr;
    if (i < s.historyCount) {
      PetscCall(VecDuplicate(s.history[i], &_resume.history[i]));
      PetscCall(VecCopy(s.history[i], _resume.history[i]));
    }
  }
  PetscCheck(_firstOrder || (s.A && s.a), _asm.dofs().comm(), PETSC_ERR_ARG_NULL,
             "resuming %s needs the accelerations A and a", _schemeName.c_str());
  if (!_firstOrder) {
    PetscCall(VecDuplicate(s.A, &_resume.A));
    PetscCall(VecDuplicate(s.a, &_resume.a));
    PetscCall(VecCopy(s.A, _resume.A));
    PetscCall(VecCopy(s.a, _resume.a));
  }
  _asm.restoreContactHistory(s.contactHistory, s.contactTime);
  _resuming = true;
  PetscFunctionReturn(0);
}

bool Dynamics::exactRestart() const {
  PetscBool alpha2 = PETSC_FALSE, bdf = PETSC_FALSE;
  PetscObjectTypeCompare(reinterpret_cast<PetscObject>(_ts), TSALPHA2, &alpha2);
  PetscObjectTypeCompare(reinterpret_cast<PetscObject>(_ts), TSBDF, &bdf);
  return !alpha2 && !bdf;  // TSALPHA2 and TSBDF (only by -dyn_ts_type) keep their state private
}

std::string Dynamics::signature() const {
  std::ostringstream o;
  o << _schemeName;
  if (_desc.integrator == model::Integrator::GeneralizedAlpha) o << " rho_inf " << _desc.rhoInf;
  if (_desc.integrator == model::Integrator::Hht) o << " alpha " << _desc.hhtAlpha;
  TSType type;
  TSGetType(_ts, &type);
  o << " / TS " << (type ? type : "?");
  return o.str();
}

}  // namespace strand::solvers
