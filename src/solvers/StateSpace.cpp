// First-order form y = (u, v) of the equations of motion (StateSpace.hpp).
#include "strand/solvers/StateSpace.hpp"

#include "strand/solvers/StaticSolver.hpp"

namespace strand::solvers {

StateSpace::StateSpace(assembly::Assembler& assembler, Mat M, Vec supported, KSP massSolver, bool damped)
    : _asm(assembler), _M(M), _supported(supported), _massSolver(massSolver), _damped(damped) {
  MPI_Comm comm = assembler.dofs().comm();
  PetscCallAbort(comm, VecGetLocalSize(supported, &_n));
  PetscCallAbort(comm, VecGetSize(supported, &_N));
  for (Vec* v : {&_free, &_up, &_vp, &_ap, &_w1, &_w2}) PetscCallAbort(comm, VecDuplicate(supported, v));
  for (Vec v : {_up, _vp, _ap}) PetscCallAbort(comm, VecSet(v, 0.0));
  PetscCallAbort(comm, VecSet(_free, 1.0));
  PetscCallAbort(comm, VecAXPY(_free, -1.0, supported));
  for (Halves* h : {&_a, &_b, &_c, &_view}) {
    PetscCallAbort(comm, VecCreateMPIWithArray(comm, 1, _n, _N, nullptr, &h->u));
    PetscCallAbort(comm, VecCreateMPIWithArray(comm, 1, _n, _N, nullptr, &h->v));
  }
}

StateSpace::~StateSpace() {
  for (Vec* v : {&_free, &_up, &_vp, &_ap, &_w1, &_w2, &_a.u, &_a.v, &_b.u, &_b.v, &_c.u, &_c.v, &_view.u, &_view.v})
    VecDestroy(v);
  MatDestroy(&_shell);
  MatDestroy(&_reduced);
  MatDestroy(&_D);
  KSPDestroy(&_reducedSolver);
}

PetscErrorCode StateSpace::createState(Vec* Y) const {
  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(_asm.dofs().comm(), 2 * _n, 2 * _N, Y));
  PetscFunctionReturn(0);
}

PetscErrorCode StateSpace::place(Halves& h, const PetscScalar* a) {
  PetscFunctionBeginUser;
  PetscCall(VecPlaceArray(h.u, a));
  PetscCall(VecPlaceArray(h.v, a + _n));
  PetscFunctionReturn(0);
}

PetscErrorCode StateSpace::reset(Halves& h) {
  PetscFunctionBeginUser;
  PetscCall(VecResetArray(h.u));
  PetscCall(VecResetArray(h.v));
  PetscFunctionReturn(0);
}

PetscErrorCode StateSpace::pack(Vec X, Vec V, Vec Y) {
  PetscFunctionBeginUser;
  PetscScalar* y;
  PetscCall(VecGetArray(Y, &y));
  PetscCall(place(_c, y));
  PetscCall(VecCopy(X, _c.u));
  PetscCall(VecCopy(V, _c.v));
  PetscCall(reset(_c));
  PetscCall(VecRestoreArray(Y, &y));
  PetscFunctionReturn(0);
}

// A plain copy (no views: unpack may run while a view is held, e.g. in a step callback).
PetscErrorCode StateSpace::unpack(Vec Y, Vec X, Vec V) {
  PetscFunctionBeginUser;
  const PetscScalar* y;
  PetscScalar *x, *v;
  PetscCall(VecGetArrayRead(Y, &y));
  PetscCall(VecGetArray(X, &x));
  PetscCall(VecGetArray(V, &v));
  for (PetscInt i = 0; i < _n; ++i) {
    x[i] = y[i];
    v[i] = y[_n + i];
  }
  PetscCall(VecRestoreArray(V, &v));
  PetscCall(VecRestoreArray(X, &x));
  PetscCall(VecRestoreArrayRead(Y, &y));
  PetscFunctionReturn(0);
}

PetscErrorCode StateSpace::view(Vec Y, Vec* X, Vec* V) {
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(Y, &_viewed));
  PetscCall(place(_view, _viewed));
  *X = _view.u;
  *V = _view.v;
  PetscFunctionReturn(0);
}

