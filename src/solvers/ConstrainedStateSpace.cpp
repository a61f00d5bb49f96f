// BDF with joints: the GGL stabilized index-2 form, or the plain index-3 form
// (ConstrainedStateSpace.hpp).
#include "strand/solvers/ConstrainedStateSpace.hpp"

#include <algorithm>

namespace strand::solvers {

ConstrainedStateSpace::ConstrainedStateSpace(assembly::Assembler& assembler, StateSpace& space, Vec supported,
                                             Vec multipliers, bool damped, Form form)
    : _asm(assembler), _space(space), _damped(damped), _form(form) {
  const model::DofMap& dofs = assembler.dofs();
  MPI_Comm comm = dofs.comm();
  PetscInt N;
  PetscCallAbort(comm, VecGetLocalSize(supported, &_n));
  PetscCallAbort(comm, VecGetSize(supported, &N));
  PetscCallAbort(comm, VecGetOwnershipRange(supported, &_rstart, nullptr));
  const PetscInt* ranges;
  PetscCallAbort(comm, VecGetOwnershipRanges(supported, &ranges));
  PetscMPIInt size;
  PetscCallAbort(comm, MPI_Comm_size(comm, &size));
  _ranges.assign(ranges, ranges + size + 1);
  for (Vec* v : {&_free, &_multiplierRows, &_otherRows, &_w}) PetscCallAbort(comm, VecDuplicate(supported, v));
  PetscCallAbort(comm, VecSet(_free, 1.0));
  PetscCallAbort(comm, VecAXPY(_free, -1.0, supported));
  PetscCallAbort(comm, VecPointwiseMult(_multiplierRows, multipliers, _free));
  PetscCallAbort(comm, VecSet(_otherRows, 1.0));
  PetscCallAbort(comm, VecAXPY(_otherRows, -1.0, _multiplierRows));
  const PetscScalar *s, *m;
  PetscCallAbort(comm, VecGetArrayRead(supported, &s));
  PetscCallAbort(comm, VecGetArrayRead(_multiplierRows, &m));
  for (PetscInt i = 0; i < _n; ++i) {
    _supportedRow.push_back(s[i] != 0.0);
    _multiplierRow.push_back(m[i] != 0.0);
  }
  PetscCallAbort(comm, VecRestoreArrayRead(_multiplierRows, &m));
  PetscCallAbort(comm, VecRestoreArrayRead(supported, &s));
  for (Vec* h : {_a, _c})
    for (int k = 0; k < 2; ++k) PetscCallAbort(comm, VecCreateMPIWithArray(comm, 1, _n, N, nullptr, &h[k]));
  for (Mat* A : {&_K, &_M, &_C, &_dC}) PetscCallAbort(comm, dofs.createMatrix(A, "dyn_ggl_"));
  if (damped) PetscCallAbort(comm, dofs.createMatrix(&_D, "dyn_ggl_"));
  PetscCallAbort(comm, assembler.massMatrix(_M, true));
}

ConstrainedStateSpace::~ConstrainedStateSpace() {
  for (Vec* v : {&_free, &_multiplierRows, &_otherRows, &_w, &_atol, &_rtol}) VecDestroy(v);
  for (Vec* h : {_a, _c})
    for (int k = 0; k < 2; ++k) VecDestroy(&h[k]);
  for (Mat* A : {&_K, &_D, &_M, &_C, &_dC, &_J}) MatDestroy(A);
}

PetscErrorCode ConstrainedStateSpace::place(Vec* h, const PetscScalar* a) {
  PetscFunctionBeginUser;
  PetscCall(VecPlaceArray(h[0], a));
  PetscCall(VecPlaceArray(h[1], a + _n));
  PetscFunctionReturn(0);
}

PetscErrorCode ConstrainedStateSpace::reset(Vec* h) {
  PetscFunctionBeginUser;
  PetscCall(VecResetArray(h[0]));
  PetscCall(VecResetArray(h[1]));
  PetscFunctionReturn(0);
}

PetscInt ConstrainedStateSpace::doubled(PetscInt col, int half) const {
  const auto r = std::upper_bound(_ranges.begin(), _ranges.end(), col) - _ranges.begin() - 1;
  return col + _ranges[r] + half * (_ranges[r + 1] - _ranges[r]);
}

// The unconstrained residual (StateSpace), then the u-half of the multiplier rows and the GGL term.
PetscErrorCode ConstrainedStateSpace::residual(PetscReal t, Vec Y, Vec Ydot, Vec F) {
  PetscFunctionBeginUser;
  PetscCall(_space.implicitResidual(t, Y, Ydot, F));
  const PetscScalar* y;
  PetscScalar* f;
  PetscCall(VecGetArrayRead(Y, &y));
  PetscCall(VecGetArray(F, &f));
  PetscCall(place(_a, y));
  PetscCall(place(_c, f));
  // keep u' - v on coordinate rows and u - u_p on supported rows; multiplier rows anew
  PetscCall(VecPointwiseMult(_c[0], _c[0], _otherRows));
  if (_form == Form::Ggl) {  // + s G^T mu~ on coordinate rows, s G v on multiplier rows
    PetscCall(_asm.constraintGradientProduct(_a[0], _a[1], _w));
    PetscCall(VecPointwiseMult(_w, _w, _free));
  } else {  // mu~ = 0 on multiplier rows
    PetscCall(VecPointwiseMult(_w, _multiplierRows, _a[1]));
  }
  PetscCall(VecAXPY(_c[0], 1.0, _w));
  PetscCall(reset(_a));
  PetscCall(reset(_c));
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(Y, &y));
  PetscFunctionReturn(0);
}

