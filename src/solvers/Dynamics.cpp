#include "strand/solvers/Dynamics.hpp"
#include "strand/solvers/Schemes.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <sstream>

#include "strand/solvers/AdamsBashforthMoulton.hpp"
#include "strand/solvers/StrandBdf.hpp"
#include "strand/solvers/GeneralizedAlpha.hpp"
#include "strand/solvers/IsotropicMass.hpp"
#include "strand/solvers/StaticSolver.hpp"

namespace strand::solvers {


Dynamics::Dynamics(assembly::Assembler& assembler, const model::DynamicsDesc& desc) : _asm(assembler), _desc(desc) {
  const model::DofMap& dofs = assembler.dofs();
  MPI_Comm comm = dofs.comm();
  _damped = assembler.model().velocityDependent();
  // Kinds whose mass depends on the coordinates (the ALE elements) add their inertia
  // M(q) a + Q_p(q, v) to the residual and its derivatives to the Newton matrix (formFunction,
  // formJacobian); _M holds the constant part. The first-order forms factor a constant mass: they
  // are refused for such models (the scene reader says so with the scene's line first).
  _variableMass = assembler.hasVariableMass();
  if (_variableMass && model::isFirstOrder(desc.integrator))
    throw std::logic_error("Dynamics: a configuration-dependent mass needs a generalized-alpha scheme");
  _moving = assembler.model().hasPrescribedMotion();
  _constrained = assembler.hasConstraints();
  for (const model::Body& b : assembler.model().bodies()) _energyFloor += 1e-12 * b.properties.EA * b.length;
  PetscCallAbort(comm, dofs.createMatrix(&_M, "dyn_mass_"));
  PetscCallAbort(comm, dofs.createMatrix(&_J, "dyn_"));
  PetscCallAbort(comm, assembler.massMatrix(_M, false));
  PetscCallAbort(comm, dofs.createVector(&_fext));  // its duplicates are the assembler's own layout (no copies)
  {  // only products with M from here on: the compact M_s (x) I when the mass is isotropic
    Mat op;
    PetscBool compact;
    PetscCallAbort(comm, isotropicMassOperator(_M, &op, &compact));
    PetscCallAbort(comm, PetscInfo(nullptr, "mass for products: %s\n", compact ? "M_s (x) I" : "BAIJ"));
    PetscCallAbort(comm, MatDestroy(&_M));
    _M = op;
  }
  PetscCallAbort(comm, VecDuplicate(_fext, &_w1));
  PetscCallAbort(comm, VecDuplicate(_fext, &_w2));
  PetscCallAbort(comm, VecDuplicate(_fext, &_a0));
  PetscCallAbort(comm, VecDuplicate(_fext, &_supported));
  PetscCallAbort(comm, VecDuplicate(_fext, &_reaction));
  PetscCallAbort(comm, VecSet(_reaction, 0.0));  // moveSupportedRows writes the supported rows alone
  PetscCallAbort(comm, VecDuplicate(_fext, &_multipliers));
  PetscCallAbort(comm, assembler.multiplierMask(_multipliers));
  PetscCallAbort(comm, VecDuplicate(_fext, &_notMultiplier));
  PetscCallAbort(comm, VecSet(_notMultiplier, 1.0));
  PetscCallAbort(comm, VecAXPY(_notMultiplier, -1.0, _multipliers));
  PetscCallAbort(comm, assembler.externalForce(_fext));
  // loads that depend on the configuration (the ALE kinds' load on their material) have no
  // potential of the body alone (material enters and leaves it): _fext keeps the constant loads,
  // and the energy balance counts the others' work v . Q(q) (powers)
  _configurationLoads = assembler.hasConfigurationLoads();
  if (_configurationLoads) {  // _fext -= Q(q0) (the work vectors: u = 0 in _w1, Q(q0) in _w2)
    PetscCallAbort(comm, VecSet(_w1, 0.0));
    PetscCallAbort(comm, assembler.configurationLoads(_w1, _w2));
    PetscCallAbort(comm, VecAXPY(_fext, -1.0, _w2));
  }
  PetscCallAbort(comm, assembler.supportMask(_supported));
  {  // and 1e-12 |f| |q0|: the potential -f.u of the constant loads has the round-off eps |f| |q0|
     // (a rigid pendulum hanging at rest: 6e-27 J "created", with no cable in the floor above)
    PetscReal fnorm;
    PetscCallAbort(comm, VecNorm(_fext, NORM_2, &fnorm));
    _energyFloor += 1e-12 * fnorm * assembler.coordinateNorm();
  }

  _firstOrder = model::isFirstOrder(desc.integrator);
  _explicit = model::isExplicit(desc.integrator);
  _schemeName = solvers::schemeName(desc);

  PetscCallAbort(comm, GeneralizedAlphaRegister());
  PetscCallAbort(comm, AdamsBashforthMoultonRegister());
  PetscCallAbort(comm, StrandBdfRegister());
  PetscCallAbort(comm, TSCreate(comm, &_ts));
  PetscCallAbort(comm, TSSetOptionsPrefix(_ts, "dyn_"));
  if (_firstOrder) {
    // the explicit form and the support forces need the factored mass; with joints (BDF only) the
    // multipliers come from the Newton system instead
    if (!_constrained) PetscCallAbort(comm, createMassSolver(_fext, &_massSolver));
    _space = std::make_unique<StateSpace>(assembler, _M, _supported, _massSolver, _damped);
    if (_constrained)
      _constrainedSpace = std::make_unique<ConstrainedStateSpace>(assembler, *_space, _supported, _multipliers, _damped,
                                                                  desc.constraintForm);
    PetscCallAbort(comm, _space->createState(&_Y));
    if (desc.integrator == model::Integrator::Bdf) {  // ours, TSBDF's algorithm: its history goes into checkpoints
      PetscCallAbort(comm, TSSetType(_ts, kTsStrandBdf));
      PetscCallAbort(comm, StrandBdfSetOrder(_ts, desc.bdfOrder));
    } else if (desc.integrator == model::Integrator::Rk4) {
      PetscCallAbort(comm, TSSetType(_ts, TSRK));
      PetscCallAbort(comm, TSRKSetType(_ts, TSRK4));
    } else {
      PetscCallAbort(comm, TSSetType(_ts, kTsAdamsBashforthMoulton));
    }
  } else {
    PetscCallAbort(comm, TSSetType(_ts, kTsGeneralizedAlpha));
    PetscCallAbort(comm, GeneralizedAlphaSetNewtonRetry(_ts, retryNewton, this));
    PetscCallAbort(comm, GeneralizedAlphaSetStepCuts(_ts, desc.stepCuts));
    if (_asm.hasContactHistory()) PetscCallAbort(comm, GeneralizedAlphaSetSettle(_ts, settleContact, this));
    PetscCallAbort(comm, TSSetI2Function(_ts, nullptr, formFunction, this));
    PetscCallAbort(comm, TSSetI2Jacobian(_ts, _J, _J, formJacobian, this));
    PetscCallAbort(comm, applyScheme());
  }
  PetscCallAbort(comm, configureTimeStepping(_ts, desc));
  PetscCallAbort(comm, TSMonitorSet(_ts, monitor, this, nullptr));
  PetscCallAbort(comm, TSSetApplicationContext(_ts, this));
  PetscCallAbort(comm, TSSetPostStep(_ts, postStep));

  if (_explicit) {
    PetscCallAbort(comm, _space->setExplicit(_ts));
    return;
  }
  SNES snes;
  KSP ksp;
  PetscCallAbort(comm, TSGetSNES(_ts, &snes));
  PetscCallAbort(comm, SNESSetTolerances(snes, 0.0, 1e-10, 1e-12, 25, PETSC_DEFAULT));
  // The Newton matrix is kept across iterations and steps while it contracts (NewtonMatrixReuse,
  // formJacobian decides at every iterate); -dyn_newton_matrix_contraction 0 gives full Newton.
  // as in statics: the residual has a round-off floor (NewtonConvergence.cpp)
  _floor.coordinateNorm = assembler.coordinateNorm();
  _floor.keptTolerance = 1e-3;  // a kept matrix's correction: at most 1e-3 of the first (NewtonConvergence.cpp)
  PetscCallAbort(comm, SNESSetConvergenceTest(snes, roundoffFloorConvergence, &_floor, nullptr));
  if (assembler.hasContact()) {
    // Belt-pulley contact opens and closes, and regularized friction turns steeply near zero slip:
    // full Newton steps can cycle between two iterates (the dynamic capstan, dt 2e-3 s: |R| 136,
    // 283, 136, ... for 25 iterations). A backtracking line search settles them.
    SNESLineSearch ls;
    PetscCallAbort(comm, SNESGetLineSearch(snes, &ls));
    PetscCallAbort(comm, SNESLineSearchSetType(ls, SNESLINESEARCHBT));
  } else {
    PetscCallAbort(comm, useFullNewtonStep(snes, &_floor));  // no residual the step test discards
  }
  PetscCallAbort(comm, SNESGetKSP(snes, &ksp));
  // second-order form: K + c_v D + c_a M is regular without the multiplier rows (the interface
  // Schur PC takes them); the first-order constrained state space keeps MUMPS
  const bool regularInterior = !_constrainedSpace && !assembler.model().freeMaterialCoordinates();
  PetscCallAbort(comm, setDirectSolverDefaults(ksp, _constrained, regularInterior));
  if (_constrainedSpace) {  // the assembled 2n x 2n Newton matrix, by the direct solver above
    PetscCallAbort(comm, _constrainedSpace->setImplicit(_ts));
    if (desc.adaptive) PetscCallAbort(comm, _constrainedSpace->setTolerances(_ts, desc.atol, desc.rtol));
  } else if (_firstOrder) {
    PetscCallAbort(comm, _space->setImplicit(_ts));  // the exact Schur-complement solve
  }
}

Dynamics::~Dynamics() {
  TSDestroy(&_ts);
  _constrainedSpace.reset();
  _space.reset();
  KSPDestroy(&_massSolver);
  VecDestroy(&_Y);
  VecDestroy(&_acc);
  VecDestroy(&_ydot);
  VecDestroy(&_resume.A);
  VecDestroy(&_resume.a);
  for (Vec& v : _resume.history) VecDestroy(&v);
  MatDestroy(&_M);
  MatDestroy(&_J);
  for (Vec* v : {&_fext, &_w1, &_w2, &_a0, &_supported, &_reaction, &_multipliers, &_notMultiplier}) VecDestroy(v);
}

// The scene's scheme parameters for the current TS type (ours, or PETSc's TSALPHA2 when chosen
// with -dyn_ts_type alpha2).
PetscErrorCode Dynamics::applyScheme() {
  PetscFunctionBeginUser;
  const AlphaParams p = _params = alphaParams(_desc);
  PetscBool ours;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(_ts), kTsGeneralizedAlpha, &ours));
  if (ours) PetscCall(GeneralizedAlphaSetParams(_ts, p.alphaM, p.alphaF, p.gamma, p.beta));
  else PetscCall(TSAlpha2SetParams(_ts, 1.0 - p.alphaM, 1.0 - p.alphaF, p.gamma, p.beta));  // PETSc weights the end of the step
  PetscFunctionReturn(0);
}

