// BDF with a readable history, fixed or adaptive step (StrandBdf.hpp).
#include "strand/solvers/StrandBdf.hpp"
#include "strand/math/Lagrange.hpp"

#include <petsc/private/tsimpl.h>

#include <algorithm>

namespace strand::solvers {

namespace {

constexpr size_t kKeep = 7;  // states kept: order 5 needs 5, its predictor 6, plus the half step

struct BdfData {
  PetscInt order = 2;
  PetscInt k = 1, steps = 0;       // current order, steps since the start
  PetscInt stageOrder = 1;         // the order of the stage being solved (error estimate)
  std::vector<PetscReal> times;    // most recent first (after the start the half step is last)
  std::vector<Vec> states;
  PetscReal stageTime = 0.0, shift = 0.0;
  Vec V0 = nullptr, Ydot = nullptr;  // y' = shift y + V0 at the stage
};

BdfData* dataOf(TS ts) { return static_cast<BdfData*>(ts->data); }

PetscErrorCode checkType(TS ts) {
  PetscBool match;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(ts), kTsStrandBdf, &match));
  PetscCheck(match, PetscObjectComm(reinterpret_cast<PetscObject>(ts)), PETSC_ERR_ARG_WRONG, "TS is not of type %s",
             kTsStrandBdf);
  PetscFunctionReturn(0);
}

PetscErrorCode snesFunction(SNES, Vec Y, Vec F, TS ts) {
  BdfData* d = dataOf(ts);
  PetscFunctionBeginUser;
  PetscCall(VecWAXPY(d->Ydot, d->shift, Y, d->V0));
  PetscCall(TSComputeIFunction(ts, d->stageTime, Y, d->Ydot, F, PETSC_FALSE));
  PetscFunctionReturn(0);
}

PetscErrorCode snesJacobian(SNES, Vec Y, Mat J, Mat P, TS ts) {
  BdfData* d = dataOf(ts);
  PetscFunctionBeginUser;
  PetscCall(VecWAXPY(d->Ydot, d->shift, Y, d->V0));
  PetscCall(TSComputeIJacobian(ts, d->stageTime, Y, d->Ydot, d->shift, J, P, PETSC_FALSE));
  PetscFunctionReturn(0);
}

// One BDF solve at t1 on the nodes t1 and the first k history times; Y holds the predictor and
// returns the solution. *ok: Newton converged (TSAdaptCheckStage counts the failures).
PetscErrorCode solveStage(TS ts, PetscReal t1, PetscInt k, Vec Y, PetscBool* ok) {
  BdfData* d = dataOf(ts);
  PetscFunctionBeginUser;
  std::vector<PetscReal> T{t1};
  for (PetscInt j = 0; j < k && j < static_cast<PetscInt>(d->times.size()); ++j) T.push_back(d->times[j]);
  const std::vector<double> c = math::lagrangeDerivativeAtFirst(T);
  PetscCall(VecSet(d->V0, 0.0));
  PetscCall(VecMAXPY(d->V0, static_cast<PetscInt>(T.size()) - 1, c.data() + 1, d->states.data()));
  d->shift = c[0];
  d->stageTime = t1;
  PetscCall(TSPreStage(ts, t1));
  PetscCall(SNESSolve(ts->snes, nullptr, Y));
  PetscInt nits, lits;
  PetscCall(SNESGetIterationNumber(ts->snes, &nits));
  PetscCall(SNESGetLinearSolveIterations(ts->snes, &lits));
  ts->snes_its += nits;
  ts->ksp_its += lits;
  PetscCall(TSPostStage(ts, t1, 0, &Y));
  PetscCall(TSAdaptCheckStage(ts->adapt, ts, t1, Y, ok));
  PetscFunctionReturn(0);
}