PetscErrorCode StateSpace::releaseView(Vec Y) {
  PetscFunctionBeginUser;
  PetscCall(reset(_view));
  PetscCall(VecRestoreArrayRead(Y, &_viewed));
  PetscFunctionReturn(0);
}

PetscErrorCode StateSpace::prescribedMotion(PetscReal t) {
  PetscFunctionBeginUser;
  if (!_asm.model().hasPrescribedMotion()) PetscFunctionReturn(0);  // _up, _vp, _ap stay zero
  for (Vec v : {_up, _vp, _ap}) PetscCall(VecSet(v, 0.0));
  PetscCall(_asm.prescribedMotion(t, _up, _vp, _ap));
  PetscFunctionReturn(0);
}

PetscErrorCode StateSpace::prescribe(PetscReal t, Vec Y) {
  PetscFunctionBeginUser;
  PetscScalar* y;
  PetscCall(VecGetArray(Y, &y));
  PetscCall(place(_c, y));
  PetscCall(_asm.prescribedMotion(t, _c.u, _c.v, nullptr));
  PetscCall(reset(_c));
  PetscCall(VecRestoreArray(Y, &y));
  PetscFunctionReturn(0);
}

// a = M_ff^{-1} (f_ext - f_int(u, v) - M_fs a_p) on free rows, a_p on supported rows; needs
// prescribedMotion(t) first (acceleration() calls it, rhsFunction has).
PetscErrorCode StateSpace::acceleration(PetscReal t, Vec X, Vec V, Vec A) {
  PetscFunctionBeginUser;
  PetscCall(prescribedMotion(t));
  PetscCall(_asm.residual(X, _damped ? V : nullptr, t, _w1));
  PetscCall(MatMultAdd(_M, _ap, _w1, _w1));
  PetscCall(_asm.zeroSupportedRows(_w1));
  PetscCall(VecScale(_w1, -1.0));
  PetscCall(KSPSolve(_massSolver, _w1, A));
  PetscCall(VecAXPY(A, 1.0, _ap));  // the supported rows of the solution are zero
  PetscFunctionReturn(0);
}

PetscErrorCode StateSpace::rhsFunction(TS, PetscReal t, Vec Y, Vec F, void* ctx) {
  PetscFunctionBeginUser;
  auto* s = static_cast<StateSpace*>(ctx);
  const PetscScalar* y;
  PetscScalar* f;
  PetscCall(VecGetArrayRead(Y, &y));
  PetscCall(VecGetArray(F, &f));
  PetscCall(s->place(s->_a, y));
  PetscCall(s->place(s->_c, f));
  PetscCall(s->acceleration(t, s->_a.u, s->_a.v, s->_c.v));
  PetscCall(VecPointwiseMult(s->_c.u, s->_a.v, s->_free));  // u' = v, v_p on supported rows
  PetscCall(VecAXPY(s->_c.u, 1.0, s->_vp));
  PetscCall(s->reset(s->_a));
  PetscCall(s->reset(s->_c));
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(Y, &y));
  PetscFunctionReturn(0);
}

