// M_s (x) I on more than one rank, with the off-process part applied to its nonzero rows only
// (IsotropicMassProduct.hpp).
//
// PETSc's MPIMAIJ multiplies the off-process part B_s (x) I row by row over all local rows
// (MatMultAdd_SeqMAIJ_3 of PETSc 3.18: every row reads its row pointer and adds its three sums into
// y), so each product streams y once more, read and written, though a chain segment's B_s has
// nonzeros in two block rows. On two ranks at 1e5 cable elements that pass is 5 MB per rank and
// product, about a third of the compact product's traffic, and it is the part of a step that only
// two ranks pay. Here the own-column part keeps PETSc's SeqMAIJ kernel and the off-process part
// is a compressed list of its nonzero rows.
#include "solvers/IsotropicMassProduct.hpp"

#include <vector>

namespace strand::solvers {

namespace {

struct SplitProduct {
  PetscInt bs = 0;
  Mat Ms = nullptr;    // the scalar MPIAIJ M_s, kept for its own-column part
  Mat own = nullptr;   // that part (x) I: SeqMAIJ
  Vec xOwn = nullptr;  // sequential views of the local entries of x, y and z
  Vec yOwn = nullptr;
  Vec zOwn = nullptr;
  VecScatter toGhosts = nullptr;  // x's entries in the off-process columns, block by block
  Vec ghosts = nullptr;
  // the off-process part's nonzero block rows: row r gets sum_k value[k] * ghost block column[k]
  std::vector<PetscInt> row, start, column;
  std::vector<PetscScalar> value;
};

SplitProduct* productOf(Mat A) {
  void* ctx;
  PetscCallAbort(PETSC_COMM_SELF, MatShellGetContext(A, &ctx));
  return static_cast<SplitProduct*>(ctx);
}

// z = y + (M_s (x) I) x, or z = (M_s (x) I) x when y is null
PetscErrorCode apply(Mat A, Vec x, Vec y, Vec z) {
  SplitProduct* p = productOf(A);
  const PetscScalar *xa, *ya = nullptr;
  PetscScalar* za;
  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(p->toGhosts, x, p->ghosts, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArray(z, &za));
  PetscCall(VecPlaceArray(p->xOwn, xa));
  PetscCall(VecPlaceArray(p->zOwn, za));
  if (!y) {
    PetscCall(MatMult(p->own, p->xOwn, p->zOwn));
  } else if (y == z) {
    PetscCall(MatMultAdd(p->own, p->xOwn, p->zOwn, p->zOwn));
  } else {
    PetscCall(VecGetArrayRead(y, &ya));
    PetscCall(VecPlaceArray(p->yOwn, ya));
    PetscCall(MatMultAdd(p->own, p->xOwn, p->yOwn, p->zOwn));
    PetscCall(VecResetArray(p->yOwn));
    PetscCall(VecRestoreArrayRead(y, &ya));
  }
  PetscCall(VecResetArray(p->xOwn));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(VecScatterEnd(p->toGhosts, x, p->ghosts, INSERT_VALUES, SCATTER_FORWARD));
  const PetscScalar* g;
  PetscCall(VecGetArrayRead(p->ghosts, &g));
  const PetscInt bs = p->bs;
  for (std::size_t i = 0; i < p->row.size(); ++i) {
    PetscScalar* zr = za + bs * p->row[i];
    for (PetscInt k = p->start[i]; k < p->start[i + 1]; ++k) {
      const PetscScalar* gk = g + bs * p->column[k];
      for (PetscInt c = 0; c < bs; ++c) zr[c] += p->value[k] * gk[c];
    }
  }
  PetscCall(VecRestoreArrayRead(p->ghosts, &g));
  PetscCall(VecResetArray(p->zOwn));
  PetscCall(VecRestoreArray(z, &za));
  PetscFunctionReturn(0);
}

PetscErrorCode mult(Mat A, Vec x, Vec y) { return apply(A, x, nullptr, y); }
PetscErrorCode multAdd(Mat A, Vec x, Vec y, Vec z) { return apply(A, x, y, z); }

PetscErrorCode destroy(Mat A) {
  SplitProduct* p = productOf(A);
  PetscFunctionBeginUser;
  PetscCall(VecScatterDestroy(&p->toGhosts));
  for (Vec* v : {&p->ghosts, &p->xOwn, &p->yOwn, &p->zOwn}) PetscCall(VecDestroy(v));
  PetscCall(MatDestroy(&p->own));
  PetscCall(MatDestroy(&p->Ms));
  delete p;
  PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode splitIsotropicProduct(Mat Ms, PetscInt bs, Mat* op) {
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(Ms));
  PetscFunctionBeginUser;
  auto* p = new SplitProduct;
  p->bs = bs;
  PetscCall(PetscObjectReference(reinterpret_cast<PetscObject>(Ms)));
  p->Ms = Ms;
  Mat Ad, Ao;
  const PetscInt* garray;
  PetscCall(MatMPIAIJGetSeqAIJ(Ms, &Ad, &Ao, &garray));
  PetscCall(MatCreateMAIJ(Ad, bs, &p->own));

  // the off-process part's nonzero rows, its columns numbered as the ghost blocks
  PetscInt rows, ghostBlocks;
  PetscCall(MatGetSize(Ao, &rows, &ghostBlocks));
  const PetscInt *ia, *ja;
  PetscBool done;
  const PetscScalar* a;
  PetscCall(MatGetRowIJ(Ao, 0, PETSC_FALSE, PETSC_FALSE, &rows, &ia, &ja, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "no row structure of the mass's off-process part");
  PetscCall(MatSeqAIJGetArrayRead(Ao, &a));
  p->start.push_back(0);
  for (PetscInt r = 0; r < rows; ++r) {
    if (ia[r + 1] == ia[r]) continue;
    p->row.push_back(r);
    for (PetscInt k = ia[r]; k < ia[r + 1]; ++k) {
      p->column.push_back(ja[k]);
      p->value.push_back(a[k]);
    }
    p->start.push_back(static_cast<PetscInt>(p->column.size()));
  }
  PetscCall(MatSeqAIJRestoreArrayRead(Ao, &a));
  PetscCall(MatRestoreRowIJ(Ao, 0, PETSC_FALSE, PETSC_FALSE, &rows, &ia, &ja, &done));

  PetscInt localRows, localCols;
  PetscCall(MatGetLocalSize(Ms, &localRows, &localCols));
  Vec x;  // a vector of the operator's column layout, for the scatter
  PetscCall(VecCreateMPI(comm, bs * localCols, PETSC_DETERMINE, &x));
  PetscCall(VecSetBlockSize(x, bs));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, bs * ghostBlocks, &p->ghosts));
  IS from, to;
  PetscCall(ISCreateBlock(PETSC_COMM_SELF, bs, ghostBlocks, garray, PETSC_COPY_VALUES, &from));
  PetscCall(ISCreateStride(PETSC_COMM_SELF, bs * ghostBlocks, 0, 1, &to));
  PetscCall(VecScatterCreate(x, from, p->ghosts, to, &p->toGhosts));
  PetscCall(ISDestroy(&from));
  PetscCall(ISDestroy(&to));
  PetscCall(VecDestroy(&x));
  PetscCall(VecCreateSeqWithArray(PETSC_COMM_SELF, bs, bs * localCols, nullptr, &p->xOwn));
  PetscCall(VecCreateSeqWithArray(PETSC_COMM_SELF, bs, bs * localRows, nullptr, &p->yOwn));
  PetscCall(VecCreateSeqWithArray(PETSC_COMM_SELF, bs, bs * localRows, nullptr, &p->zOwn));

  PetscCall(MatCreateShell(comm, bs * localRows, bs * localCols, PETSC_DETERMINE, PETSC_DETERMINE, p, op));
  PetscCall(MatShellSetOperation(*op, MATOP_MULT, reinterpret_cast<void (*)(void)>(mult)));
  PetscCall(MatShellSetOperation(*op, MATOP_MULT_ADD, reinterpret_cast<void (*)(void)>(multAdd)));
  PetscCall(MatShellSetOperation(*op, MATOP_DESTROY, reinterpret_cast<void (*)(void)>(destroy)));
  PetscFunctionReturn(0);
}

}  // namespace strand::solvers