PetscErrorCode push(BdfData* d, PetscReal t, Vec y, bool front) {
  PetscFunctionBeginUser;
  Vec copy;
  PetscCall(VecDuplicate(y, &copy));
  PetscCall(VecCopy(y, copy));
  d->times.insert(front ? d->times.begin() : d->times.end(), t);
  d->states.insert(front ? d->states.begin() : d->states.end(), copy);
  while (d->states.size() > kKeep) {
    PetscCall(VecDestroy(&d->states.back()));
    d->states.pop_back();
    d->times.pop_back();
  }
  PetscFunctionReturn(0);
}

PetscErrorCode clearHistory(BdfData* d) {
  PetscFunctionBeginUser;
  for (Vec& v : d->states) PetscCall(VecDestroy(&v));
  d->states.clear();
  d->times.clear();
  PetscFunctionReturn(0);
}

// The weighted local error of the stage y_{n+1} = ts->vec_sol at stageTime (StrandBdf.hpp; as
// TSEvaluateWLTE_BDF).
PetscErrorCode evaluateWlte(TS ts, NormType norm, PetscInt* order, PetscReal* wlte) {
  BdfData* d = dataOf(ts);
  PetscFunctionBeginUser;
  const PetscInt k = std::min<PetscInt>(d->stageOrder, static_cast<PetscInt>(d->states.size()) - 1);
  std::vector<PetscReal> T{d->stageTime};
  T.insert(T.end(), d->times.begin(), d->times.begin() + k + 1);
  std::vector<double> a = math::lagrangeDerivativeAtFirst({T.begin(), T.end() - 1});
  const std::vector<double> b = math::lagrangeDerivativeAtFirst(T);
  a.push_back(0.0);
  std::vector<PetscScalar> alpha(k + 2);
  for (PetscInt i = 0; i < k + 2; ++i) alpha[i] = (a[i] - b[i]) / a[0];
  Vec Y = d->Ydot;  // free outside the SNES solve
  PetscCall(VecCopy(ts->vec_sol, Y));
  PetscCall(VecScale(Y, 1.0 + alpha[0]));
  PetscCall(VecMAXPY(Y, k + 1, alpha.data() + 1, d->states.data()));
  PetscReal wa, wr;
  PetscCall(TSErrorWeightedNorm(ts, ts->vec_sol, Y, norm, wlte, &wa, &wr));
  if (order) *order = k + 1;
  PetscFunctionReturn(0);
}

// Back to the start's single state y_0 (a rejected first step drops its half step).
PetscErrorCode keepOnlyFirst(BdfData* d) {
  PetscFunctionBeginUser;
  while (d->states.size() > 1) {
    PetscCall(VecDestroy(&d->states.back()));
    d->states.pop_back();
    d->times.pop_back();
  }
  PetscFunctionReturn(0);
}