PetscErrorCode StateSpace::iFunction(TS, PetscReal t, Vec Y, Vec Ydot, Vec F, void* ctx) {
  PetscFunctionBeginUser;
  auto* s = static_cast<StateSpace*>(ctx);
  PetscCall(s->prescribedMotion(t));
  const PetscScalar *y, *yd;
  PetscScalar* f;
  PetscCall(VecGetArrayRead(Y, &y));
  PetscCall(VecGetArrayRead(Ydot, &yd));
  PetscCall(VecGetArray(F, &f));
  PetscCall(s->place(s->_a, y));
  PetscCall(s->place(s->_b, yd));
  PetscCall(s->place(s->_c, f));
  const Halves &q = s->_a, &qd = s->_b, &r = s->_c;
  // u rows: u' - v (free), u - u_p (supported)
  PetscCall(VecWAXPY(r.u, -1.0, q.v, qd.u));
  PetscCall(VecPointwiseMult(r.u, r.u, s->_free));
  PetscCall(VecWAXPY(s->_w1, -1.0, s->_up, q.u));
  PetscCall(VecPointwiseMult(s->_w1, s->_w1, s->_supported));
  PetscCall(VecAXPY(r.u, 1.0, s->_w1));
  // v rows: M v~' + f_int - f_ext (free), v - v_p (supported)
  PetscCall(s->_asm.residual(q.u, s->_damped ? q.v : nullptr, t, r.v));
  PetscCall(VecPointwiseMult(s->_w1, qd.v, s->_free));
  PetscCall(VecAXPY(s->_w1, 1.0, s->_ap));
  PetscCall(MatMultAdd(s->_M, s->_w1, r.v, r.v));
  PetscCall(VecPointwiseMult(r.v, r.v, s->_free));
  PetscCall(VecWAXPY(s->_w1, -1.0, s->_vp, q.v));
  PetscCall(VecPointwiseMult(s->_w1, s->_w1, s->_supported));
  PetscCall(VecAXPY(r.v, 1.0, s->_w1));
  for (Halves* h : {&s->_a, &s->_b, &s->_c}) PetscCall(s->reset(*h));
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(Ydot, &yd));
  PetscCall(VecRestoreArrayRead(Y, &y));
  PetscFunctionReturn(0);
}

PetscErrorCode StateSpace::iJacobian(TS, PetscReal t, Vec Y, Vec, PetscReal shift, Mat, Mat, void* ctx) {
  PetscFunctionBeginUser;
  auto* s = static_cast<StateSpace*>(ctx);
  s->_sigma = shift;
  const PetscScalar* y;
  PetscCall(VecGetArrayRead(Y, &y));
  PetscCall(s->place(s->_a, y));
  PetscCall(s->_asm.dynamicJacobian(s->_a.u, s->_damped ? s->_a.v : nullptr, t, shift, shift * shift, s->_reduced,
                                    s->_damped ? s->_D : nullptr));
  PetscCall(s->reset(s->_a));
  PetscCall(VecRestoreArrayRead(Y, &y));
  PetscCall(KSPSetOperators(s->_reducedSolver, s->_reduced, s->_reduced));
  PetscFunctionReturn(0);
}

// y = [sigma x_u - x_v; K x_u + (sigma M + D) x_v] on free rows, [x_u; x_v] on supported rows, with
// K x_u = J x_u - (sigma D + sigma^2 M) x_u for the assembled J = K + sigma D + sigma^2 M.
PetscErrorCode StateSpace::shellMult(Mat J, Vec x, Vec y) {
  PetscFunctionBeginUser;
  StateSpace* s;
  PetscCall(MatShellGetContext(J, &s));
  const PetscReal sg = s->_sigma;
  const PetscScalar* xa;
  PetscScalar* ya;
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArray(y, &ya));
  PetscCall(s->place(s->_a, xa));
  PetscCall(s->place(s->_c, ya));
  const Halves &in = s->_a, &out = s->_c;
  Vec xuf = s->_w1, w = s->_w2;
  PetscCall(VecPointwiseMult(xuf, in.u, s->_free));
  PetscCall(VecWAXPY(out.u, -1.0, in.v, in.u));  // sigma x_u - x_v, then supported rows x_u
  PetscCall(VecAXPY(out.u, sg - 1.0, in.u));
  PetscCall(VecPointwiseMult(out.u, out.u, s->_free));
  PetscCall(VecAXPY(out.u, 1.0, in.u));
  PetscCall(VecAXPY(out.u, -1.0, xuf));
  PetscCall(MatMult(s->_reduced, xuf, out.v));  // J x_uf + (sigma M + D)(x_vf - sigma x_uf)
  PetscCall(VecPointwiseMult(w, in.v, s->_free));
  PetscCall(VecAXPY(w, -sg, xuf));
  PetscCall(MatMult(s->_M, w, xuf));  // xuf is free now
  PetscCall(VecAXPY(out.v, sg, xuf));
  if (s->_damped) PetscCall(MatMultAdd(s->_D, w, out.v, out.v));
  PetscCall(VecPointwiseMult(out.v, out.v, s->_free));
  PetscCall(VecPointwiseMult(w, in.v, s->_supported));
  PetscCall(VecAXPY(out.v, 1.0, w));
  PetscCall(s->reset(s->_a));
  PetscCall(s->reset(s->_c));
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscFunctionReturn(0);
}

