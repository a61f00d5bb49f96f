#include "strand/ffr/HubBeamDynamics.hpp"

#include <cmath>
#include <sstream>

#include "strand/solvers/AdamsBashforthMoulton.hpp"
#include "strand/solvers/GeneralizedAlpha.hpp"
#include "strand/solvers/Schemes.hpp"

namespace strand::ffr {

namespace {

Eigen::VectorXd toEigen(Vec x, PetscInt offset, PetscInt n) {
  const PetscScalar* a;
  VecGetArrayRead(x, &a);
  Eigen::VectorXd v = Eigen::Map<const Eigen::VectorXd>(a + offset, n);
  VecRestoreArrayRead(x, &a);
  return v;
}

void toVec(const Eigen::VectorXd& v, Vec x, PetscInt offset) {
  PetscScalar* a;
  VecGetArray(x, &a);
  Eigen::Map<Eigen::VectorXd>(a + offset, v.size()) = v;
  VecRestoreArray(x, &a);
}

// dense Mat (column major, leading dimension = rows) <- Eigen (column major)
PetscErrorCode fillDense(Mat J, const Eigen::MatrixXd& m) {
  PetscFunctionBeginUser;
  PetscScalar* a;
  PetscCall(MatDenseGetArrayWrite(J, &a));
  Eigen::Map<Eigen::MatrixXd>(a, m.rows(), m.cols()) = m;
  PetscCall(MatDenseRestoreArrayWrite(J, &a));
  PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

std::string fmt(double v, int precision = 4) {
  std::ostringstream o;
  o.precision(precision);
  o << v;
  return o.str();
}

PetscErrorCode postStep(TS ts);

}  // namespace

HubBeamDynamics::HubBeamDynamics(const HubBeam& model, const model::DynamicsDesc& desc)
    : _model(model), _desc(desc), _n(model.size()) {
  using model::Integrator;
  _firstOrder = model::isFirstOrder(desc.integrator);
  _explicit = model::isExplicit(desc.integrator);
  _schemeName = solvers::schemeName(desc);
  if (model.driven()) {
    Eigen::MatrixXd M;
    model.mass(Eigen::VectorXd::Zero(_n), M);
    _massFactor.compute(M);
  }
  const MPI_Comm self = PETSC_COMM_SELF;
  PetscCallAbort(self, solvers::GeneralizedAlphaRegister());
  PetscCallAbort(self, solvers::AdamsBashforthMoultonRegister());
  PetscCallAbort(self, TSCreate(self, &_ts));
  PetscCallAbort(self, TSSetOptionsPrefix(_ts, "ffr_"));
  const PetscInt N = _firstOrder ? 2 * _n : _n;
  PetscCallAbort(self, MatCreateSeqDense(self, N, N, nullptr, &_J));
  if (_firstOrder) {
    PetscCallAbort(self, VecCreateSeq(self, 2 * _n, &_Y));
    if (desc.integrator == Integrator::Bdf) {
      PetscCallAbort(self, TSSetType(_ts, TSBDF));
      PetscCallAbort(self, TSBDFSetOrder(_ts, desc.bdfOrder));
      PetscCallAbort(self, TSSetIFunction(_ts, nullptr, iFunction, this));
      PetscCallAbort(self, TSSetIJacobian(_ts, _J, _J, iJacobian, this));
    } else {
      if (desc.integrator == Integrator::Rk4) {
        PetscCallAbort(self, TSSetType(_ts, TSRK));
        PetscCallAbort(self, TSRKSetType(_ts, TSRK4));
      } else {
        PetscCallAbort(self, TSSetType(_ts, solvers::kTsAdamsBashforthMoulton));
      }
      PetscCallAbort(self, TSSetRHSFunction(_ts, nullptr, rhsFunction, this));
    }
  } else {
    PetscCallAbort(self, VecCreateSeq(self, _n, &_X));
    PetscCallAbort(self, VecDuplicate(_X, &_V));
    PetscCallAbort(self, TSSetType(_ts, solvers::kTsGeneralizedAlpha));
    PetscCallAbort(self, TSSetI2Function(_ts, nullptr, i2Function, this));
    PetscCallAbort(self, TSSetI2Jacobian(_ts, _J, _J, i2Jacobian, this));
    const solvers::AlphaParams p = _params = solvers::alphaParams(desc);
    PetscCallAbort(self, solvers::GeneralizedAlphaSetParams(_ts, p.alphaM, p.alphaF, p.gamma, p.beta));
  }
  // the small-system path runs every fixed-step scheme; adaptive BDF needs TSBDF's error control
  _dense = !(desc.integrator == Integrator::Bdf && desc.adaptive);
  PetscCallAbort(self, solvers::configureTimeStepping(_ts, desc));
  PetscCallAbort(self, TSMonitorSet(_ts, monitor, this, nullptr));
  PetscCallAbort(self, TSSetApplicationContext(_ts, this));
  PetscCallAbort(self, TSSetPostStep(_ts, postStep));
  if (_explicit) return;
  SNES snes;
  SNESLineSearch ls;
  KSP ksp;
  PC pc;
  PetscCallAbort(self, TSGetSNES(_ts, &snes));
  PetscCallAbort(self, SNESSetTolerances(snes, newtonTolerance(), 1e-10, 1e-14, 25, PETSC_DEFAULT));
  // at least one Newton step: the predictor's residual can be below atol at small steps, and
  // accepting it unsolved lets a displacement error of atol / |K| per step accumulate (measured:
  // 1.2e-7 m of tip error after 3e5 steps). The driven hub is linear: one step solves it exactly.
  PetscCallAbort(self, SNESSetForceIteration(snes, PETSC_TRUE));
  PetscCallAbort(self, SNESGetLineSearch(snes, &ls));
  PetscCallAbort(self, SNESLineSearchSetType(ls, SNESLINESEARCHBASIC));
  PetscCallAbort(self, SNESGetKSP(snes, &ksp));
  PetscCallAbort(self, KSPSetType(ksp, KSPPREONLY));
  PetscCallAbort(self, KSPGetPC(ksp, &pc));
  PetscCallAbort(self, PCSetType(pc, PCLU));
}

HubBeamDynamics::~HubBeamDynamics() {
  TSDestroy(&_ts);
  MatDestroy(&_J);
  VecDestroy(&_X);
  VecDestroy(&_V);
  VecDestroy(&_Y);
}

PetscErrorCode HubBeamDynamics::setFromOptions() {
  PetscFunctionBeginUser;
  PetscCall(TSSetFromOptions(_ts));
  // -ffr_dense wins; otherwise PETSc options for this TS (-ffr_ts_*, -ffr_snes_*, ...) ask for the TS
  PetscBool dense = _dense ? PETSC_TRUE : PETSC_FALSE, set = PETSC_FALSE;
  PetscCall(PetscOptionsGetBool(nullptr, "ffr_", "-dense", &dense, &set));
  if (!set && _dense) {
    char* all = nullptr;
    PetscCall(PetscOptionsGetAll(nullptr, &all));
    const std::string options = all ? all : "";
    PetscCall(PetscFree(all));
    for (const char* p : {"-ffr_ts_", "-ffr_snes_", "-ffr_ksp_", "-ffr_pc_"})
      if (options.find(p) != std::string::npos) dense = PETSC_FALSE;
  }
  PetscCheck(!(dense && _desc.integrator == model::Integrator::Bdf && _desc.adaptive), PETSC_COMM_SELF, PETSC_ERR_SUP,
             "-ffr_dense: adaptive BDF runs on PETSc TS (TSBDF's error control); use a fixed step for the dense loop");
  _dense = dense;
  PetscFunctionReturn(0);
}

void HubBeamDynamics::acceleration(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                   Eigen::VectorXd& a) const {
  Eigen::VectorXd Q;
  _model.force(t, q, v, Q);
  if (_model.driven()) {
    a = _massFactor.solve(Q);
  } else {
    Eigen::MatrixXd M;
    _model.mass(q, M);
    a = M.ldlt().solve(Q);  // symmetric positive definite (kinetic energy)
  }
}

PetscErrorCode HubBeamDynamics::i2Function(TS, PetscReal t, Vec U, Vec V, Vec A, Vec F, void* ctx) {
  PetscFunctionBeginUser;
  auto* self = static_cast<HubBeamDynamics*>(ctx);
  const PetscInt n = self->_n;
  Eigen::VectorXd f;
  self->_model.residual(t, toEigen(U, 0, n), toEigen(V, 0, n), toEigen(A, 0, n), f);
  toVec(f, F, 0);
  PetscFunctionReturn(0);
}

PetscErrorCode HubBeamDynamics::i2Jacobian(TS, PetscReal t, Vec U, Vec V, Vec A, PetscReal sV, PetscReal sA, Mat J,
                                           Mat, void* ctx) {
  PetscFunctionBeginUser;
  auto* self = static_cast<HubBeamDynamics*>(ctx);
  const PetscInt n = self->_n;
  Eigen::MatrixXd m;
  self->_model.jacobian(t, toEigen(U, 0, n), toEigen(V, 0, n), toEigen(A, 0, n), sV, sA, m);
  PetscCall(fillDense(J, m));
  PetscFunctionReturn(0);
}

// BDF: F(y, y') = (q' - v, F(t, q, v, v'))
PetscErrorCode HubBeamDynamics::iFunction(TS, PetscReal t, Vec Y, Vec Ydot, Vec Fv, void* ctx) {
  PetscFunctionBeginUser;
  auto* self = static_cast<HubBeamDynamics*>(ctx);
  const PetscInt n = self->_n;
  const Eigen::VectorXd v = toEigen(Y, n, n);
  Eigen::VectorXd f;
  self->_model.residual(t, toEigen(Y, 0, n), v, toEigen(Ydot, n, n), f);
  toVec(toEigen(Ydot, 0, n) - v, Fv, 0);
  toVec(f, Fv, n);
  PetscFunctionReturn(0);
}

// [s I, -I; dF/dq, dF/dv + s dF/da]
PetscErrorCode HubBeamDynamics::iJacobian(TS, PetscReal t, Vec Y, Vec Ydot, PetscReal s, Mat J, Mat, void* ctx) {
  PetscFunctionBeginUser;
  auto* self = static_cast<HubBeamDynamics*>(ctx);
  const PetscInt n = self->_n;
  const Eigen::VectorXd q = toEigen(Y, 0, n), v = toEigen(Y, n, n), a = toEigen(Ydot, n, n);
  Eigen::MatrixXd dq, dva;
  self->_model.jacobian(t, q, v, a, 0.0, 0.0, dq);
  self->_model.jacobian(t, q, v, a, 1.0, s, dva);
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  m.topLeftCorner(n, n).diagonal().setConstant(s);
  m.topRightCorner(n, n).diagonal().setConstant(-1.0);
  m.bottomLeftCorner(n, n) = dq;
  m.bottomRightCorner(n, n) = dva - dq;
  PetscCall(fillDense(J, m));
  PetscFunctionReturn(0);
}

// explicit: y' = (v, M(q)^{-1} Q(t, q, v))
PetscErrorCode HubBeamDynamics::rhsFunction(TS, PetscReal t, Vec Y, Vec Fv, void* ctx) {
  PetscFunctionBeginUser;
  auto* self = static_cast<HubBeamDynamics*>(ctx);
  const PetscInt n = self->_n;
  const Eigen::VectorXd q = toEigen(Y, 0, n), v = toEigen(Y, n, n);
  Eigen::VectorXd a;
  self->acceleration(t, q, v, a);
  toVec(v, Fv, 0);
  toVec(a, Fv, n);
  PetscFunctionReturn(0);
}

PetscErrorCode HubBeamDynamics::stateOf(Vec X, Eigen::VectorXd& q, Eigen::VectorXd& v) {
  PetscFunctionBeginUser;
  if (_firstOrder) {
    q = toEigen(X, 0, _n);
    v = toEigen(X, _n, _n);
  } else {
    Vec U, V;
    PetscCall(TS2GetSolution(_ts, &U, &V));
    q = toEigen(U, 0, _n);
    v = toEigen(V, 0, _n);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode HubBeamDynamics::monitor(TS ts, PetscInt step, PetscReal t, Vec X, void* ctx) {
  PetscFunctionBeginUser;
  auto* self = static_cast<HubBeamDynamics*>(ctx);
  Eigen::VectorXd q, v;
  PetscCall(self->stateOf(X, q, v));
  PetscInt its = 0, rejected = 0;
  PetscCall(TSGetSNESIterations(ts, &its));
  PetscCall(TSGetStepRejections(ts, &rejected));
  const int newton = static_cast<int>(its) - self->_lastIterations;
  self->_lastIterations = static_cast<int>(its);
  self->record(static_cast<int>(step), t, q, v, newton, static_cast<int>(rejected));
  PetscFunctionReturn(0);
}

void HubBeamDynamics::record(int step, double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, int newton,
                             int rejected, const Eigen::VectorXd* known) {
  Eigen::VectorXd a;
  if (known) a = *known;
  else acceleration(t, q, v, a);
  HubBeamStep s;
  s.step = step;
  s.time = t;
  s.obs = _model.observe(t, q, v, a);
  const double power = s.obs.hubTorque * s.obs.omega;
  if (_haveLast) {
    s.hubWork = _last.hubWork + 0.5 * (power + _lastPower) * (t - _last.time);
    s.newtonIterations = newton;
    s.rejectedSteps = rejected;
  }
  _last = s;
  _lastPower = power;
  _haveLast = true;
  if (_onStep && *_onStep) (*_onStep)(s, q, v);
}

namespace {

// After every step: stop a run whose state is not finite or has left any beam model's range (the
// reason survives here; TSStep resets it).
PetscErrorCode postStep(TS ts) {
  PetscFunctionBeginUser;
  void* ctx;
  PetscCall(TSGetApplicationContext(ts, &ctx));
  PetscCall(static_cast<HubBeamDynamics*>(ctx)->checkState(ts));
  PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode HubBeamDynamics::checkState(TS ts) {
  PetscFunctionBeginUser;
  Vec X;
  PetscReal t;
  PetscInt step;
  PetscCall(TSGetSolution(ts, &X));
  PetscCall(TSGetTime(ts, &t));
  PetscCall(TSGetStepNumber(ts, &step));
  Eigen::VectorXd q, v;
  PetscCall(stateOf(X, q, v));
  // the TS calls this before its monitor: the step's observation is not recorded yet (the tip and
  // the hub's rate do not depend on the acceleration)
  const HubBeam::Observation o = _model.observe(t, q, v, Eigen::VectorXd::Zero(_n));
  _stop = divergence(t, static_cast<int>(step), q.allFinite() && v.allFinite(), o);
  if (!_stop.empty()) PetscCall(TSSetConvergedReason(ts, TS_DIVERGED_STEP_REJECTED));
  else if (stopRequested()) {
    _stopped = true;
    PetscCall(TSSetConvergedReason(ts, TS_CONVERGED_USER));
  }
  PetscFunctionReturn(0);
}

std::string HubBeamDynamics::divergence(double t, int step, bool finite, const HubBeam::Observation& o) const {
  const double L = _model.desc().length;
  const double tip = std::hypot(o.tipUx, o.tipUy);
  if (finite && tip <= kDeformationLimit * L) return {};
  std::ostringstream m;
  m << _schemeName << ": at t = " << fmt(t, 6) << " s (step " << step << ") ";
  if (!finite) m << "the state is not finite";
  else m << "the tip has moved " << fmt(tip, 3) << " m in the floating frame, more than " << kDeformationLimit
         << " beam lengths: the response diverges";
  const double w1 = _model.firstBendingFrequency();
  if (_model.desc().coupling == model::HubBeamCoupling::ZeroOrder && std::abs(o.omega) > w1)
    m << ". The hub turns at " << fmt(o.omega, 4) << " rad/s, above the beam's first bending frequency " << fmt(w1, 4)
      << " rad/s: the zero-order model softens dynamically there (seed 001 Eq. 7); use coupling: first_order";
  else
    m << ". " << solvers::stabilityNote(_desc) << "Try a smaller dt, an implicit integrator (generalized_alpha), or check the load";
  return m.str();
}

bool HubBeamDynamics::stopRequested() { return _stopCheck && _stopCheck(); }

PetscErrorCode HubBeamDynamics::run(const StepCallback& onStep, std::string* failure) {
  PetscFunctionBeginUser;
  _onStep = &onStep;
  _haveLast = false;
  _lastIterations = 0;
  _stop.clear();
  _stopped = false;
  failure->clear();
  if (_dense) {
    PetscCall(runDense());
    *failure = _stop;
    PetscFunctionReturn(0);
  }
  Eigen::VectorXd q = Eigen::VectorXd::Zero(_n), v = initialRate(), a;
  PetscCall(TSSetTime(_ts, 0.0));
  PetscCall(TSSetStepNumber(_ts, 0));
  PetscCall(TSSetTimeStep(_ts, _desc.dt));
  if (_firstOrder) {
    toVec(q, _Y, 0);
    toVec(v, _Y, _n);
    PetscCall(TSSetSolution(_ts, _Y));
    PetscCall(TSSolve(_ts, _Y));
  } else {
    toVec(q, _X, 0);
    toVec(v, _V, 0);
    acceleration(0.0, q, v, a);
    Vec A;
    PetscCall(VecDuplicate(_X, &A));
    toVec(a, A, 0);
    PetscCall(TS2SetSolution(_ts, _X, _V));
    PetscCall(solvers::GeneralizedAlphaSetAcceleration(_ts, A));
    PetscCall(VecDestroy(&A));
    PetscCall(TSSolve(_ts, _X));
  }
  TSConvergedReason reason;
  PetscCall(TSGetConvergedReason(_ts, &reason));
  if (!_stop.empty()) {
    *failure = _stop;
  } else if (reason < 0) {  // a Newton failure (a fixed step: the TS stops at the first)
    SNES snes;
    Vec F;
    PetscInt its;
    PetscReal t, h, norm;
    PetscCall(TSGetSNES(_ts, &snes));
    PetscCall(SNESGetIterationNumber(snes, &its));
    PetscCall(SNESGetFunction(snes, &F, nullptr, nullptr));
    PetscCall(VecNorm(F, NORM_2, &norm));
    PetscCall(TSGetTime(_ts, &t));
    PetscCall(TSGetTimeStep(_ts, &h));
    *failure = newtonFailure(t + h, _last.step + 1, static_cast<int>(its), norm);
  }
  PetscFunctionReturn(0);
}

}  // namespace strand::ffr