PetscErrorCode Dynamics::setFromOptions() {
  PetscFunctionBeginUser;
  PetscCall(TSSetFromOptions(_ts));
  PetscReal c = _reuse.contraction();
  PetscCall(PetscOptionsGetReal(nullptr, "dyn_", "-newton_matrix_contraction", &c, nullptr));
  _reuse.setContraction(c);
  PetscReal price = _reuse.price();
  PetscCall(PetscOptionsGetReal(nullptr, "dyn_", "-newton_matrix_price", &price, nullptr));
  PetscCheck(price >= 0.0, _asm.dofs().comm(), PETSC_ERR_ARG_OUTOFRANGE,
             "-dyn_newton_matrix_price %g: the price of a Newton matrix in iterations is >= 0 (0: never bought for the "
             "extra iterations of a kept one)", static_cast<double>(price));
  _reuse.setPrice(price);
  PetscCall(PetscOptionsGetReal(nullptr, "dyn_", "-newton_kept_tolerance", &_floor.keptTolerance, nullptr));
  PetscBool ours, alpha2;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(_ts), kTsGeneralizedAlpha, &ours));
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(_ts), TSALPHA2, &alpha2));
  if (_firstOrder) {
    PetscCheck(!ours && !alpha2, _asm.dofs().comm(), PETSC_ERR_SUP,
               "-dyn_ts_type: integrator %s works on the first-order form y = (u, v); choose a first-order TS "
               "(bdf, rk, %s, ...) or change the scene's integrator", _schemeName.c_str(), kTsAdamsBashforthMoulton);
    PetscFunctionReturn(0);
  }
  PetscCheck(ours || alpha2, _asm.dofs().comm(), PETSC_ERR_SUP,
             "-dyn_ts_type: the dynamics integrate a second-order system; use %s (default) or alpha2", kTsGeneralizedAlpha);
  PetscCheck(ours || !_moving, _asm.dofs().comm(), PETSC_ERR_SUP,
             "a turning hub (prescribed motion) needs -dyn_ts_type %s", kTsGeneralizedAlpha);
  PetscCheck(ours || !_constrained, _asm.dofs().comm(), PETSC_ERR_SUP,
             "joints (Lagrange multipliers, index 3) need -dyn_ts_type %s", kTsGeneralizedAlpha);
  if (alpha2) {  // the scene's parameters, then the -dyn_ts_alpha_* options over them
    PetscCall(applyScheme());
    PetscCall(TSSetFromOptions(_ts));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Dynamics::prescribe(PetscReal t, Vec X, Vec V, Vec A, void* ctx) {
  PetscFunctionBeginUser;
  PetscCall(static_cast<Dynamics*>(ctx)->_asm.prescribedMotion(t, X, V, A));
  PetscFunctionReturn(0);
}

// A direct solver for the masked mass with unit diagonal on supported rows, or with joints the
// saddle-point matrix [M G^T; G 0] at state X (the KSP keeps the matrix).
PetscErrorCode Dynamics::createMassSolver(Vec X, KSP* ksp) {
  PetscFunctionBeginUser;
  MPI_Comm comm = _asm.dofs().comm();
  Mat S;
  PetscCall(_asm.dofs().createMatrix(&S, "dyn_mass_"));
  if (_constrained) {
    PetscCall(_asm.saddleMatrix(X, S));
  } else {
    PetscCall(_asm.massMatrixAt(X, S, true));
    PetscCall(MatDiagonalSet(S, _supported, ADD_VALUES));
  }
  PetscCall(KSPCreate(comm, ksp));
  PetscCall(KSPSetOptionsPrefix(*ksp, "dyn_mass_"));
  PetscCall(KSPSetOperators(*ksp, S, S));
  PetscCall(MatDestroy(&S));
  // [M G^T; G 0]: M is regular unless material coordinates are free (Model::freeMaterialCoordinates)
  PetscCall(setDirectSolverDefaults(*ksp, _constrained, !_asm.model().freeMaterialCoordinates()));
  PetscCall(KSPSetFromOptions(*ksp));
  PetscFunctionReturn(0);
}

// Consistent start. Without joints: M a0 = f_ext - f_int(u0, v0) on the free rows, a0 = the
// prescribed acceleration on supported rows. With joints (index 3): the initial velocities are
// first projected onto the constraint manifold in the mass metric, [M G^T; G 0] [v; nu] =
// [M v; -G_s v_p], then [M G^T; G 0] [a0; lambda0] = [f_ext - f_int - M a_p; -(d/dq (G v)) v -
// G_s a_p] gives the accelerations and the multipliers (mu0 = lambda0 / s into X): the TS's first
// Newton then starts at the solution of t0. The matrix holds only the free columns of G; G_s v_p and
// G_s a_p are the joints' rates due to a driven body's prescribed velocity and acceleration (a hub
// that starts turning, or accelerating, at t0). One factorization serves both solves.
// With project = false it solves for a and lambda at (t, X, V) as given (perturbedStart).
PetscErrorCode Dynamics::consistentAcceleration(PetscReal t, Vec X, Vec V, Vec A, bool project) {
  PetscFunctionBeginUser;
  if (_constrained) {
    PetscCall(VecPointwiseMult(V, V, _notMultiplier));
    PetscCall(VecPointwiseMult(X, X, _notMultiplier));
  }
  KSP ksp;
  PetscCall(createMassSolver(X, &ksp));
  if (_constrained && project) {
    PetscCall(VecPointwiseMult(_w2, V, _supported));  // prescribed velocities stay
    PetscCall(VecWAXPY(A, -1.0, _w2, V));              // free velocities (A is scratch here)
    PetscCall(MatMult(_M, A, _w1));                    // M_ff v_f on the free rows
    PetscCall(_asm.zeroSupportedRows(_w1));
    PetscCall(subtractPrescribedRate(X, _w2, _w1, A));
    PetscCall(KSPSolve(ksp, _w1, V));
    PetscCall(VecPointwiseMult(V, V, _notMultiplier));
    PetscCall(VecAXPY(V, 1.0, _w2));
  }
  PetscCall(VecSet(A, 0.0));
  PetscCall(_asm.prescribedMotion(t, nullptr, nullptr, A));
  PetscCall(dynamicResidual(X, V, A, t, _w1, assembly::SupportRows::Value));  // with M(q) a_p + Q_p(q, v)
  PetscCall(_asm.zeroSupportedRows(_w1));
  PetscCall(VecScale(_w1, -1.0));
  if (_constrained) {
    PetscCall(VecPointwiseMult(_w1, _w1, _notMultiplier));
    PetscCall(_asm.constraintVelocityTerm(X, V, _w2));
    PetscCall(VecAXPY(_w1, -1.0, _w2));
    if (!_acc) PetscCall(VecDuplicate(_fext, &_acc));
    PetscCall(subtractPrescribedRate(X, A, _w1, _acc));
  }
  PetscCall(KSPSolve(ksp, _w1, _w2));
  PetscCall(KSPDestroy(&ksp));
  if (_constrained) {  // mu0 = lambda0 / s
    PetscCall(VecPointwiseMult(_w1, _w2, _multipliers));
    PetscCall(VecAXPY(X, 1.0 / _asm.constraintScale(), _w1));
    PetscCall(VecPointwiseMult(_w2, _w2, _notMultiplier));
  }
  PetscCall(VecAXPY(A, 1.0, _w2));
  PetscFunctionReturn(0);
}

// rhs -= G w on the multiplier rows, for w the prescribed rates (zero on free and multiplier rows):
// Assembler::constraintGradientProduct gives s G w there (and s G^T w_mu = 0 elsewhere).
PetscErrorCode Dynamics::subtractPrescribedRate(Vec X, Vec w, Vec rhs, Vec scratch) {
  PetscFunctionBeginUser;
  PetscCall(_asm.constraintGradientProduct(X, w, scratch));
  PetscCall(VecPointwiseMult(scratch, scratch, _multipliers));
  PetscCall(VecAXPY(rhs, -1.0 / _asm.constraintScale(), scratch));
  PetscFunctionReturn(0);
}

// Generalized-alpha's start with joints (index 3): perturbed starting values, after Arnold & Bruls,
// Multibody Syst. Dyn. 18 (2007) 185, Sec. 4. On a smooth solution the scheme's variables are, to
// O(h^2) (Taylor expansion of GeneralizedAlpha.hpp's recursions with Delta = alpha_m - alpha_f =
// 1/2 - gamma):
//   a_n = A(t_n + Delta h),   v_n = v(t_n) + h^2 (1/6 - beta - Delta/2) A'(t_n).
// Without joints a start from a0 = A0, v0 = v(t0) leaves only an O(h) error in a, whose effect on q is
// O(h^3) per step, while A comes from equilibrium. With joints the positions are held on the
// constraint manifold, the mismatch has nowhere else to go, and A and lambda carry an O(h) transient
// over the first ~100 steps at rho_inf = 0.9 (measured on a link carried by a driven hub,
// tests/verification/test_multibody.cpp: drive torque 0.36 % off at h = 1 ms and first order;
// with this start 1e-5 and second order). The jerk A' = (A(t0 + h) - A0) / h + O(h) comes from the
// consistent acceleration at the state extrapolated to t0 + h (q0 + h v0 + h^2/2 A0, v0 + h A0; an
// O(h^2) state error): one more factorization of the saddle-point matrix at the start. The velocity
// offset enters the first step only (GeneralizedAlphaSetStartVelocityOffset): the state reported at
// t0 is the consistent one.
PetscErrorCode Dynamics::perturbedStart(Vec X, Vec V, Vec a) {
  PetscFunctionBeginUser;
  const PetscReal h = _desc.dt, delta = _params.alphaM - _params.alphaF;
  PetscCall(VecCopy(_a0, a));
  if (!_constrained) PetscFunctionReturn(0);
  Vec Xh, Vh, jerk;
  PetscCall(VecDuplicate(X, &Xh));
  PetscCall(VecDuplicate(V, &Vh));
  PetscCall(VecDuplicate(V, &jerk));
  PetscCall(VecWAXPY(Vh, h, _a0, V));
  PetscCall(VecWAXPY(Xh, 0.5 * h, _a0, V));
  PetscCall(VecAYPX(Xh, h, X));  // X + h V + h^2/2 A0
  PetscCall(VecPointwiseMult(Xh, Xh, _notMultiplier));
  PetscCall(VecPointwiseMult(Vh, Vh, _notMultiplier));
  PetscCall(_asm.prescribedMotion(h, Xh, Vh, nullptr));
  PetscCall(consistentAcceleration(h, Xh, Vh, jerk, false));
  PetscCall(VecAXPY(jerk, -1.0, _a0));
  PetscCall(VecScale(jerk, 1.0 / h));
  PetscCall(VecAXPY(a, delta * h, jerk));
  PetscCall(VecPointwiseMult(jerk, jerk, _notMultiplier));
  PetscCall(_asm.zeroSupportedRows(jerk));  // prescribed velocities stay exact (GeneralizedAlpha.hpp)
  PetscCall(VecScale(jerk, h * h * (1.0 / 6.0 - _params.beta - 0.5 * delta)));
  PetscCall(GeneralizedAlphaSetStartVelocityOffset(_ts, jerk));
  PetscCall(VecDestroy(&Xh));
  PetscCall(VecDestroy(&Vh));
  PetscCall(VecDestroy(&jerk));
  PetscFunctionReturn(0);
}

PetscErrorCode Dynamics::currentAcceleration(Vec* A) {
  PetscFunctionBeginUser;
  PetscBool ours;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(_ts), kTsGeneralizedAlpha, &ours));
  *A = _a0;  // TSALPHA2 keeps its acceleration private: only the initial one is known
  if (ours) PetscCall(GeneralizedAlphaGetAcceleration(_ts, A));
  PetscFunctionReturn(0);
}

