#include "strand/assembly/Assembler.hpp"

#include <algorithm>
#include <cmath>

#include "ElementFamily.hpp"
#include "Multibody.hpp"
#include "NodalMomentLoads.hpp"
#include "PulleyContacts.hpp"
#include "Reels.hpp"

namespace strand::assembly {

namespace {
PetscLogEvent evResidual = 0, evJacobian = 0, evMass = 0, evDynJacobian = 0, evContact = 0;
void registerEvents() {
  static bool done = false;
  if (done) return;
  PetscClassId cid;
  PetscClassIdRegister("Strand", &cid);
  PetscLogEventRegister("Strand:Asm:Resid", cid, &evResidual);
  PetscLogEventRegister("Strand:Asm:Jacob", cid, &evJacobian);
  PetscLogEventRegister("Strand:Asm:Mass", cid, &evMass);
  PetscLogEventRegister("Strand:Asm:DynJac", cid, &evDynJacobian);
  PetscLogEventRegister("Strand:Asm:Contact", cid, &evContact);  // inside the three above
  done = true;
}
}  // namespace

Assembler::Assembler(const model::Model& model, const model::DofMap& dofs) : _model(model), _dofs(dofs) {
  registerEvents();
  PetscCallAbort(dofs.comm(), dofs.createVector(&_xWork));
  PetscCallAbort(dofs.comm(), VecDuplicate(_xWork, &_rWork));
  PetscCallAbort(dofs.comm(), VecDuplicate(_xWork, &_vWork));
  // supports and initial coordinates in the ghosted local numbering
  const PetscInt bs = dofs.blockSize();
  PetscInt nLocal = 0;
  {
    Vec xl;
    PetscCallAbort(dofs.comm(), VecGhostGetLocalForm(_xWork, &xl));
    PetscCallAbort(dofs.comm(), VecGetLocalSize(xl, &nLocal));
    PetscCallAbort(dofs.comm(), VecGhostRestoreLocalForm(_xWork, &xl));
  }
  {
    PetscInt owned;
    PetscCallAbort(dofs.comm(), VecGetLocalSize(_xWork, &owned));
    int ghosts = nLocal > owned ? 1 : 0, any = 0;
    MPI_Allreduce(&ghosts, &any, 1, MPI_INT, MPI_MAX, dofs.comm());
    _haveGhosts = any != 0;
  }
  _fixedLocal.assign(nLocal, 0);
  _q0Local.assign(nLocal, 0.0);
  _multiplierOwned.assign(dofs.ownedBlocks() * bs, 0);
  _v0Owned.assign(dofs.ownedBlocks() * bs, 0.0);
  for (int b = 0; b < model.numBlocks(); ++b) {
    const PetscInt lb = dofs.localBlock(dofs.globalBlock()[b]);
    if (lb < 0) continue;
    for (PetscInt i = 0; i < bs; ++i) {
      _fixedLocal[lb * bs + i] = model.fixedDofs()[b * bs + i];
      _q0Local[lb * bs + i] = model.initialCoordinates()[b * bs + i];
      if (lb < dofs.ownedBlocks()) {
        const double force = model.nodalForces()[b * bs + i];
        if (force != 0.0) _nodalForceOwned.push_back({lb * bs + i, force});
        _multiplierOwned[lb * bs + i] = model.multiplierDofs()[b * bs + i];
        _v0Owned[lb * bs + i] = model.initialVelocities()[b * bs + i];
      }
    }
  }
  for (PetscInt i = 0; i < dofs.ownedBlocks() * bs; ++i)
    if (_fixedLocal[i]) _fixedOwned.push_back(i);
  _noneFixed.assign(nLocal, 0);
  for (int h = 0; h < static_cast<int>(model.hubMotions().size()); ++h) {
    const model::HubMotion& hub = model.hubMotions()[h];
    for (int k = 0; k < static_cast<int>(hub.blocks.size()); ++k) {
      const PetscInt lb = dofs.localBlock(dofs.globalBlock()[hub.blocks[k]]);
      if (lb < 0 || lb >= dofs.ownedBlocks()) continue;
      _moved.push_back({lb * bs, h, k});
    }
  }
  for (int k = 0; k < static_cast<int>(model.prescribedCoordinates().size()); ++k) {
    const int dof = model.prescribedCoordinates()[k].dof;
    const PetscInt lb = dofs.localBlock(dofs.globalBlock()[dof / bs]);
    if (lb < 0 || lb >= dofs.ownedBlocks()) continue;
    const model::TimeFunction& f = model.prescribedCoordinates()[k].function;
    auto it = std::find_if(_movedFunctions.begin(), _movedFunctions.end(),
                           [&](const model::TimeFunction* g) { return *g == f; });
    if (it == _movedFunctions.end()) it = _movedFunctions.insert(_movedFunctions.end(), &f);
    _movedCoordinates.push_back({lb * bs + dof % bs, static_cast<int>(it - _movedFunctions.begin()),
                                 model.prescribedCoordinates()[k].scale, false});
  }
  std::stable_sort(_movedCoordinates.begin(), _movedCoordinates.end(),
                   [](const MovedCoordinate& a, const MovedCoordinate& b) { return a.owned < b.owned; });
  for (size_t k = 0; k < _movedCoordinates.size(); ++k)
    _movedCoordinates[k].first = k == 0 || _movedCoordinates[k - 1].owned != _movedCoordinates[k].owned;
  _movedValues.resize(_movedFunctions.size());
  for (const model::DofMap::LocalGroup& local : dofs.localGroups())
    _families.push_back(makeElementFamily(model, dofs, local, _q0Local));
  _moments = std::make_unique<NodalMomentLoads>(model, dofs, _q0Local);
  _multibody = std::make_unique<Multibody>(model, dofs, _q0Local);
  _contacts = std::make_unique<PulleyContacts>(model, dofs, _q0Local);
  _reels = std::make_unique<Reels>(model, dofs);
}

Assembler::~Assembler() {
  VecDestroy(&_xWork);
  VecDestroy(&_rWork);
  VecDestroy(&_vWork);
  VecDestroy(&_inertiaWork);
  VecDestroy(&_aWork);
  VecScatterDestroy(&_toRoot);
  VecDestroy(&_rootVec);
}

PetscErrorCode Assembler::initialState(Vec X) const {
  PetscFunctionBeginUser;
  PetscCall(VecSet(X, 0.0));  // unknowns are displacements from the reference shape
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::initialVelocity(Vec V) const {
  PetscFunctionBeginUser;
  PetscScalar* v;
  PetscCall(VecGetArray(V, &v));
  for (size_t i = 0; i < _v0Owned.size(); ++i) v[i] = _v0Owned[i];
  PetscCall(VecRestoreArray(V, &v));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::multiplierMask(Vec mask) const {
  PetscFunctionBeginUser;
  PetscScalar* m;
  PetscCall(VecGetArray(mask, &m));
  for (size_t i = 0; i < _multiplierOwned.size(); ++i) m[i] = _multiplierOwned[i];
  PetscCall(VecRestoreArray(mask, &m));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::supportMask(Vec mask) const {
  PetscFunctionBeginUser;
  PetscScalar* m;
  PetscInt n;
  PetscCall(VecGetLocalSize(mask, &n));
  PetscCall(VecGetArray(mask, &m));
  for (PetscInt i = 0; i < n; ++i) m[i] = _fixedLocal[i] ? 1.0 : 0.0;
  PetscCall(VecRestoreArray(mask, &m));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::saddleMatrix(Vec X, Mat S) {
  PetscFunctionBeginUser;
  LocalRead x;
  PetscCall(beginLocal(X, _xWork, &x));
  PetscCall(MatZeroEntries(S));
  for (const auto& f : _families) PetscCall(f->mass(S, _fixedLocal));
  for (const auto& f : _families) PetscCall(f->massAt(x.a, S, _fixedLocal));  // M(q) of the ALE kinds
  PetscCall(_reels->massAt(x.a, S, _fixedLocal));
  PetscCall(_contacts->mass(S));  // free pulleys
  PetscCall(_multibody->mass(S, _fixedLocal));
  PetscCall(_multibody->jacobian(x.a, 1.0, 0.0, 0.0, S, _fixedLocal, true));
  PetscCall(endLocal(&x));
  PetscCall(assembleWithSupportDiagonal(S));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::jointVector(Vec X, Vec W, const std::function<void(const double*, const double*, double*)>& add,
                                      Vec R) {
  PetscFunctionBeginUser;
  LocalRead x, w;
  LocalSum r;
  PetscCall(beginLocal(X, _xWork, &x));
  PetscCall(beginLocal(W, _vWork, &w));
  PetscCall(beginLocalSum(R, {X, W}, &r));
  add(x.a, w.a, r.a);
  PetscCall(endLocalSum(&r));
  PetscCall(endLocal(&x));
  PetscCall(endLocal(&w));
  PetscCall(deliver(r, R));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::constraintVelocityTerm(Vec X, Vec V, Vec R) {
  return jointVector(X, V, [&](const double* x, const double* v, double* r) { _multibody->velocityTerm(x, v, r); }, R);
}

PetscErrorCode Assembler::constraintGradientProduct(Vec X, Vec W, Vec R) {
  return jointVector(
      X, W, [&](const double* x, const double* w, double* r) { _multibody->gradientProduct(x, w, _constraintScale, r); },
      R);
}

PetscErrorCode Assembler::constraintGradientMatrices(Vec X, Vec W, Mat C, Mat dC) {
  PetscFunctionBeginUser;
  LocalRead x, w;
  PetscCall(beginLocal(X, _xWork, &x));
  PetscCall(beginLocal(W, _vWork, &w));
  for (Mat A : {C, dC})
    if (A) PetscCall(MatZeroEntries(A));
  PetscCall(_multibody->gradientProductJacobian(x.a, w.a, _constraintScale, C, dC, _fixedLocal));
  PetscCall(endLocal(&x));
  PetscCall(endLocal(&w));
  for (Mat A : {C, dC})
    if (A) {
      PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
      PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
    }
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::constraintViolation(Vec X, Vec V, PetscReal* position, PetscReal* velocity) {
  PetscFunctionBeginUser;
  LocalRead x, v;
  PetscCall(beginLocal(X, _xWork, &x));
  PetscCall(beginLocal(V, _vWork, &v));
  double local[2];
  _multibody->violation(x.a, v.a, &local[0], &local[1]);
  PetscCall(endLocal(&x));
  PetscCall(endLocal(&v));
  double global[2];
  PetscCallMPI(MPI_Allreduce(local, global, 2, MPI_DOUBLE, MPI_MAX, _dofs.comm()));
  *position = global[0];
  *velocity = global[1];
  PetscFunctionReturn(0);
}

// The ghosted local form of `from`: its own, ghosts updated in place, when it has our layout (its
// owned values stay as they are, so a read-locked input is fine); else a copy in `work`.
PetscErrorCode Assembler::beginLocal(Vec from, Vec work, LocalRead* view) {
  bool own;
  PetscFunctionBeginUser;
  PetscCall(_dofs.sharesGhosts(from, &own));
  view->owner = own ? from : work;
  if (!own) PetscCall(VecCopy(from, work));
  PetscCall(updateGhosts(view->owner));
  PetscCall(VecGhostGetLocalForm(view->owner, &view->local));
  PetscCall(VecGetArrayRead(view->local, &view->a));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::endLocal(LocalRead* view) {
  PetscFunctionBeginUser;
  PetscCall(VecRestoreArrayRead(view->local, &view->a));
  PetscCall(VecGhostRestoreLocalForm(view->owner, &view->local));
  PetscFunctionReturn(0);
}

// A zeroed ghosted local form to sum element contributions into: R's own when R has our layout
// and is none of the inputs being read, else _rWork's.
PetscErrorCode Assembler::beginLocalSum(Vec R, std::initializer_list<Vec> inputs, LocalSum* sum) {
  bool own;
  PetscFunctionBeginUser;
  PetscCall(_dofs.sharesGhosts(R, &own));
  for (Vec in : inputs) own = own && in != R;
  sum->owner = own ? R : _rWork;
  PetscCall(VecGhostGetLocalForm(sum->owner, &sum->local));
  PetscCall(VecSet(sum->local, 0.0));
  PetscCall(VecGetArray(sum->local, &sum->a));
  PetscFunctionReturn(0);
}

// The ghosts' sums added to their owners: sum->owner holds the owned result.
PetscErrorCode Assembler::endLocalSum(LocalSum* sum) {
  PetscFunctionBeginUser;
  PetscCall(VecRestoreArray(sum->local, &sum->a));
  PetscCall(VecGhostRestoreLocalForm(sum->owner, &sum->local));
  PetscCall(addGhostsToOwners(sum->owner));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::deliver(const LocalSum& sum, Vec R) {
  PetscFunctionBeginUser;
  if (sum.owner != R) PetscCall(VecCopy(sum.owner, R));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::updateGhosts(Vec work) {
  PetscFunctionBeginUser;
  if (_haveGhosts) {
    PetscCall(VecGhostUpdateBegin(work, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecGhostUpdateEnd(work, INSERT_VALUES, SCATTER_FORWARD));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::addGhostsToOwners(Vec work) {
  PetscFunctionBeginUser;
  if (_haveGhosts) {
    PetscCall(VecGhostUpdateBegin(work, ADD_VALUES, SCATTER_REVERSE));
    PetscCall(VecGhostUpdateEnd(work, ADD_VALUES, SCATTER_REVERSE));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::staticResidual(Vec X, PetscReal loadFactor, Vec R) {
  PetscFunctionBeginUser;
  PetscCall(assembleResidual(X, nullptr, 0.0, loadFactor, R, SupportRows::Value));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::residual(Vec X, Vec V, PetscReal t, Vec R, SupportRows rows) {
  PetscFunctionBeginUser;
  PetscCall(assembleResidual(X, V, t, _model.loadFactor(t), R, rows));
  PetscCall(addTimedLoads(t, R, -1.0, rows == SupportRows::Value));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::residualWithInertia(Vec X, Vec V, Vec A, bool damped, PetscReal t, Vec R, SupportRows rows) {
  PetscFunctionBeginUser;
  PetscCall(assembleResidual(X, V, t, _model.loadFactor(t), R, rows, A, damped));
  PetscCall(addTimedLoads(t, R, -1.0, rows == SupportRows::Value));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::assembleResidual(Vec X, Vec V, PetscReal t, PetscReal loadFactor, Vec R, SupportRows rows,
                                           Vec A, bool damped) {
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(evResidual, 0, 0, 0, 0));
  LocalRead x, v, a;
  LocalSum r;
  PetscCall(beginLocal(X, _xWork, &x));
  if (V) PetscCall(beginLocal(V, _vWork, &v));
  PetscCheck(!A || V, _dofs.comm(), PETSC_ERR_ARG_NULL, "the residual with inertia needs the velocities");
  if (A) {
    if (!_aWork) PetscCall(VecDuplicate(_xWork, &_aWork));
    PetscCall(beginLocal(A, _aWork, &a));
  }
  PetscCall(beginLocalSum(R, {X, V, A}, &r));
  const double* vd = V && damped ? v.a : nullptr;  // the damping's velocities
  if (A)
    for (const auto& f : _families) PetscCallCXX(f->residualWithInertia(x.a, v.a, a.a, damped, loadFactor, r.a));
  else
    for (const auto& f : _families) PetscCallCXX(f->residual(x.a, vd, loadFactor, r.a));
  _moments->residual(x.a, loadFactor, r.a);
  PetscCallCXX(_multibody->residual(x.a, _constraintScale, loadFactor, r.a));
  PetscCall(PetscLogEventBegin(evContact, 0, 0, 0, 0));
  _contacts->residual(x.a, vd, t, r.a);
  _contacts->pulleyResidual(x.a, vd, r.a);  // free pulleys' damping, tensioners' springs
  PetscCall(PetscLogEventEnd(evContact, 0, 0, 0, 0));
  _reels->residual(vd, r.a);  // reels' damping
  if (A) _reels->inertiaResidual(x.a, a.a, r.a);
  PetscCall(endLocalSum(&r));
  // owned rows: nodal forces and supports
  PetscScalar* owned;
  PetscCall(VecGetArray(r.owner, &owned));
  for (const auto& [i, f] : _nodalForceOwned) owned[i] -= loadFactor * f;
  if (rows == SupportRows::Value)
    for (PetscInt i : _fixedOwned) owned[i] = x.a[i];
  PetscCall(VecRestoreArray(r.owner, &owned));
  PetscCall(endLocal(&x));
  if (V) PetscCall(endLocal(&v));
  if (A) PetscCall(endLocal(&a));
  PetscCall(deliver(r, R));
  PetscCall(PetscLogEventEnd(evResidual, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

// The unit diagonal of supported rows (the element matrices were masked), then final assembly.
PetscErrorCode Assembler::assembleWithSupportDiagonal(Mat J) const {
  PetscFunctionBeginUser;
  const PetscInt row0 = _dofs.ownedBegin() * _dofs.blockSize();
  for (PetscInt i : _fixedOwned) PetscCall(MatSetValue(J, row0 + i, row0 + i, 1.0, ADD_VALUES));
  PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::staticJacobian(Vec X, PetscReal loadFactor, Mat J) {
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(evJacobian, 0, 0, 0, 0));
  LocalRead x;
  PetscCall(beginLocal(X, _xWork, &x));
  PetscCall(MatZeroEntries(J));
  for (const auto& f : _families) PetscCall(f->jacobian(x.a, loadFactor, J, _fixedLocal));
  PetscCall(_moments->jacobian(x.a, loadFactor, J, _fixedLocal));
  PetscCall(_multibody->jacobian(x.a, _constraintScale, 0.0, loadFactor, J, _fixedLocal));
  PetscCall(PetscLogEventBegin(evContact, 0, 0, 0, 0));
  PetscCall(_contacts->jacobian(x.a, nullptr, 0.0, 0.0, J, nullptr, _fixedLocal));
  PetscCall(PetscLogEventEnd(evContact, 0, 0, 0, 0));
  PetscCall(endLocal(&x));
  PetscCall(assembleWithSupportDiagonal(J));
  PetscCall(PetscLogEventEnd(evJacobian, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::dynamicJacobian(Vec X, Vec V, PetscReal t, PetscReal shiftV, PetscReal shiftA, Mat J, Mat D,
                                          Vec A) {
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(evDynJacobian, 0, 0, 0, 0));
  LocalRead x, v;
  PetscCall(beginLocal(X, _xWork, &x));
  if (V) PetscCall(beginLocal(V, _vWork, &v));
  PetscCall(MatZeroEntries(J));
  if (D) PetscCall(MatZeroEntries(D));
  const double loadFactor = _model.loadFactor(t);
  // with A: the variable-mass kinds' inertia in the same element matrices (the reels' below)
  const bool inertia = A && V && hasVariableMass();
  LocalRead a;
  if (inertia) {
    if (!_aWork) PetscCall(VecDuplicate(_xWork, &_aWork));
    PetscCall(beginLocal(A, _aWork, &a));
  }
  for (const auto& f : _families)
    PetscCall(f->dynamicJacobian(x.a, v.a, loadFactor, shiftV, shiftA, J, D, _fixedLocal, inertia ? a.a : nullptr));
  PetscCall(_moments->jacobian(x.a, loadFactor, J, _fixedLocal));
  PetscCall(_multibody->jacobian(x.a, _constraintScale, shiftA, loadFactor, J, _fixedLocal));
  PetscCall(PetscLogEventBegin(evContact, 0, 0, 0, 0));
  PetscCall(_contacts->jacobian(x.a, V ? v.a : nullptr, t, shiftV, J, D, _fixedLocal));
  PetscCall(_contacts->pulleyMatrices(shiftV, shiftA, J, D));
  PetscCall(PetscLogEventEnd(evContact, 0, 0, 0, 0));
  PetscCall(_reels->dampingMatrices(shiftV, J, D, _fixedLocal));
  if (inertia) {
    PetscCall(_reels->inertiaJacobian(x.a, a.a, shiftA, J, _fixedLocal));
    PetscCall(endLocal(&a));
  }
  PetscCall(endLocal(&x));
  if (V) PetscCall(endLocal(&v));
  PetscCall(assembleWithSupportDiagonal(J));
  if (D) {
    PetscCall(MatAssemblyBegin(D, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(D, MAT_FINAL_ASSEMBLY));
  }
  PetscCall(PetscLogEventEnd(evDynJacobian, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::externalForce(Vec F) {
  PetscFunctionBeginUser;
  Vec X0, R1;
  PetscCall(VecDuplicate(F, &X0));
  PetscCall(VecDuplicate(F, &R1));
  PetscCall(VecSet(X0, 0.0));
  // supported rows included (Reaction rows): the energy balance needs the loads' power on moving supports
  PetscCall(assembleResidual(X0, nullptr, 0.0, 0.0, F, SupportRows::Reaction));   // f_int(0)
  PetscCall(assembleResidual(X0, nullptr, 0.0, 1.0, R1, SupportRows::Reaction));  // f_int(0) - f_ext
  PetscCall(VecAXPY(F, -1.0, R1));
  PetscCall(VecDestroy(&X0));
  PetscCall(VecDestroy(&R1));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::massMatrix(Mat M, bool maskSupports) {
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(evMass, 0, 0, 0, 0));
  PetscCall(MatZeroEntries(M));
  for (const auto& f : _families) PetscCall(f->mass(M, maskSupports ? _fixedLocal : _noneFixed));
  PetscCall(_multibody->mass(M, maskSupports ? _fixedLocal : _noneFixed));
  PetscCall(_contacts->mass(M));
  PetscCall(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
  PetscCall(PetscLogEventEnd(evMass, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::addInertia(Vec X, Vec V, Vec A, Vec R) {
  PetscFunctionBeginUser;
  if (!hasVariableMass()) PetscFunctionReturn(0);
  if (!_inertiaWork) PetscCall(VecDuplicate(_xWork, &_inertiaWork));  // the element sums go into its local form
  Vec F = _inertiaWork;
  LocalRead x, v, a;
  LocalSum r;
  PetscCall(beginLocal(X, _xWork, &x));
  PetscCall(beginLocal(V, _vWork, &v));
  PetscCall(beginLocal(A, _rWork, &a));
  PetscCall(beginLocalSum(F, {X, V, A}, &r));
  for (const auto& f : _families) PetscCallCXX(f->inertia(x.a, v.a, a.a, r.a));
  _reels->inertiaResidual(x.a, a.a, r.a);
  PetscCall(endLocalSum(&r));
  PetscCall(endLocal(&x));
  PetscCall(endLocal(&v));
  PetscCall(endLocal(&a));
  PetscCall(VecAXPY(R, 1.0, F));
  PetscFunctionReturn(0);
}

bool Assembler::hasConfigurationLoads() const {
  for (const auto& f : _families)
    if (f->configurationLoads()) return true;
  return false;
}

PetscErrorCode Assembler::configurationLoads(Vec X, Vec F) {
  PetscFunctionBeginUser;
  LocalRead x;
  LocalSum r;
  PetscCall(beginLocal(X, _xWork, &x));
  PetscCall(beginLocalSum(F, {X}, &r));
  for (const auto& f : _families) PetscCallCXX(f->addConfigurationLoads(x.a, r.a));
  PetscCall(endLocalSum(&r));
  PetscCall(endLocal(&x));
  PetscCall(deliver(r, F));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::inertiaJacobian(Vec X, Vec V, Vec A, PetscReal shiftV, PetscReal shiftA, Mat J) {
  PetscFunctionBeginUser;
  PetscCall(MatZeroEntries(J));
  if (hasVariableMass()) {
    LocalRead x, v, a;
    PetscCall(beginLocal(X, _xWork, &x));
    PetscCall(beginLocal(V, _vWork, &v));
    PetscCall(beginLocal(A, _rWork, &a));
    for (const auto& f : _families) PetscCall(f->inertiaJacobian(x.a, v.a, a.a, shiftV, shiftA, J, _fixedLocal));
    PetscCall(_reels->inertiaJacobian(x.a, a.a, shiftA, J, _fixedLocal));
    PetscCall(endLocal(&a));
    PetscCall(endLocal(&v));
    PetscCall(endLocal(&x));
  }
  PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::massMatrixAt(Vec X, Mat M, bool maskSupports) {
  PetscFunctionBeginUser;
  PetscCall(MatZeroEntries(M));
  const std::vector<char>& fixed = maskSupports ? _fixedLocal : _noneFixed;
  for (const auto& f : _families) PetscCall(f->mass(M, fixed));
  PetscCall(_multibody->mass(M, fixed));
  PetscCall(_contacts->mass(M));
  if (hasVariableMass()) {
    LocalRead x;
    PetscCall(beginLocal(X, _xWork, &x));
    for (const auto& f : _families) PetscCall(f->massAt(x.a, M, fixed));
    PetscCall(_reels->massAt(x.a, M, fixed));
    PetscCall(endLocal(&x));
  }
  PetscCall(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::variableKineticEnergy(Vec X, Vec V, PetscReal* T, PetscReal* loadPower) {
  PetscFunctionBeginUser;
  *T = 0.0;
  if (loadPower) *loadPower = 0.0;
  if (!hasVariableMass()) PetscFunctionReturn(0);
  LocalRead x, v;
  PetscCall(beginLocal(X, _xWork, &x));
  PetscCall(beginLocal(V, _vWork, &v));
  double local[2] = {0.0, 0.0}, global[2];
  for (const auto& f : _families) local[0] += f->kineticEnergy(x.a, v.a, loadPower ? &local[1] : nullptr);
  local[0] += _reels->kineticEnergy(x.a, v.a);
  PetscCall(endLocal(&x));
  PetscCall(endLocal(&v));
  PetscCallMPI(MPI_Allreduce(local, global, 2, MPI_DOUBLE, MPI_SUM, _dofs.comm()));
  *T = global[0];
  if (loadPower) *loadPower = global[1];
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::prescribedMotion(PetscReal t, Vec X, Vec V, Vec A) const {
  PetscFunctionBeginUser;
  if (_moved.empty() && _movedCoordinates.empty()) PetscFunctionReturn(0);
  PetscScalar *x = nullptr, *v = nullptr, *a = nullptr;
  if (X) PetscCall(VecGetArray(X, &x));
  if (V) PetscCall(VecGetArray(V, &v));
  if (A) PetscCall(VecGetArray(A, &a));
  const int D = _model.dim();
  for (const MovedBlock& m : _moved) {
    const model::HubMotion& hub = _model.hubMotions()[m.hub];
    double u[3], du[3], ddu[3];
    hub.state(m.block, &_model.initialCoordinates()[hub.blocks[m.block] * D], D, t, u, du, ddu);
    for (int i = 0; i < D; ++i) {
      if (x) x[m.owned + i] = u[i];
      if (v) v[m.owned + i] = du[i];
      if (a) a[m.owned + i] = ddu[i];
    }
  }
  // the scene's angle is the one at t = 0: phi = angle + f(t) - f(0) (user-guide, "Turning hubs")
  std::vector<model::TimeValue>& f = _movedValues;
  for (size_t k = 0; k < f.size(); ++k) {
    f[k] = _movedFunctions[k]->at(t);
    f[k].f -= _movedFunctions[k]->at(0.0).f;
  }
  // sorted by coordinate: the first function of a coordinate assigns, the others add
  for (const MovedCoordinate& m : _movedCoordinates) {
    const model::TimeValue& fk = f[m.function];
    if (x) x[m.owned] = (m.first ? 0.0 : x[m.owned]) + m.scale * fk.f;
    if (v) v[m.owned] = (m.first ? 0.0 : v[m.owned]) + m.scale * fk.df;
    if (a) a[m.owned] = (m.first ? 0.0 : a[m.owned]) + m.scale * fk.ddf;
  }
  if (X) PetscCall(VecRestoreArray(X, &x));
  if (V) PetscCall(VecRestoreArray(V, &v));
  if (A) PetscCall(VecRestoreArray(A, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::moveSupportedRows(Vec R, Vec to) const {
  PetscFunctionBeginUser;
  PetscScalar *r, *t;
  PetscCall(VecGetArray(R, &r));
  PetscCall(VecGetArray(to, &t));
  for (PetscInt i : _fixedOwned) t[i] = r[i], r[i] = 0.0;
  PetscCall(VecRestoreArray(to, &t));
  PetscCall(VecRestoreArray(R, &r));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::zeroSupportedRows(Vec R) const {
  PetscFunctionBeginUser;
  PetscScalar* r;
  PetscCall(VecGetArray(R, &r));
  for (PetscInt i : _fixedOwned) r[i] = 0.0;
  PetscCall(VecRestoreArray(R, &r));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::gyroscopicMatrix(Mat G) {
  PetscFunctionBeginUser;
  PetscCall(MatZeroEntries(G));
  for (const auto& f : _families) PetscCall(f->gyroscopic(G, _fixedLocal));
  PetscCall(MatAssemblyBegin(G, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(G, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::strainEnergy(Vec X, PetscReal* U) {
  PetscFunctionBeginUser;
  LocalRead x;
  PetscCall(beginLocal(X, _xWork, &x));
  double local = 0.0;
  for (const auto& f : _families) local += f->strainEnergy(x.a);
  local += _contacts->springEnergy(x.a);
  PetscCall(endLocal(&x));
  PetscCallMPI(MPI_Allreduce(&local, U, 1, MPI_DOUBLE, MPI_SUM, _dofs.comm()));
  PetscFunctionReturn(0);
}

PetscReal Assembler::coordinateNorm() const {
  double local = 0.0, global = 0.0;
  const PetscInt n = _dofs.ownedBlocks() * _dofs.blockSize();
  for (PetscInt i = 0; i < n; ++i) local += _q0Local[i] * _q0Local[i];
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, _dofs.comm());
  return std::sqrt(global);
}

PetscErrorCode Assembler::freeDofs(IS* is) const {
  PetscFunctionBeginUser;
  const PetscInt bs = _dofs.blockSize(), n = _dofs.ownedBlocks() * bs, row0 = _dofs.ownedBegin() * bs;
  std::vector<PetscInt> idx;
  for (PetscInt i = 0; i < n; ++i)
    if (!_fixedLocal[i]) idx.push_back(row0 + i);
  PetscCall(ISCreateGeneral(_dofs.comm(), static_cast<PetscInt>(idx.size()), idx.data(), PETSC_COPY_VALUES, is));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::addTimedLoads(PetscReal t, Vec R, PetscReal scale, bool skipSupported) const {
  PetscFunctionBeginUser;
  if (_model.timedLoads().empty()) PetscFunctionReturn(0);
  const PetscInt bs = _dofs.blockSize(), first = _dofs.ownedBegin(), owned = _dofs.ownedBlocks();
  PetscScalar* r;
  PetscCall(VecGetArray(R, &r));
  for (const model::TimedLoad& l : _model.timedLoads()) {
    const double g = scale * l.function.at(t).f;
    for (size_t k = 0; k < l.dofs.size(); ++k) {
      const PetscInt blk = _dofs.globalBlock()[l.dofs[k] / bs] - first;
      const PetscInt i = blk * bs + l.dofs[k] % bs;
      if (blk >= 0 && blk < owned && !(skipSupported && _fixedLocal[i])) r[i] += g * l.values[k];
    }
  }
  PetscCall(VecRestoreArray(R, &r));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::contactPoints(Vec X, Vec V, PetscReal t, std::vector<ContactPointOut>& out) {
  PetscFunctionBeginUser;
  LocalRead x, v;
  PetscCall(beginLocal(X, _xWork, &x));
  if (V) PetscCall(beginLocal(V, _vWork, &v));
  out.clear();
  _contacts->points(x.a, V ? v.a : nullptr, t, out);
  PetscCall(endLocal(&x));
  if (V) PetscCall(endLocal(&v));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::contactForce(Vec X, Vec V, PetscReal t, Vec F) {
  PetscFunctionBeginUser;
  LocalRead x, v;
  LocalSum f;
  PetscCall(beginLocal(X, _xWork, &x));
  if (V) PetscCall(beginLocal(V, _vWork, &v));
  PetscCall(beginLocalSum(F, {X, V}, &f));
  _contacts->residual(x.a, V ? v.a : nullptr, t, f.a, -1.0);
  PetscCall(endLocalSum(&f));
  PetscCall(endLocal(&x));
  if (V) PetscCall(endLocal(&v));
  PetscCall(deliver(f, F));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::contactEnergy(Vec X, Vec V, PetscReal t, PetscReal* stored, PetscReal* power) {
  PetscFunctionBeginUser;
  LocalRead x, v;
  PetscCall(beginLocal(X, _xWork, &x));
  if (V) PetscCall(beginLocal(V, _vWork, &v));
  double mine[2] = {0.0, 0.0}, all[2];
  _contacts->energy(x.a, V ? v.a : nullptr, t, &mine[0], &mine[1]);
  PetscCall(endLocal(&x));
  if (V) PetscCall(endLocal(&v));
  PetscCallMPI(MPI_Allreduce(mine, all, 2, MPI_DOUBLE, MPI_SUM, _dofs.comm()));
  *stored = all[0];
  *power = all[1];
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::pulleyLoads(Vec X, Vec V, PetscReal t, std::vector<PulleyLoad>& load) {
  PetscFunctionBeginUser;
  LocalRead x, v;
  PetscCall(beginLocal(X, _xWork, &x));
  if (V) PetscCall(beginLocal(V, _vWork, &v));
  constexpr int stride = PulleyContacts::kLoadStride;
  std::vector<double> mine(stride * _model.pulleys().size(), 0.0), all(mine.size(), 0.0);
  _contacts->pulleyLoads(x.a, V ? v.a : nullptr, t, mine.data());
  PetscCall(endLocal(&x));
  if (V) PetscCall(endLocal(&v));
  PetscCallMPI(MPI_Allreduce(mine.data(), all.data(), static_cast<int>(mine.size()), MPI_DOUBLE, MPI_SUM, _dofs.comm()));
  load.assign(_model.pulleys().size(), PulleyLoad{});
  for (size_t p = 0; p < load.size(); ++p) {
    const double* a = &all[stride * p];
    const model::PulleyDesc& d = _model.pulleys()[p];
    load[p] = {a[0], a[1], a[2], d.free() ? a[3] : d.speed.at(t).f, a[4]};
  }
  PetscFunctionReturn(0);
}

bool Assembler::hasContactHistory() const { return _contacts->hasHistory(); }

PetscErrorCode Assembler::commitContact(Vec X, Vec V, PetscReal t) {
  PetscFunctionBeginUser;
  if (!_contacts->hasHistory()) PetscFunctionReturn(0);
  LocalRead x, v;
  PetscCall(beginLocal(X, _xWork, &x));
  if (V) PetscCall(beginLocal(V, _vWork, &v));
  _contacts->commit(x.a, V ? v.a : nullptr, t);
  PetscCall(endLocal(&x));
  if (V) PetscCall(endLocal(&v));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::settleContact(Vec X, Vec V, PetscReal t, bool release, PetscInt* changed) {
  PetscFunctionBeginUser;
  *changed = 0;
  if (!_contacts->hasHistory()) PetscFunctionReturn(0);
  LocalRead x, v;
  PetscCall(beginLocal(X, _xWork, &x));
  if (V) PetscCall(beginLocal(V, _vWork, &v));
  int mine = _contacts->settle(x.a, V ? v.a : nullptr, t, release), all = 0;
  PetscCall(endLocal(&x));
  if (V) PetscCall(endLocal(&v));
  PetscCallMPI(MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_SUM, _dofs.comm()));
  if (!release) _contacts->changedAnywhere(all > 0);  // what a release after it frees, on every rank alike
  *changed = all;
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::contactHistory(std::vector<double>& packed, double* tn) const {
  PetscFunctionBeginUser;
  std::vector<double> mine;
  for (const PulleyContacts::HistoryEntry& e : _contacts->history())
    mine.insert(mine.end(), {double(e.body), double(e.element), double(e.pulley), double(e.point), e.z});
  int size, count = static_cast<int>(mine.size());
  PetscCallMPI(MPI_Comm_size(_dofs.comm(), &size));
  std::vector<int> counts(size), offsets(size, 0);
  PetscCallMPI(MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, _dofs.comm()));
  for (int r = 1; r < size; ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
  packed.assign(static_cast<size_t>(offsets[size - 1] + counts[size - 1]), 0.0);
  PetscCallMPI(MPI_Allgatherv(mine.data(), count, MPI_DOUBLE, packed.data(), counts.data(), offsets.data(),
                              MPI_DOUBLE, _dofs.comm()));
  *tn = _contacts->committedTime();
  PetscFunctionReturn(0);
}

void Assembler::restoreContactHistory(const std::vector<double>& packed, double tn) {
  std::vector<PulleyContacts::HistoryEntry> entries;
  for (size_t i = 0; i + 4 < packed.size(); i += 5)
    entries.push_back({static_cast<int>(packed[i]), static_cast<int>(packed[i + 1]), static_cast<int>(packed[i + 2]),
                       static_cast<int>(packed[i + 3]), packed[i + 4]});
  _contacts->restore(entries, tn);
}

PetscErrorCode Assembler::gatherToRoot(Vec X, std::vector<double>& out) {
  PetscFunctionBeginUser;
  PetscCall(toModelOrder(X, out));
  for (size_t i = 0; i < out.size(); ++i) out[i] += _model.initialCoordinates()[i];
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::toModelOrder(Vec X, std::vector<double>& out) {
  PetscFunctionBeginUser;
  if (!_toRoot) PetscCall(VecScatterCreateToZero(X, &_toRoot, &_rootVec));
  PetscCall(VecScatterBegin(_toRoot, X, _rootVec, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(_toRoot, X, _rootVec, INSERT_VALUES, SCATTER_FORWARD));
  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(_dofs.comm(), &rank));
  out.clear();
  if (rank == 0) {
    const PetscScalar* a;
    PetscCall(VecGetArrayRead(_rootVec, &a));
    const PetscInt bs = _dofs.blockSize();
    out.resize(_model.numDofs());
    for (int b = 0; b < _model.numBlocks(); ++b)
      for (PetscInt i = 0; i < bs; ++i) out[b * bs + i] = a[_dofs.globalBlock()[b] * bs + i];
    PetscCall(VecRestoreArrayRead(_rootVec, &a));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::fromModelOrder(const std::vector<double>& in, Vec X) {
  PetscFunctionBeginUser;
  if (!_toRoot) PetscCall(VecScatterCreateToZero(X, &_toRoot, &_rootVec));
  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(_dofs.comm(), &rank));
  if (rank == 0) {
    PetscCheck(in.size() == static_cast<size_t>(_model.numDofs()), PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ,
               "fromModelOrder: %zu values for %d coordinates", in.size(), _model.numDofs());
    PetscScalar* a;
    PetscCall(VecGetArray(_rootVec, &a));
    const PetscInt bs = _dofs.blockSize();
    for (int b = 0; b < _model.numBlocks(); ++b)
      for (PetscInt i = 0; i < bs; ++i) a[_dofs.globalBlock()[b] * bs + i] = in[b * bs + i];
    PetscCall(VecRestoreArray(_rootVec, &a));
  }
  PetscCall(VecScatterBegin(_toRoot, _rootVec, X, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(_toRoot, _rootVec, X, INSERT_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(0);
}

}  // namespace strand::assembly