// One step, as TSStep_BDF: attempts until the adaptor accepts one (fixed step: the first attempt,
// or a failed Newton ends the run through TSAdaptCheckStage and TSSetMaxSNESFailures). The stage
// is solved in ts->vec_sol, which returns to y_n after a rejected attempt.
PetscErrorCode step(TS ts) {
  BdfData* d = dataOf(ts);
  PetscFunctionBeginUser;
  if (d->states.empty()) {  // a start: the initial state is the history
    PetscCall(push(d, ts->ptime, ts->vec_sol, true));
    d->k = 1;
    d->steps = 0;
  }
  PetscInt k = d->steps > 0 ? std::min(d->k + 1, d->order) : std::min<PetscInt>(2, d->order);
  Vec Y = ts->vec_sol;
  PetscBool accept = PETSC_TRUE;
  PetscInt rejections = 0;
  while (!ts->reason) {
    const PetscReal h = ts->time_step, t1 = ts->ptime + h;
    PetscBool ok = PETSC_TRUE;
    if (d->steps == 0) {  // backward Euler to t + h/2, kept as a history point
      PetscCall(keepOnlyFirst(d));
      PetscCall(VecCopy(d->states[0], Y));
      PetscCall(solveStage(ts, ts->ptime + 0.5 * h, 1, Y, &ok));
      if (ok) PetscCall(push(d, ts->ptime + 0.5 * h, Y, false));
    }
    if (ok) {  // predictor: the polynomial through the last min(kp + 1, history) states at t1
      const PetscInt kp = k - (accept ? 0 : 1);
      const size_t m = std::min<size_t>(kp + 1, d->times.size());
      const std::vector<double> c = math::lagrangeValues({d->times.begin(), d->times.begin() + m}, t1);
      PetscCall(VecSet(Y, 0.0));
      PetscCall(VecMAXPY(Y, static_cast<PetscInt>(m), c.data(), d->states.data()));
      d->stageOrder = k;
      PetscCall(solveStage(ts, t1, k, Y, &ok));
    }
    if (ok) {
      TSAdapt adapt;
      PetscReal next = h;
      PetscCall(TSGetAdapt(ts, &adapt));
      PetscCall(TSAdaptCandidatesClear(adapt));
      PetscCall(TSAdaptCandidateAdd(adapt, "strand_bdf", k, 1, 1.0, 1.0, PETSC_TRUE));
      PetscCall(TSAdaptChoose(adapt, ts, h, nullptr, &next, &accept));
      if (accept) {
        PetscCall(push(d, t1, Y, true));
        d->k = k;
        ++d->steps;
        ts->ptime += h;
        ts->time_step = next;
        PetscFunctionReturn(0);
      }
      ts->time_step = next;
    }
    // rejected (Newton failed: TSAdaptCheckStage cut the step or ended the run), back to y_n
    PetscCall(VecCopy(d->states[0], Y));
    ts->reject++;
    accept = PETSC_FALSE;
    if (!ts->reason && ++rejections > ts->max_reject && ts->max_reject >= 0) ts->reason = TS_DIVERGED_STEP_REJECTED;
  }
  if (d->steps == 0) PetscCall(keepOnlyFirst(d));
  PetscFunctionReturn(0);
}

PetscErrorCode setUp(TS ts) {
  BdfData* d = dataOf(ts);
  PetscFunctionBeginUser;
  for (Vec* v : {&d->V0, &d->Ydot})
    if (!*v) PetscCall(VecDuplicate(ts->vec_sol, v));
  PetscReal low, high;  // as TSSetUp_BDF: the step at most doubles
  PetscCall(TSGetAdapt(ts, &ts->adapt));
  PetscCall(TSAdaptGetClip(ts->adapt, &low, &high));
  PetscCall(TSAdaptSetClip(ts->adapt, low, std::min<PetscReal>(high, 2.0)));
  PetscCall(TSGetSNES(ts, &ts->snes));
  PetscFunctionReturn(0);
}

PetscErrorCode reset(TS ts) {
  BdfData* d = dataOf(ts);
  PetscFunctionBeginUser;
  PetscCall(clearHistory(d));
  PetscCall(VecDestroy(&d->V0));
  PetscCall(VecDestroy(&d->Ydot));
  PetscFunctionReturn(0);
}

PetscErrorCode destroy(TS ts) {
  PetscFunctionBeginUser;
  PetscCall(reset(ts));
  delete dataOf(ts);
  ts->data = nullptr;
  PetscCall(PetscObjectComposeFunction(reinterpret_cast<PetscObject>(ts), "TSBDFSetOrder_C", nullptr));
  PetscFunctionReturn(0);
}

PetscErrorCode setFromOptions(TS ts, PetscOptionItems* PetscOptionsObject) {
  BdfData* d = dataOf(ts);
  PetscFunctionBeginUser;
  PetscOptionsHeadBegin(PetscOptionsObject, "Strand fixed-step BDF options");
  PetscCall(PetscOptionsInt("-ts_strand_bdf_order", "Order of the BDF method", "StrandBdfSetOrder", d->order,
                            &d->order, nullptr));
  PetscOptionsHeadEnd();
  PetscCheck(d->order >= 1 && d->order <= 5, PetscObjectComm(reinterpret_cast<PetscObject>(ts)),
             PETSC_ERR_ARG_OUTOFRANGE, "BDF order %d not in 1..5", static_cast<int>(d->order));
  PetscFunctionReturn(0);
}