PetscErrorCode Dynamics::supportForce(Vec F) {
  PetscFunctionBeginUser;
  if (_firstOrder) {  // copies, not views: a step callback may hold the view
    Vec Y, X, V;
    PetscReal t;
    PetscCall(TSGetSolution(_ts, &Y));
    PetscCall(TSGetTime(_ts, &t));
    PetscCall(VecDuplicate(F, &X));
    PetscCall(VecDuplicate(F, &V));
    PetscCall(_space->unpack(Y, X, V));
    PetscCall(supportForceAt(t, X, V, F));
    PetscCall(VecDestroy(&X));
    PetscCall(VecDestroy(&V));
    PetscFunctionReturn(0);
  }
  if (_reactionValid) {  // from the last residual of the step (formFunction), at the same state
    PetscCall(VecCopy(_reaction, F));
    PetscFunctionReturn(0);
  }
  Vec X, V, A;
  PetscReal t;
  PetscCall(TS2GetSolution(_ts, &X, &V));
  PetscCall(TSGetTime(_ts, &t));
  PetscCall(currentAcceleration(&A));
  PetscCall(dynamicResidual(X, V, A, t, F, assembly::SupportRows::Reaction));
  PetscCall(VecPointwiseMult(F, F, _supported));
  PetscFunctionReturn(0);
}

