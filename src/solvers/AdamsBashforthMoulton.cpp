// The "strand_abm4" TS (AdamsBashforthMoulton.hpp). Uses PETSc's private TS header the way PETSc's
// own implementations do (ts->ops, ts->data).
#include "strand/solvers/AdamsBashforthMoulton.hpp"

#include <petsc/private/tsimpl.h>

#include <algorithm>

namespace strand::solvers {

namespace {

struct AbmData {
  Vec f[4] = {};          // f_n, f_{n-1}, f_{n-2}, f_{n-3}
  Vec k[4] = {};          // RK4 stages; k[0] also holds f* of the corrector
  Vec y0 = nullptr, y1 = nullptr;  // start of the step, stage / predictor state
  int history = 0;        // valid entries of f (they were taken with step h)
  PetscReal h = 0.0;
  PetscInt lastStep = -1; // ts->steps of the last step taken (a restarted TS resets the history)
  Vec pending[4] = {};    // a history set before the first step (AdamsBashforthMoultonSetHistory)
  int pendingCount = 0;
  PetscReal pendingH = 0.0;
};

AbmData* dataOf(TS ts) { return static_cast<AbmData*>(ts->data); }

// Classical RK4 from (t, y0) with k1 = f_n given; result in ts->vec_sol.
PetscErrorCode rk4Step(TS ts, AbmData* d, PetscReal t, PetscReal h) {
  PetscFunctionBeginUser;
  PetscCall(VecCopy(d->f[0], d->k[0]));
  const PetscReal c[3] = {0.5, 0.5, 1.0};
  for (int s = 1; s < 4; ++s) {
    PetscCall(VecWAXPY(d->y1, c[s - 1] * h, d->k[s - 1], d->y0));
    PetscCall(TSComputeRHSFunction(ts, t + c[s - 1] * h, d->y1, d->k[s]));
  }
  const PetscScalar w[4] = {h / 6.0, h / 3.0, h / 3.0, h / 6.0};
  PetscCall(VecCopy(d->y0, ts->vec_sol));
  PetscCall(VecMAXPY(ts->vec_sol, 4, w, d->k));
  PetscFunctionReturn(0);
}

PetscErrorCode step(TS ts) {
  AbmData* d = dataOf(ts);
  PetscFunctionBeginUser;
  const PetscReal t = ts->ptime, h = ts->time_step;
  if (d->pendingCount > 0) {  // continue a checkpointed history
    for (int i = 0; i < d->pendingCount; ++i) PetscCall(VecCopy(d->pending[i], d->f[i]));
    d->history = d->pendingCount;
    d->h = d->pendingH;
    d->lastStep = ts->steps - 1;
    d->pendingCount = 0;
  }
  if (ts->steps == 0 || ts->steps != d->lastStep + 1 || h != d->h) d->history = 0;
  PetscCall(VecCopy(ts->vec_sol, d->y0));
  if (d->history == 0) {
    PetscCall(TSComputeRHSFunction(ts, t, d->y0, d->f[0]));
    d->history = 1;
    d->h = h;
  }
  PetscCall(TSPreStage(ts, t));
  if (d->history < 4) {
    PetscCall(rk4Step(ts, d, t, h));
  } else {
    const PetscScalar p[4] = {55.0 * h / 24.0, -59.0 * h / 24.0, 37.0 * h / 24.0, -9.0 * h / 24.0};
    PetscCall(VecCopy(d->y0, d->y1));
    PetscCall(VecMAXPY(d->y1, 4, p, d->f));
    PetscCall(TSComputeRHSFunction(ts, t + h, d->y1, d->k[0]));  // f*
    const PetscScalar c[3] = {19.0 * h / 24.0, -5.0 * h / 24.0, 1.0 * h / 24.0};
    PetscCall(VecCopy(d->y0, ts->vec_sol));
    PetscCall(VecMAXPY(ts->vec_sol, 3, c, d->f));
    PetscCall(VecAXPY(ts->vec_sol, 9.0 * h / 24.0, d->k[0]));
  }
  PetscCall(TSPostStage(ts, t + h, 0, &ts->vec_sol));
  PetscBool ok;
  PetscCall(TSAdaptCheckStage(ts->adapt, ts, t + h, ts->vec_sol, &ok));
  if (!ok) {
    PetscCall(VecCopy(d->y0, ts->vec_sol));  // the last accepted state
    ts->reason = TS_DIVERGED_STEP_REJECTED;
    PetscFunctionReturn(0);
  }
  // shift the history and evaluate f_{n+1}
  Vec oldest = d->f[3];
  for (int i = 3; i > 0; --i) d->f[i] = d->f[i - 1];
  d->f[0] = oldest;
  PetscCall(TSComputeRHSFunction(ts, t + h, ts->vec_sol, d->f[0]));
  d->history = std::min(d->history + 1, 4);
  d->lastStep = ts->steps;
  PetscReal next = h;
  PetscBool accept;
  PetscCall(TSAdaptChoose(ts->adapt, ts, h, nullptr, &next, &accept));
  ts->ptime += h;
  ts->time_step = next;
  PetscFunctionReturn(0);
}

PetscErrorCode setUp(TS ts) {
  AbmData* d = dataOf(ts);
  PetscFunctionBeginUser;
  PetscCall(TSCheckImplicitTerm(ts));
  for (Vec* v : {&d->f[0], &d->f[1], &d->f[2], &d->f[3], &d->k[0], &d->k[1], &d->k[2], &d->k[3], &d->y0, &d->y1})
    if (!*v) PetscCall(VecDuplicate(ts->vec_sol, v));
  d->history = 0;
  PetscFunctionReturn(0);
}

PetscErrorCode reset(TS ts) {
  AbmData* d = dataOf(ts);
  PetscFunctionBeginUser;
  for (Vec* v : {&d->f[0], &d->f[1], &d->f[2], &d->f[3], &d->k[0], &d->k[1], &d->k[2], &d->k[3], &d->y0, &d->y1,
                 &d->pending[0], &d->pending[1], &d->pending[2], &d->pending[3]})
    PetscCall(VecDestroy(v));
  d->history = 0;
  d->pendingCount = 0;
  PetscFunctionReturn(0);
}

PetscErrorCode destroy(TS ts) {
  PetscFunctionBeginUser;
  PetscCall(reset(ts));
  delete dataOf(ts);
  ts->data = nullptr;
  PetscFunctionReturn(0);
}

PetscErrorCode view(TS, PetscViewer viewer) {
  PetscBool ascii;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(viewer), PETSCVIEWERASCII, &ascii));
  if (ascii) PetscCall(PetscViewerASCIIPrintf(viewer, "  Adams-Bashforth-Moulton 4 (PECE), RK4 start\n"));
  PetscFunctionReturn(0);
}