PetscErrorCode view(TS ts, PetscViewer viewer) {
  PetscBool ascii;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(viewer), PETSCVIEWERASCII, &ascii));
  if (ascii)
    PetscCall(PetscViewerASCIIPrintf(viewer, "  order %d, TSBDF's start (half step) and error estimate\n",
                                     static_cast<int>(dataOf(ts)->order)));
  PetscFunctionReturn(0);
}

PetscErrorCode create(TS ts) {
  PetscFunctionBeginUser;
  ts->ops->reset = reset;
  ts->ops->destroy = destroy;
  ts->ops->view = view;
  ts->ops->setup = setUp;
  ts->ops->setfromoptions = setFromOptions;
  ts->ops->step = step;
  ts->ops->evaluatewlte = evaluateWlte;
  ts->ops->snesfunction = snesFunction;
  ts->ops->snesjacobian = snesJacobian;
  ts->default_adapt_type = TSADAPTNONE;
  ts->usessnes = PETSC_TRUE;
  ts->data = new BdfData();
  PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode StrandBdfRegister() {
  static bool registered = false;
  PetscFunctionBeginUser;
  if (!registered) PetscCall(TSRegister(kTsStrandBdf, create));
  registered = true;
  PetscFunctionReturn(0);
}

PetscErrorCode StrandBdfSetOrder(TS ts, PetscInt order) {
  PetscFunctionBeginUser;
  PetscCall(checkType(ts));
  PetscCheck(order >= 1 && order <= 5, PetscObjectComm(reinterpret_cast<PetscObject>(ts)), PETSC_ERR_ARG_OUTOFRANGE,
             "BDF order %d not in 1..5", static_cast<int>(order));
  dataOf(ts)->order = order;
  PetscFunctionReturn(0);
}

PetscErrorCode StrandBdfGetHistory(TS ts, BdfHistory* h) {
  PetscFunctionBeginUser;
  PetscCall(checkType(ts));
  const BdfData* d = dataOf(ts);
  h->order = d->k;
  h->steps = d->steps;
  h->times = d->times;
  h->states = d->states;
  PetscFunctionReturn(0);
}

PetscErrorCode StrandBdfGetDerivative(TS ts, Vec ydot, PetscBool* known) {
  PetscFunctionBeginUser;
  PetscCall(checkType(ts));
  BdfData* d = dataOf(ts);
  // after an accepted step the history holds y_{n+1} first, then the k nodes its stage used
  *known = d->steps > 0 && static_cast<PetscInt>(d->states.size()) > d->k ? PETSC_TRUE : PETSC_FALSE;
  if (!*known) PetscFunctionReturn(0);
  const std::vector<double> c = math::lagrangeDerivativeAtFirst({d->times.begin(), d->times.begin() + d->k + 1});
  PetscCall(VecSet(ydot, 0.0));
  PetscCall(VecMAXPY(ydot, d->k + 1, c.data(), d->states.data()));
  PetscFunctionReturn(0);
}

PetscErrorCode StrandBdfSetHistory(TS ts, const BdfHistory& h) {
  PetscFunctionBeginUser;
  PetscCall(checkType(ts));
  BdfData* d = dataOf(ts);
  PetscCall(clearHistory(d));
  for (size_t j = 0; j < h.states.size(); ++j) PetscCall(push(d, h.times[j], h.states[j], false));
  d->k = h.order;
  d->steps = h.steps;
  PetscFunctionReturn(0);
}

}  // namespace strand::solvers