// The exact inverse of shellMult: (K + sigma D + sigma^2 M) x_u = r_v + (sigma M + D) r_u (free
// rows; r_u on supported rows), x_v = sigma x_u - r_u (free rows; r_v on supported rows).
PetscErrorCode StateSpace::shellApply(PC pc, Vec r, Vec x) {
  PetscFunctionBeginUser;
  StateSpace* s;
  PetscCall(PCShellGetContext(pc, &s));
  const PetscReal sg = s->_sigma;
  const PetscScalar* ra;
  PetscScalar* xa;
  PetscCall(VecGetArrayRead(r, &ra));
  PetscCall(VecGetArray(x, &xa));
  PetscCall(s->place(s->_a, ra));
  PetscCall(s->place(s->_c, xa));
  const Halves &in = s->_a, &out = s->_c;
  Vec ruf = s->_w1, b = s->_w2;
  PetscCall(VecPointwiseMult(ruf, in.u, s->_free));
  PetscCall(MatMult(s->_M, ruf, b));
  PetscCall(VecScale(b, sg));
  if (s->_damped) PetscCall(MatMultAdd(s->_D, ruf, b, b));
  PetscCall(VecAXPY(b, 1.0, in.v));
  PetscCall(VecPointwiseMult(b, b, s->_free));
  PetscCall(VecAXPY(b, 1.0, in.u));
  PetscCall(VecAXPY(b, -1.0, ruf));  // supported rows: r_u
  PetscCall(KSPSolve(s->_reducedSolver, b, out.u));
  PetscCall(VecWAXPY(out.v, -1.0, in.u, out.u));
  PetscCall(VecAXPY(out.v, sg - 1.0, out.u));
  PetscCall(VecPointwiseMult(out.v, out.v, s->_free));
  PetscCall(VecPointwiseMult(b, in.v, s->_supported));
  PetscCall(VecAXPY(out.v, 1.0, b));
  PetscCall(s->reset(s->_a));
  PetscCall(s->reset(s->_c));
  PetscCall(VecRestoreArray(x, &xa));
  PetscCall(VecRestoreArrayRead(r, &ra));
  PetscFunctionReturn(0);
}

PetscErrorCode StateSpace::setImplicit(TS ts) {
  PetscFunctionBeginUser;
  MPI_Comm comm = _asm.dofs().comm();
  if (!_shell) {
    PetscCall(MatCreateShell(comm, 2 * _n, 2 * _n, 2 * _N, 2 * _N, this, &_shell));
    PetscCall(MatShellSetOperation(_shell, MATOP_MULT, reinterpret_cast<void (*)(void)>(shellMult)));
    PetscCall(_asm.dofs().createMatrix(&_reduced, "dyn_reduced_"));
    if (_damped) PetscCall(_asm.dofs().createMatrix(&_D, "dyn_reduced_"));
    PetscCall(KSPCreate(comm, &_reducedSolver));
    PetscCall(KSPSetOptionsPrefix(_reducedSolver, "dyn_reduced_"));
    PetscCall(setDirectSolverDefaults(_reducedSolver, false));
    PetscCall(KSPSetFromOptions(_reducedSolver));
  }
  PetscCall(TSSetIFunction(ts, nullptr, iFunction, this));
  PetscCall(TSSetIJacobian(ts, _shell, _shell, iJacobian, this));
  SNES snes;
  KSP ksp;
  PC pc;
  PetscCall(TSGetSNES(ts, &snes));
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCSHELL));
  PetscCall(PCShellSetContext(pc, this));
  PetscCall(PCShellSetApply(pc, shellApply));
  PetscCall(PCShellSetName(pc, "strand state-space Schur complement (exact; factored matrix: -dyn_reduced_)"));
  PetscFunctionReturn(0);
}

PetscErrorCode StateSpace::setExplicit(TS ts) {
  PetscFunctionBeginUser;
  PetscCall(TSSetRHSFunction(ts, nullptr, rhsFunction, this));
  PetscFunctionReturn(0);
}

}  // namespace strand::solvers