// f_s = M a + f_int - f_ext on supported rows, with a from the state (StateSpace::acceleration);
// with joints f_int includes s G^T mu of the state's multipliers, and a is the v-half of the
// derivative BDF solved for in the last step (StrandBdfGetDerivative: the pair (a, lambda) for
// which the step's residual vanishes, as generalized-alpha's reaction uses its own a), or the
// consistent start's before the first step.
PetscErrorCode Dynamics::supportForceAt(PetscReal t, Vec X, Vec V, Vec F) {
  PetscFunctionBeginUser;
  if (!_acc) PetscCall(VecDuplicate(_fext, &_acc));
  if (_constrained) {
    PetscBool known = PETSC_FALSE, bdf;
    PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(_ts), kTsStrandBdf, &bdf));
    PetscCheck(bdf, _asm.dofs().comm(), PETSC_ERR_SUP, "support forces with joints need -dyn_ts_type %s or %s",
               kTsStrandBdf, kTsGeneralizedAlpha);
    if (!_ydot) PetscCall(VecDuplicate(_Y, &_ydot));
    PetscCall(StrandBdfGetDerivative(_ts, _ydot, &known));
    if (known) {  // copies: the monitor may hold a view of the state
      PetscCall(_space->unpack(_ydot, _w2, _acc));
      PetscCall(VecPointwiseMult(_acc, _acc, _notMultiplier));
    } else {
      PetscCall(VecCopy(_a0, _acc));
    }
  } else {
    PetscCall(_space->acceleration(t, X, V, _acc));
  }
  PetscCall(dynamicResidual(X, V, _acc, t, F, assembly::SupportRows::Reaction));
  PetscCall(VecPointwiseMult(F, F, _supported));
  PetscFunctionReturn(0);
}

