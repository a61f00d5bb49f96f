// Adds element matrices (blocks x blocks, `stride` blocks per element of one group) to a PETSc
// matrix (internal to the Assembler).
//
// On one rank a matrix is SeqBAIJ, whose MatSetValuesBlocked inserts row by row. On several ranks
// it is MPIBAIJ, whose MatSetValuesBlocked copies and inserts block by block, a search in the row
// for each block: at 1e5 cable elements that took 1.7-2.5 % of a two-rank time step against under
// 0.4 % for the one-rank insertion (perf, docs/performance.md). An element whose blocks this rank
// all owns therefore goes straight into the MPIBAIJ's diagonal part, a SeqBAIJ numbered from the
// first owned block (MatMPIBAIJGetSeqBAIJ), which is where MatSetValuesBlocked would have put it;
// the elements at the rank's interface and every other matrix type take the general path.
// MatAssemblyBegin/End of the matrix then assemble both parts as usual.
#pragma once
#include <petscmat.h>

#include "strand/model/DofMap.hpp"

namespace strand::assembly {

class ElementInserter {
public:
  // An inserter for A, which must have the DofMap's layout (DofMap::createMatrix), and the local
  // elements of one group.
  static PetscErrorCode create(Mat A, const model::DofMap& dofs, const model::DofMap::LocalGroup& group,
                               ElementInserter* out);

  // A += Ke on the blocks of the group's local element k (Ke row-major, stride D x stride D).
  PetscErrorCode add(int k, const double* Ke) const {
    PetscFunctionBeginUser;
    const PetscInt n = _group->stride;
    const PetscInt* lb = _group->localBlocksOf(k);
    bool owned = _diag != nullptr;
    for (PetscInt a = 0; a < n && owned; ++a) owned = lb[a] < _owned;
    if (owned)
      PetscCall(MatSetValuesBlocked(_diag, n, lb, n, lb, Ke, ADD_VALUES));  // owned blocks: local = global - first
    else
      PetscCall(MatSetValuesBlocked(_A, n, _group->globalBlocksOf(k), n, _group->globalBlocksOf(k), Ke, ADD_VALUES));
    PetscFunctionReturn(0);
  }

private:
  Mat _A = nullptr;
  Mat _diag = nullptr;  // the MPIBAIJ's diagonal part, or null: general path only
  const model::DofMap::LocalGroup* _group = nullptr;
  PetscInt _owned = 0;
};

inline PetscErrorCode ElementInserter::create(Mat A, const model::DofMap& dofs, const model::DofMap::LocalGroup& group,
                                              ElementInserter* out) {
  PetscBool mpibaij;
  PetscFunctionBeginUser;
  out->_A = A;
  out->_group = &group;
  out->_owned = dofs.ownedBlocks();
  out->_diag = nullptr;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(A), MATMPIBAIJ, &mpibaij));
  if (mpibaij) PetscCall(MatMPIBAIJGetSeqBAIJ(A, &out->_diag, nullptr, nullptr));
  PetscFunctionReturn(0);
}

}  // namespace strand::assembly