PetscErrorCode create(TS ts) {
  PetscFunctionBeginUser;
  ts->ops->reset = reset;
  ts->ops->destroy = destroy;
  ts->ops->view = view;
  ts->ops->setup = setUp;
  ts->ops->step = step;
  ts->default_adapt_type = TSADAPTNONE;
  ts->usessnes = PETSC_FALSE;
  ts->data = new AbmData();
  PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode AdamsBashforthMoultonGetHistory(TS ts, PetscInt* count, PetscReal* h, Vec f[4]) {
  PetscFunctionBeginUser;
  PetscBool match;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(ts), kTsAdamsBashforthMoulton, &match));
  PetscCheck(match, PetscObjectComm(reinterpret_cast<PetscObject>(ts)), PETSC_ERR_ARG_WRONG, "TS is not %s",
             kTsAdamsBashforthMoulton);
  AbmData* d = dataOf(ts);
  *count = d->history;
  *h = d->h;
  for (int i = 0; i < 4; ++i) f[i] = d->f[i];
  PetscFunctionReturn(0);
}

PetscErrorCode AdamsBashforthMoultonSetHistory(TS ts, PetscInt count, PetscReal h, const Vec f[]) {
  PetscFunctionBeginUser;
  PetscBool match;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(ts), kTsAdamsBashforthMoulton, &match));
  PetscCheck(match && count >= 0 && count <= 4, PetscObjectComm(reinterpret_cast<PetscObject>(ts)), PETSC_ERR_ARG_WRONG,
             "%s: a history of 0..4 entries", kTsAdamsBashforthMoulton);
  AbmData* d = dataOf(ts);
  for (PetscInt i = 0; i < count; ++i) {
    if (!d->pending[i]) PetscCall(VecDuplicate(f[i], &d->pending[i]));
    PetscCall(VecCopy(f[i], d->pending[i]));
  }
  d->pendingCount = static_cast<int>(count);
  d->pendingH = h;
  PetscFunctionReturn(0);
}

PetscErrorCode AdamsBashforthMoultonRegister() {
  static bool registered = false;
  PetscFunctionBeginUser;
  if (!registered) PetscCall(TSRegister(kTsAdamsBashforthMoulton, create));
  registered = true;
  PetscFunctionReturn(0);
}

}  // namespace strand::solvers