// F = M A + f_int(U, V) - f_ext; zero on supported rows (the TS sets them).
PetscErrorCode Dynamics::formFunction(TS, PetscReal t, Vec U, Vec V, Vec A, Vec F, void* ctx) {
  PetscFunctionBeginUser;
  auto* self = static_cast<Dynamics*>(ctx);
  PetscCall(self->dynamicResidual(U, V, A, t, F, assembly::SupportRows::Reaction));
  if (self->_moving) {  // the support force of this state; the last call of a step is at its end
    PetscCall(self->_asm.moveSupportedRows(F, self->_reaction));  // (only supported rows: the rest stays 0)
    self->_reactionValid = true;
  } else {
    PetscCall(self->_asm.zeroSupportedRows(F));
  }
  PetscFunctionReturn(0);
}

// A Newton failure after a kept matrix: once more with full Newton (NewtonMatrixReuse).
PetscErrorCode Dynamics::retryNewton(void* ctx, PetscBool* again) {
  PetscFunctionBeginUser;
  *again = static_cast<Dynamics*>(ctx)->_reuse.retryWithFullNewton() ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

// The bristle law's stick/slip states held while Newton solves (GeneralizedAlphaSetSettle).
PetscErrorCode Dynamics::settleContact(void* ctx, PetscReal t, Vec X, Vec V, PetscBool release, PetscInt* changed) {
  PetscFunctionBeginUser;
  auto* self = static_cast<Dynamics*>(ctx);
  PetscCall(self->_asm.settleContact(X, V, t, release == PETSC_TRUE, changed));
  PetscFunctionReturn(0);
}

std::string Dynamics::newtonStart() const {
  const char* name = "";
  if (_ownAlpha) PetscCallAbort(PETSC_COMM_SELF, GeneralizedAlphaGetPredictor(_ts, nullptr, &name));
  return name;
}

PetscErrorCode Dynamics::formJacobian(TS ts, PetscReal t, Vec U, Vec V, Vec A, PetscReal shiftV, PetscReal shiftA, Mat J, Mat,
                                      void* ctx) {
  PetscFunctionBeginUser;
  auto* self = static_cast<Dynamics*>(ctx);
  SNES snes;
  bool rebuild;
  PetscCall(TSGetSNES(ts, &snes));
  PetscCall(self->_reuse.decide(snes, self->_floor, shiftA, shiftV, &rebuild));
  self->_floor.keptMatrix = !rebuild;
  // where Newton started away from the constant-acceleration predictor (NewtonFloor::offset)
  if (self->_ownAlpha) PetscCall(GeneralizedAlphaGetPredictorOffset(ts, &self->_floor.offset));
  if (rebuild && self->_variableMass) PetscCall(self->_asm.dynamicJacobian(U, V, t, shiftV, shiftA, J, nullptr, A));
  else if (rebuild) PetscCall(self->_asm.dynamicJacobian(U, self->_damped ? V : nullptr, t, shiftV, shiftA, J));
  PetscFunctionReturn(0);
}

// v . f_d with the Kelvin-Voigt force f_d = f_int(u, v) - f_int(u, 0), and v . f_s with the
// support force f_s (supportForce).
PetscErrorCode Dynamics::powers(PetscReal t, Vec X, Vec V, const std::optional<PetscReal>& configurationPower,
                                PetscReal* damping, PetscReal* support, PetscReal* load) {
  PetscFunctionBeginUser;
  *damping = *support = *load = 0.0;
  // All three powers include the supported rows, as the support force does (zero v there unless the
  // support moves), so the balance E = T + U + P + W_d - W_s - W_t closes on moving supports too.
  if (_asm.hasTimedLoads() || _asm.model().hasLoadFunction() || _configurationLoads) {
    // v . f(t) of the time-dependent loads, and v . Q(q) of the configuration-dependent ones
    PetscCall(VecSet(_w1, 0.0));
    PetscCall(_asm.addTimedLoads(t, _w1, 1.0));
    if (_asm.model().hasLoadFunction()) PetscCall(VecAXPY(_w1, _asm.model().loadFactor(t), _fext));
    if (_configurationLoads && !configurationPower) {
      PetscCall(_asm.configurationLoads(X, _w2));
      PetscCall(VecAXPY(_w1, _asm.model().loadFactor(t), _w2));
    }
    PetscCall(VecDot(_w1, V, load));
    if (_configurationLoads && configurationPower) *load += _asm.model().loadFactor(t) * *configurationPower;
  }
  if (_damped) {
    PetscCall(_asm.residual(X, V, t, _w1, assembly::SupportRows::Reaction));
    PetscCall(_asm.residual(X, nullptr, t, _w2, assembly::SupportRows::Reaction));
    PetscCall(VecAXPY(_w1, -1.0, _w2));
    PetscCall(VecDot(_w1, V, damping));
  }
  // Belt-pulley contact: its normal penalty is stored energy (DynamicsStep::contact), the rest of
  // its power (friction, normal damping, the driven pulleys' input; Assembler::contactEnergy) is
  // load work, added by the caller. Its velocity-dependent part, -v . (Q(X, V) - Q(X, 0)) in the
  // damping power above, is taken back out of that.
  if (_asm.hasContact() && _damped) {
    PetscScalar withV = 0.0, atRest = 0.0;
    PetscCall(_asm.contactForce(X, V, t, _w1));
    PetscCall(VecDot(_w1, V, &withV));
    PetscCall(_asm.contactForce(X, nullptr, t, _w2));
    PetscCall(VecDot(_w2, V, &atRest));
    *damping += withV - atRest;
  }
  if (_moving) {
    if (_firstOrder) PetscCall(supportForceAt(t, X, V, _w1));
    else PetscCall(supportForce(_w1));
    PetscCall(VecDot(_w1, V, support));
  }
  PetscFunctionReturn(0);
}

// F = M A + f_int(X, V) - f_ext(t), with the inertia of kinds with M(q) in the same element pass.
PetscErrorCode Dynamics::dynamicResidual(Vec X, Vec V, Vec A, PetscReal t, Vec F, assembly::SupportRows rows) {
  PetscFunctionBeginUser;
  if (_variableMass) PetscCall(_asm.residualWithInertia(X, V, A, _damped, t, F, rows));
  else PetscCall(_asm.residual(X, _damped ? V : nullptr, t, F, rows));
  PetscCall(MatMultAdd(_M, A, F, F));
  PetscFunctionReturn(0);
}

PetscErrorCode Dynamics::energies(Vec X, Vec V, DynamicsStep* s, std::optional<PetscReal>* configurationPower) {
  PetscFunctionBeginUser;
  PetscScalar vmv, fu;
  PetscCall(MatMult(_M, V, _w1));
  PetscCall(VecDot(_w1, V, &vmv));
  s->kinetic = 0.5 * vmv;
  configurationPower->reset();
  if (_variableMass) {  // and the configuration loads' power v . Q(X) in the same pass, for powers()
    PetscReal T, q = 0.0;
    PetscCall(_asm.variableKineticEnergy(X, V, &T, _configurationLoads ? &q : nullptr));
    s->kinetic += T;
    if (_configurationLoads) *configurationPower = q;
  }
  PetscCall(_asm.strainEnergy(X, &s->strain));
  PetscCall(VecDot(_fext, X, &fu));
  s->potential = _asm.model().hasLoadFunction() ? 0.0 : -fu;  // time-scaled loads: their work instead
  PetscFunctionReturn(0);
}

PetscErrorCode Dynamics::monitor(TS ts, PetscInt step, PetscReal t, Vec X, void* ctx) {
  PetscFunctionBeginUser;
  auto* self = static_cast<Dynamics*>(ctx);
  // After a failed step, TSSolve monitors the last accepted state once more under its step number
  // (PETSc 3.18 src/ts/interface/ts.c): not a new step, so no second row of it.
  TSConvergedReason reason;
  PetscCall(TSGetConvergedReason(ts, &reason));
  if (reason < 0 && step == self->_last.step) PetscFunctionReturn(0);
  if (self->_firstOrder) {  // X is the state (u, v)
    Vec U, V;
    PetscCall(self->_space->view(X, &U, &V));
    PetscCall(self->monitorState(step, t, U, V));
    PetscCall(self->_space->releaseView(X));
  } else {
    Vec V;
    PetscCall(TS2GetSolution(ts, nullptr, &V));
    PetscCall(self->monitorState(step, t, X, V));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Dynamics::monitorState(PetscInt step, PetscReal t, Vec X, Vec V) {
  PetscFunctionBeginUser;
  PetscCall(_asm.commitContact(X, V, t));  // the bristle law's deflections of the accepted state
  DynamicsStep s;
  s.step = static_cast<int>(step);
  s.time = t;
  if (step > 0) {
    s.timeStep = t - _last.time;
    if (!_explicit) {
      SNES snes;
      PetscCall(TSGetSNES(_ts, &snes));
      PetscCall(SNESGetIterationNumber(snes, &s.newtonIterations));
    }
    PetscInt rejected;
    PetscCall(TSGetStepRejections(_ts, &rejected));
    s.rejectedSteps = static_cast<int>(rejected);
  }
  std::optional<PetscReal> configurationPower;
  PetscCall(energies(X, V, &s, &configurationPower));
  if (_constrained) PetscCall(_asm.constraintViolation(X, V, &s.constraintPosition, &s.constraintVelocity));
  PetscReal pd, ps, pl, pc = 0.0;
  PetscCall(powers(t, X, V, configurationPower, &pd, &ps, &pl));
  if (_asm.hasContact()) PetscCall(_asm.contactEnergy(X, V, t, &s.contact, &pc));
  pl += pc;
  const double half = 0.5 * (t - _last.time);
  s.dissipated = step > 0 ? _last.dissipated + half * (pd + _lastDampingPower) : 0.0;
  s.supportWork = step > 0 ? _last.supportWork + half * (ps + _lastSupportPower) : 0.0;
  s.loadWork = step > 0 ? _last.loadWork + half * (pl + _lastLoadPower) : 0.0;
  _last = s;
  _lastDampingPower = pd;
  _lastSupportPower = ps;
  _lastLoadPower = pl;
  // Blow-up guard: the schemes only remove energy (numerical dissipation), and a stable run's
  // balance error is O(h^2) small; energy *created* beyond half of the largest T + |U| + |P| + |W|
  // seen means the discrete solution has left the exact one for good (measured on the 20-link chain at
  // rho_inf = 1: E - E0 went from -2e-3 J to 1e11 J = T within 50 steps, without a Newton failure).
  if (step == 0) _e0 = s.energy();
  _energyScale = std::max(_energyScale, s.kinetic + std::fabs(s.strain) + s.contact + std::fabs(s.potential) +
                                                        std::fabs(s.dissipated) + std::fabs(s.supportWork) +
                                                        std::fabs(s.loadWork));
  // It must persist for kBlowUpSteps steps (or be NaN/inf): in the first steps from rest every
  // energy is tiny and the trapezoidal work sums are still O(h / t) off (measured: RK4 on the
  // spin-up, step 1: 1.4e-31 J "created", half the energy held then).
  // Below an absolute floor, 1e-12 of the cables' unit-strain energy sum EA L, energies are noise
  // (the spin-up's first 6 steps at h = 1.5e-5 s: 1e-31 J).
  const double created = s.energy() - _e0;
  if (step > 0 && !(created <= std::max(0.5 * _energyScale, _energyFloor))) {
    if (_overSteps++ == 0) _blowUpAt = s;  // the first step of the streak
    if (_overSteps >= kBlowUpSteps || !std::isfinite(created)) _blowUp = std::isfinite(created) ? created : 1.0;
  } else {
    _overSteps = 0;
  }
  s.suspect = _overSteps > 0 || !std::isfinite(created);  // e.g. no checkpoint of this state
  _last.suspect = s.suspect;
  if (_onStep && *_onStep) PetscCall((*_onStep)(s, X, V));
  PetscFunctionReturn(0);
}

PetscErrorCode Dynamics::postStep(TS ts) {
  PetscFunctionBeginUser;
  void* ctx;
  PetscCall(TSGetApplicationContext(ts, &ctx));
  auto* self = static_cast<Dynamics*>(ctx);
  if (self->_explicit && self->_moving) {  // supported DOFs exactly on the prescribed motion
    Vec Y;
    PetscReal t;
    PetscCall(TSGetSolution(ts, &Y));
    PetscCall(TSGetTime(ts, &t));
    PetscCall(self->_space->prescribe(t, Y));
  }
  if (self->_blowUp > 0.0) PetscCall(TSSetConvergedReason(ts, TS_DIVERGED_STEP_REJECTED));
  if (self->_desc.adaptive && !self->_explicit) {  // a step at the controller's floor: it has collapsed
    PetscReal t;
    PetscCall(TSGetTime(ts, &t));
    const double taken = t - self->_last.time;  // the monitor has not seen this step yet
    if (taken <= (1.0 + 1e-6) * kMinStepFraction * self->_desc.dt) {
      self->_collapsedStep = taken;
      PetscCall(TSSetConvergedReason(ts, TS_DIVERGED_STEP_REJECTED));
    }
  }
  if (self->_stopCheck) {  // every rank must stop at the same step
    int stop = self->_stopCheck() ? 1 : 0, size;
    const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(ts));
    PetscCallMPI(MPI_Comm_size(comm, &size));
    if (size > 1) PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &stop, 1, MPI_INT, MPI_MAX, comm));
    TSConvergedReason reason;
    PetscCall(TSGetConvergedReason(ts, &reason));
    if (stop && self->_blowUp == 0.0 && reason == TS_CONVERGED_ITERATING) {  // not over a finish or a failure
      self->_stopped = true;
      PetscCall(TSSetConvergedReason(ts, TS_CONVERGED_USER));
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Dynamics::run(Vec X, Vec V, const StepCallback& onStep, std::string* failure) {
  PetscFunctionBeginUser;
  PetscCheck(!(_explicit && _constrained), _asm.dofs().comm(), PETSC_ERR_SUP,
             "%s: joints (Lagrange multipliers) need an implicit integrator (generalized_alpha, bdf)", _schemeName.c_str());
  failure->clear();
  _onStep = &onStep;
  _stopped = false;
  const double t0 = _resuming ? _resume.time : 0.0;
  PetscCall(TSSetTime(_ts, t0));
  PetscCall(TSSetStepNumber(_ts, _resuming ? _resume.step : 0));
  PetscCall(TSSetTimeStep(_ts, _desc.dt));
  _reactionValid = false;
  _blowUp = _energyScale = _collapsedStep = 0.0;
  _overSteps = 0;
  if (_resuming) {  // the energy monitor continues its sums
    _last = _resume.last;
    _e0 = _resume.e0;
    _energyScale = _resume.energyScale;
    _lastDampingPower = _resume.lastDampingPower;
    _lastSupportPower = _resume.lastSupportPower;
    _lastLoadPower = _resume.lastLoadPower;
  } else {
    PetscCall(_asm.prescribedMotion(0.0, X, V, nullptr));
  }
  Vec X0 = nullptr;  // explicit schemes: the initial state, for the stability estimate of a failure
  if (_firstOrder) {
    if (_explicit) {
      PetscCall(VecDuplicate(X, &X0));
      PetscCall(VecCopy(X, X0));
    }
    if (_constrained) {
      // GGL: s = 1 / dt^2 (the first step's, then fixed: lambda~ = lambda / s is a state variable in
      // the BDF history), the order of sigma^2 M in the Newton matrix. Index 3 (every unknown in the
      // error norm): s = 1, the multipliers in newtons as a user would weigh them. Consistent start
      // as for index 3: velocities projected onto G v = 0, lambda~0 from the acceleration-level
      // system, mu~0 = 0.
      const bool ggl = _desc.constraintForm == model::DynamicsDesc::ConstraintForm::Ggl;
      _asm.setConstraintScale(ggl ? 1.0 / (_desc.dt * _desc.dt) : 1.0);
      if (!_resuming) PetscCall(consistentAcceleration(0.0, X, V, _a0, true));
    }
    PetscCall(_space->pack(X, V, _Y));
    PetscCall(TSSetSolution(_ts, _Y));
    PetscBool abm, bdf;
    PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(_ts), kTsAdamsBashforthMoulton, &abm));
    if (abm && _resuming && _resume.historyCount > 0)
      PetscCall(AdamsBashforthMoultonSetHistory(_ts, _resume.historyCount, _resume.historyStep, _resume.history.data()));
    PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(_ts), kTsStrandBdf, &bdf));
    if (bdf) {  // a checkpoint's history, or none: a start
      BdfHistory h;
      if (_resuming) {
        h.order = _resume.bdfOrder;
        h.steps = _resume.bdfSteps;
        h.times = _resume.historyTimes;
        h.states.assign(_resume.history.begin(), _resume.history.begin() + _resume.historyTimes.size());
        if (_desc.adaptive) PetscCall(TSSetTimeStep(_ts, _resume.historyStep));  // the controller's next step
      }
      PetscCall(StrandBdfSetHistory(_ts, h));
    }
    PetscCall(TSSolve(_ts, _Y));
    PetscCall(_space->unpack(_Y, X, V));
  } else {
    // index-3 scaling of the joint rows: s = 1 / (beta h^2) (times (1 - alpha_m)/(1 - alpha_f)),
    // the mass rows' shiftA, so that [shiftA M + K, s G^T; s G, 0] has balanced rows
    if (_constrained)
      _asm.setConstraintScale((1.0 - _params.alphaM) / ((1.0 - _params.alphaF) * _params.beta * _desc.dt * _desc.dt));
    if (_resuming) PetscCall(VecCopy(_resume.A, _a0));
    else PetscCall(consistentAcceleration(0.0, X, V, _a0, true));
    PetscCall(TS2SetSolution(_ts, X, V));
    PetscBool ours;
    PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(_ts), kTsGeneralizedAlpha, &ours));
    _ownAlpha = ours == PETSC_TRUE;
    if (ours) {
      if (_resuming) {
        PetscCall(GeneralizedAlphaSetState(_ts, _resume.A, _resume.a));
        // the start the run had chosen (older checkpoints: the option's, checked again)
        if (_resume.newtonStart >= 0) PetscCall(GeneralizedAlphaSetPredictor(_ts, _resume.newtonStart));
        PetscCall(GeneralizedAlphaResumeStepCuts(_ts, _resume.stepCuts, _resume.nominalStep));  // mid-way back from a cut
      } else {
        Vec a;
        PetscCall(VecDuplicate(_a0, &a));
        PetscCall(perturbedStart(X, V, a));
        PetscCall(GeneralizedAlphaSetState(_ts, _a0, a));
        PetscCall(VecDestroy(&a));
      }
      PetscCall(GeneralizedAlphaSetCoordinateNorm(_ts, _floor.coordinateNorm));
      if (_moving) PetscCall(GeneralizedAlphaSetPrescribedMotion(_ts, prescribe, this));
      if (_constrained) PetscCall(GeneralizedAlphaSetAlgebraic(_ts, _multipliers));
    }
    PetscCall(TSSolve(_ts, X));
  }
  TSConvergedReason reason;
  PetscCall(TSGetConvergedReason(_ts, &reason));
  if (reason < 0) {
    std::ostringstream msg;
    const DynamicsStep& at = _blowUp > 0.0 ? _blowUpAt : _last;
    msg << schemeName() << " stopped at t = " << at.time << " s after step " << at.step << " (dt "
        << (at.timeStep > 0.0 ? at.timeStep : _desc.dt) << " s): ";
    if (_blowUp > 0.0) {
  const double grown = _last.energy() - _e0;
      msg << "energy was created: the balance grew by " << at.energy() - _e0 << " J, more than half the energy the "
          << "system has held, and kept growing (" << grown << " J at t = " << _last.time
          << " s): the solution has blown up. ";
    } else if (_collapsedStep > 0.0) {
      msg << "the adaptive step collapsed to " << _collapsedStep << " s, at or below the controller's floor ("
          << kMinStepFraction << " of the first step): the local error estimate does not fall with the step. ";
    } else if (_explicit) {
      msg << "the step was rejected (" << TSConvergedReasons[reason] << "). ";
    } else {
      SNES snes;
      SNESConvergedReason sr;
      PetscCall(TSGetSNES(_ts, &snes));
      PetscCall(SNESGetConvergedReason(snes, &sr));
      if (_desc.integrator == model::Integrator::Bdf && _desc.adaptive)
        msg << "the adaptive step was rejected more than the TS allows in a row, last by Newton "
            << SNESConvergedReasons[sr] << " (" << TSConvergedReasons[reason] << "). ";
      else
        msg << "Newton " << SNESConvergedReasons[sr] << " in the next step (" << TSConvergedReasons[reason] << "). ";
    }
    if (_explicit) {
      PetscReal omega = 0.0;
      PetscCall(highestFrequency(X0, &omega));
      msg << "This scheme is explicit; the highest frequency of the model is omega_max ~ " << omega
          << " rad/s (from the initial state), so dt omega_max = " << _desc.dt * omega << ". ";
      if (_desc.integrator == model::Integrator::Rk4) {
        msg << "RK4 is stable only while dt omega_max <= 2 sqrt(2) = 2.83 (undamped modes; 2.79 for damped ones), "
            << "i.e. dt <= " << 2.0 * std::sqrt(2.0) / omega << " s. ";
      } else {
        // AdamsBashforthMoulton.hpp: undamped modes grow by 1 + 0.16 (h omega)^6 per step; growth
        // by e over the run needs 0.16 (h omega)^6 t_end / h <= 1
        const double dtSafe = std::pow(0.16 * std::pow(omega, 6) * _desc.tEnd, -0.2);
        msg << "Adams-Bashforth-Moulton 4 (PECE) amplifies undamped oscillations by about 1 + 0.16 (dt omega)^6 "
            << "per step (and is unstable beyond dt omega = 1.28 for damped ones): the highest mode grew from "
            << "round-off. dt <= " << dtSafe << " s keeps its growth below a factor e over t_end; RK4 damps "
            << "these modes instead. ";
      }
      msg << "Use a smaller dynamics.dt, or an implicit integrator (generalized_alpha, bdf) whose step accuracy "
             "alone sets (docs/user-guide.md, \"Dynamics\").";
    } else {
      msg << failureHint(at);
    }
    *failure = msg.str();
  }
  PetscCall(VecDestroy(&X0));
  _onStep = nullptr;
  if (_resuming) {
    PetscCall(VecDestroy(&_resume.A));
    PetscCall(VecDestroy(&_resume.a));
    for (Vec& v : _resume.history) PetscCall(VecDestroy(&v));
    _resuming = false;
  }
  PetscFunctionReturn(0);
}


}  // namespace strand::solvers
