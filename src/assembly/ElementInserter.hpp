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
//
// Held blocks. Given the supported DOFs (`fixed`, per local DOF), an element block all of whose
// coordinates are supported and that no coupling holds (a prescribed material coordinate of an ALE
// element, a pinned node's position) is left out: the caller has zeroed its rows and columns, so
// its element couplings are zero, and a matrix first assembled this way never stores them (PETSc's
// assembly drops the preallocated blocks that were not set; the held block's own diagonal block is
// still set, so that every row keeps its diagonal for the unit entry or MatDiagonalSet). Its
// factorization then sees the held block as an isolated unknown instead of a coupled zero: the
// 2D ALE node's three blocks factor like the cable's two (docs/architecture.md, decision 29). A
// matrix must keep one convention: every assembly of it masks, or none does.
#pragma once
#include <algorithm>
#include <vector>

#include <petscmat.h>

#include "strand/model/DofMap.hpp"

namespace strand::assembly {

class ElementInserter {
public:
  // An inserter for A, which must have the DofMap's layout (DofMap::createMatrix), and the local
  // elements of one group; with `fixed` (the mask the caller applied), held blocks left out.
  static PetscErrorCode create(Mat A, const model::DofMap& dofs, const model::DofMap::LocalGroup& group,
                               ElementInserter* out, const std::vector<char>* fixed = nullptr);

  // A += Ke on the blocks of the group's local element k (Ke row-major, stride D x stride D).
  PetscErrorCode add(int k, const double* Ke) const {
    PetscFunctionBeginUser;
    const PetscInt n = _group->stride;
    const PetscInt* lb = _group->localBlocksOf(k);
    if (_fixed) {
      int keep[kMaxStride], m = 0;
      for (int a = 0; a < n; ++a)
        if (!held(lb[a])) keep[m++] = a;
      if (m < n) {
        for (int a = 0, j = 0; a < n; ++a) {  // the held blocks' diagonal blocks (zero)
          if (j < m && keep[j] == a) {
            ++j;
            continue;
          }
          PetscCall(addPart(k, Ke, &a, 1));
        }
        PetscFunctionReturn(addPart(k, Ke, keep, m));
      }
    }
    bool owned = _diag != nullptr;
    for (PetscInt a = 0; a < n && owned; ++a) owned = lb[a] < _owned;
    if (owned)
      PetscCall(MatSetValuesBlocked(_diag, n, lb, n, lb, Ke, ADD_VALUES));  // owned blocks: local = global - first
    else
      PetscCall(MatSetValuesBlocked(_A, n, _group->globalBlocksOf(k), n, _group->globalBlocksOf(k), Ke, ADD_VALUES));
    PetscFunctionReturn(0);
  }

private:
  static constexpr int kMaxStride = 8;  // blocks per element

  bool held(PetscInt lb) const {
    if ((*_coupled)[lb]) return false;
    for (PetscInt i = 0; i < _bs; ++i)
      if (!(*_fixed)[lb * _bs + i]) return false;
    return true;
  }

  // Ke's blocks keep[0..m) alone (their rows and columns), by the general path.
  PetscErrorCode addPart(int k, const double* Ke, const int* keep, int m) const {
    PetscFunctionBeginUser;
    if (m == 0) PetscFunctionReturn(0);
    const PetscInt n = _group->stride, N = n * _bs, M = m * _bs;
    const PetscInt* gb = _group->globalBlocksOf(k);
    PetscInt rows[kMaxStride];
    double part[kMaxStride * kMaxStride * 9];
    for (int a = 0; a < m; ++a) rows[a] = gb[keep[a]];
    for (int a = 0; a < m; ++a)
      for (PetscInt i = 0; i < _bs; ++i)
        for (int c = 0; c < m; ++c)
          std::copy_n(Ke + (keep[a] * _bs + i) * N + keep[c] * _bs, _bs, part + (a * _bs + i) * M + c * _bs);
    PetscCall(MatSetValuesBlocked(_A, m, rows, m, rows, part, ADD_VALUES));
    PetscFunctionReturn(0);
  }

  Mat _A = nullptr;
  Mat _diag = nullptr;  // the MPIBAIJ's diagonal part, or null: general path only
  const model::DofMap::LocalGroup* _group = nullptr;
  PetscInt _owned = 0, _bs = 1;
  const std::vector<char>* _fixed = nullptr;    // per local DOF (null: insert every block)
  const std::vector<char>* _coupled = nullptr;  // per local block (DofMap::coupledLocal)
};

inline PetscErrorCode ElementInserter::create(Mat A, const model::DofMap& dofs, const model::DofMap::LocalGroup& group,
                                              ElementInserter* out, const std::vector<char>* fixed) {
  PetscBool mpibaij;
  PetscFunctionBeginUser;
  PetscCheck(group.stride <= kMaxStride && dofs.blockSize() <= 3, dofs.comm(), PETSC_ERR_SUP,
             "ElementInserter: at most %d blocks of 3 coordinates per element", kMaxStride);
  out->_A = A;
  out->_group = &group;
  out->_owned = dofs.ownedBlocks();
  out->_bs = dofs.blockSize();
  out->_fixed = fixed;
  out->_coupled = &dofs.coupledLocal();
  out->_diag = nullptr;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(A), MATMPIBAIJ, &mpibaij));
  if (mpibaij) PetscCall(MatMPIBAIJGetSeqBAIJ(A, &out->_diag, nullptr, nullptr));
  PetscFunctionReturn(0);
}

}  // namespace strand::assembly