namespace {
// A += scale * (row `row` of B), its columns mapped to `half` of the doubled layout.
template <class Map>
PetscErrorCode addRow(Mat A, PetscInt target, Mat B, PetscInt row, PetscScalar scale, const Map& map,
                      std::vector<PetscInt>& cols, std::vector<PetscScalar>& vals) {
  PetscFunctionBeginUser;
  PetscInt nc;
  const PetscInt* c;
  const PetscScalar* v;
  PetscCall(MatGetRow(B, row, &nc, &c, &v));
  cols.resize(nc);
  vals.resize(nc);
  for (PetscInt k = 0; k < nc; ++k) {
    cols[k] = map(c[k]);
    vals[k] = scale * v[k];
  }
  PetscCall(MatSetValues(A, 1, &target, nc, cols.data(), vals.data(), ADD_VALUES));
  PetscCall(MatRestoreRow(B, row, &nc, &c, &v));
  PetscFunctionReturn(0);
}
}  // namespace

PetscErrorCode ConstrainedStateSpace::fill(Mat A, PetscReal sigma) {
  PetscFunctionBeginUser;
  std::vector<PetscInt> cols;
  std::vector<PetscScalar> vals;
  auto toU = [this](PetscInt c) { return doubled(c, 0); };
  auto toV = [this](PetscInt c) { return doubled(c, 1); };
  for (PetscInt i = 0; i < _n; ++i) {
    const PetscInt g = _rstart + i, U = doubled(g, 0), V = doubled(g, 1);
    if (_supportedRow[i]) {  // u - u_p, v - v_p
      PetscCall(MatSetValue(A, U, U, 1.0, ADD_VALUES));
      PetscCall(MatSetValue(A, V, V, 1.0, ADD_VALUES));
      continue;
    }
    PetscCall(addRow(A, V, _K, g, 1.0, toU, cols, vals));  // K_T: elastic, s H(lambda~), s G^T, s G
    PetscCall(addRow(A, V, _M, g, sigma, toV, cols, vals));
    if (_damped) PetscCall(addRow(A, V, _D, g, 1.0, toV, cols, vals));
    if (!_multiplierRow[i]) {  // u' - v
      PetscCall(MatSetValue(A, U, U, sigma, ADD_VALUES));
      PetscCall(MatSetValue(A, U, V, -1.0, ADD_VALUES));
    }
    if (_form == Form::Ggl) {
      PetscCall(addRow(A, U, _dC, g, 1.0, toU, cols, vals));
      PetscCall(addRow(A, U, _C, g, 1.0, toV, cols, vals));
    } else if (_multiplierRow[i]) {
      PetscCall(MatSetValue(A, U, V, 1.0, ADD_VALUES));
    }
  }
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode ConstrainedStateSpace::jacobian(PetscReal t, Vec Y, PetscReal shift, Mat* J) {
  PetscFunctionBeginUser;
  const PetscScalar* y;
  PetscCall(VecGetArrayRead(Y, &y));
  PetscCall(place(_a, y));
  PetscCall(_asm.dynamicJacobian(_a[0], _damped ? _a[1] : nullptr, t, 0.0, 0.0, _K, _damped ? _D : nullptr));
  if (_form == Form::Ggl) PetscCall(_asm.constraintGradientMatrices(_a[0], _a[1], _C, _dC));
  PetscCall(reset(_a));
  PetscCall(VecRestoreArrayRead(Y, &y));
  MPI_Comm comm = _asm.dofs().comm();
  if (!_J) {  // exact preallocation: the rows' pattern once through a preallocator
    const PetscInt N = 2 * _ranges.back();
    Mat pre;
    PetscCall(MatCreate(comm, &pre));
    PetscCall(MatSetSizes(pre, 2 * _n, 2 * _n, N, N));
    PetscCall(MatSetType(pre, MATPREALLOCATOR));
    PetscCall(MatSetUp(pre));
    PetscCall(fill(pre, shift));
    PetscCall(MatCreate(comm, &_J));
    PetscCall(MatSetSizes(_J, 2 * _n, 2 * _n, N, N));
    PetscCall(MatSetType(_J, MATAIJ));
    PetscCall(MatPreallocatorPreallocate(pre, PETSC_TRUE, _J));
    PetscCall(MatSetOption(_J, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
    PetscCall(MatDestroy(&pre));
  }
  PetscCall(MatZeroEntries(_J));
  PetscCall(fill(_J, shift));
  if (J) *J = _J;
  PetscFunctionReturn(0);
}

PetscErrorCode ConstrainedStateSpace::iFunction(TS, PetscReal t, Vec Y, Vec Ydot, Vec F, void* ctx) {
  return static_cast<ConstrainedStateSpace*>(ctx)->residual(t, Y, Ydot, F);
}

PetscErrorCode ConstrainedStateSpace::iJacobian(TS, PetscReal t, Vec Y, Vec, PetscReal shift, Mat, Mat, void* ctx) {
  return static_cast<ConstrainedStateSpace*>(ctx)->jacobian(t, Y, shift, nullptr);
}

PetscErrorCode ConstrainedStateSpace::setImplicit(TS ts) {
  PetscFunctionBeginUser;
  if (!_J) {  // the matrix (and its pattern) at the zero state
    Vec Y;
    PetscCall(_space.createState(&Y));
    PetscCall(VecSet(Y, 0.0));
    PetscCall(jacobian(0.0, Y, 1.0, nullptr));
    PetscCall(VecDestroy(&Y));
  }
  PetscCall(TSSetIFunction(ts, nullptr, iFunction, this));
  PetscCall(TSSetIJacobian(ts, _J, _J, iJacobian, this));
  // MUMPS: the doubled system has two zero diagonal blocks (both multipliers), whose delayed pivots
  // outgrow MUMPS's default workspace estimate (+20 %): measured on the 20-link chain, the first
  // factorization fails with FACTOR_OUTMEMORY (INFOG(1) = -9) at 20 % and passes at 100 %.
  // -dyn_mat_mumps_icntl_14 still overrides it.
  SNES snes;
  KSP ksp;
  PC pc;
  PetscBool lu;
  MatSolverType type = nullptr;
  PetscCall(TSGetSNES(ts, &snes));
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCLU, &lu));
  if (lu) PetscCall(PCFactorGetMatSolverType(pc, &type));
  PetscBool mumps = PETSC_FALSE;
  if (type) PetscCall(PetscStrcmp(type, MATSOLVERMUMPS, &mumps));
  if (mumps) {
    Mat F;
    PetscCall(KSPSetOperators(ksp, _J, _J));
    PetscCall(PCFactorSetUpMatSolverType(pc));
    PetscCall(PCFactorGetMatrix(pc, &F));
    PetscCall(MatMumpsSetIcntl(F, 14, 100));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ConstrainedStateSpace::setTolerances(TS ts, PetscReal atol, PetscReal rtol) {
  PetscFunctionBeginUser;
  if (_form == Form::Index3) PetscFunctionReturn(0);  // the scalar tolerances: every unknown in the norm
  PetscCall(_space.createState(&_atol));
  PetscCall(VecDuplicate(_atol, &_rtol));
  PetscScalar *a, *r;
  PetscCall(VecGetArray(_atol, &a));
  PetscCall(VecGetArray(_rtol, &r));
  for (PetscInt i = 0; i < _n; ++i)
    for (PetscInt half = 0; half < 2; ++half) {
      a[half * _n + i] = _multiplierRow[i] ? 0.0 : atol;
      r[half * _n + i] = _multiplierRow[i] ? 0.0 : rtol;
    }
  PetscCall(VecRestoreArray(_rtol, &r));
  PetscCall(VecRestoreArray(_atol, &a));
  PetscCall(TSSetTolerances(ts, atol, _atol, rtol, _rtol));
  PetscFunctionReturn(0);
}

}  // namespace strand::solvers
