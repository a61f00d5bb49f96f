// Adds element matrices (4 x 4 blocks) to a PETSc matrix (internal to the Assembler).
//
// On one rank a matrix is SeqBAIJ, whose MatSetValuesBlocked inserts row by row. On several ranks
// it is MPIBAIJ, whose MatSetValuesBlocked copies and inserts block by block, a search in the row
// for each of the 16 blocks: at 1e5 cable elements that took 1.7-2.5 % of a two-rank time step against
// under 0.4 % for the one-rank insertion (perf, docs/performance.md session 24). An element whose
// four blocks this rank owns therefore goes straight into the MPIBAIJ's diagonal part, a SeqBAIJ
// numbered from the first owned block (MatMPIBAIJGetSeqBAIJ), which is where MatSetValuesBlocked
// would have put it; the elements at the rank's interface and every other matrix type take the
// general path. MatAssemblyBegin/End of the matrix then assemble both parts as usual.
#pragma once
#include <petscmat.h>

#include "strand/model/DofMap.hpp"

namespace strand::assembly {

class ElementInserter {
public:
  // An inserter for A, which must have the DofMap's layout (DofMap::createMatrix).
  static PetscErrorCode create(Mat A, const model::DofMap& dofs, ElementInserter* out);

  // A += Ke on the blocks of local element k (Ke row-major, 4 D x 4 D).
  PetscErrorCode add(int k, const double* Ke) const {
    PetscFunctionBeginUser;
    const PetscInt* lb = &_dofs->elementLocalBlocks()[4 * k];
    const PetscInt owned = _dofs->ownedBlocks();
    if (_diag && lb[0] < owned && lb[1] < owned && lb[2] < owned && lb[3] < owned)
      PetscCall(MatSetValuesBlocked(_diag, 4, lb, 4, lb, Ke, ADD_VALUES));  // owned blocks: local = global - first
    else
      PetscCall(MatSetValuesBlocked(_A, 4, &_dofs->elementGlobalBlocks()[4 * k], 4,
                                    &_dofs->elementGlobalBlocks()[4 * k], Ke, ADD_VALUES));
    PetscFunctionReturn(0);
  }

private:
  Mat _A = nullptr;
  Mat _diag = nullptr;  // the MPIBAIJ's diagonal part, or null: general path only
  const model::DofMap* _dofs = nullptr;
};

inline PetscErrorCode ElementInserter::create(Mat A, const model::DofMap& dofs, ElementInserter* out) {
  PetscBool mpibaij;
  PetscFunctionBeginUser;
  out->_A = A;
  out->_dofs = &dofs;
  out->_diag = nullptr;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(A), MATMPIBAIJ, &mpibaij));
  if (mpibaij) PetscCall(MatMPIBAIJGetSeqBAIJ(A, &out->_diag, nullptr, nullptr));
  PetscFunctionReturn(0);
}

}  // namespace strand::assembly
