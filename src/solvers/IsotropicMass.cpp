// The compact mass operator M_s (x) I (IsotropicMass.hpp).
#include "strand/solvers/IsotropicMass.hpp"

#include <vector>

#include "solvers/IsotropicMassProduct.hpp"

namespace strand::solvers {

namespace {

// a column-major bs x bs block equal to v[0] I
bool isMultipleOfIdentity(const PetscScalar* v, PetscInt bs) {
  for (PetscInt j = 0; j < bs; ++j)
    for (PetscInt i = 0; i < bs; ++i)
      if (v[i + j * bs] != (i == j ? v[0] : 0.0)) return false;
  return true;
}

// M_s by block row: global block columns, values, and the counts in own and other ranks' columns
struct ScalarRows {
  std::vector<std::vector<PetscInt>> cols;
  std::vector<std::vector<PetscScalar>> vals;
  std::vector<PetscInt> ownCount, otherCount;
};

// One sequential BAIJ part (the own-column block, or the off-process one with its global block
// columns globalColumn): appends each block's multiple of I to its row; *isotropic = false at the
// first block that is not one.
PetscErrorCode readPart(Mat part, const PetscInt* globalColumn, PetscInt columnOffset, bool own, ScalarRows* rows,
                        bool* isotropic) {
  PetscInt n, bs;
  const PetscInt *ia, *ja;
  PetscBool done;
  PetscScalar* a;
  PetscFunctionBeginUser;
  PetscCall(MatGetBlockSize(part, &bs));
  PetscCall(MatGetRowIJ(part, 0, PETSC_FALSE, PETSC_TRUE, &n, &ia, &ja, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "no block row structure of the mass matrix");
  PetscCall(MatSeqBAIJGetArray(part, &a));
  for (PetscInt r = 0; r < n && *isotropic; ++r)
    for (PetscInt k = ia[r]; k < ia[r + 1]; ++k) {
      const PetscScalar* block = a + k * bs * bs;
      if (!isMultipleOfIdentity(block, bs)) {
        *isotropic = false;
        break;
      }
      if (block[0] == 0.0) continue;  // a zero block (e.g. of multipliers): no entry in M_s
      rows->cols[r].push_back(globalColumn ? globalColumn[ja[k]] : columnOffset + ja[k]);
      rows->vals[r].push_back(block[0]);
      ++(own ? rows->ownCount : rows->otherCount)[r];
    }
  PetscCall(MatSeqBAIJRestoreArray(part, &a));
  PetscCall(MatRestoreRowIJ(part, 0, PETSC_FALSE, PETSC_TRUE, &n, &ia, &ja, &done));
  PetscFunctionReturn(0);
}

// M without its zero entries (AIJ) when they are most of what it stores (a model whose mass is
// mostly configuration-dependent, the ALE kinds', keeps only its rigid bodies' here: each product
// would otherwise stream the whole pattern of zeros), else M itself, referenced.
PetscErrorCode dropZeros(Mat M, Mat* op) {
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(M));
  PetscInt rstart, rend, cstart, cend;
  PetscFunctionBeginUser;
  PetscCall(MatGetOwnershipRange(M, &rstart, &rend));
  PetscCall(MatGetOwnershipRangeColumn(M, &cstart, &cend));
  ScalarRows rows;  // the nonzeros by row (global columns), read once
  rows.cols.resize(rend - rstart);
  rows.vals.resize(rend - rstart);
  rows.ownCount.assign(rend - rstart, 0);
  rows.otherCount.assign(rend - rstart, 0);
  double counts[2] = {0.0, 0.0};  // nonzero, stored
  for (PetscInt r = rstart; r < rend; ++r) {
    PetscInt n;
    const PetscInt* cols;
    const PetscScalar* vals;
    PetscCall(MatGetRow(M, r, &n, &cols, &vals));
    for (PetscInt k = 0; k < n; ++k) {
      if (vals[k] == 0.0) continue;
      rows.cols[r - rstart].push_back(cols[k]);
      rows.vals[r - rstart].push_back(vals[k]);
      ++(cols[k] >= cstart && cols[k] < cend ? rows.ownCount : rows.otherCount)[r - rstart];
    }
    counts[0] += static_cast<double>(rows.cols[r - rstart].size());
    counts[1] += n;
    PetscCall(MatRestoreRow(M, r, &n, &cols, &vals));
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_DOUBLE, MPI_SUM, comm));
  if (2.0 * counts[0] >= counts[1]) {
    PetscCall(PetscObjectReference(reinterpret_cast<PetscObject>(M)));
    *op = M;
    PetscFunctionReturn(0);
  }
  Mat A;
  PetscCall(MatCreate(comm, &A));
  PetscCall(MatSetSizes(A, rend - rstart, cend - cstart, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetType(A, MATAIJ));
  PetscCall(MatSeqAIJSetPreallocation(A, 0, rows.ownCount.data()));
  PetscCall(MatMPIAIJSetPreallocation(A, 0, rows.ownCount.data(), 0, rows.otherCount.data()));
  for (PetscInt r = rstart; r < rend; ++r)
    PetscCall(MatSetValues(A, 1, &r, static_cast<PetscInt>(rows.cols[r - rstart].size()), rows.cols[r - rstart].data(),
                           rows.vals[r - rstart].data(), INSERT_VALUES));
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  *op = A;
  PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode isotropicMassOperator(Mat M, Mat* op, PetscBool* compact) {
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(M));
  PetscBool mpibaij, seqbaij;
  PetscInt bs, rstart, rend, cstart, cend;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(M), MATMPIBAIJ, &mpibaij));
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(M), MATSEQBAIJ, &seqbaij));
  PetscCall(MatGetBlockSize(M, &bs));
  PetscCall(MatGetOwnershipRange(M, &rstart, &rend));
  PetscCall(MatGetOwnershipRangeColumn(M, &cstart, &cend));
  const PetscInt blockRows = (rend - rstart) / bs;
  ScalarRows rows;
  rows.cols.resize(blockRows);
  rows.vals.resize(blockRows);
  rows.ownCount.assign(blockRows, 0);
  rows.otherCount.assign(blockRows, 0);
  bool isotropic = (mpibaij || seqbaij) && bs > 1;
  if (mpibaij) {
    Mat Ad, Ao;
    const PetscInt* garray;
    PetscCall(MatMPIBAIJGetSeqBAIJ(M, &Ad, &Ao, &garray));
    PetscCall(readPart(Ad, nullptr, cstart / bs, true, &rows, &isotropic));
    if (isotropic) PetscCall(readPart(Ao, garray, 0, false, &rows, &isotropic));
  } else if (seqbaij && isotropic) {
    PetscCall(readPart(M, nullptr, 0, true, &rows, &isotropic));
  }
  int here = isotropic ? 1 : 0, everywhere;
  PetscCallMPI(MPI_Allreduce(&here, &everywhere, 1, MPI_INT, MPI_MIN, comm));
  *compact = static_cast<PetscBool>(everywhere == 1);
  if (!*compact) {
    PetscCall(dropZeros(M, op));
    PetscFunctionReturn(0);
  }

  Mat Ms;
  PetscCall(MatCreate(comm, &Ms));
  PetscCall(MatSetSizes(Ms, blockRows, (cend - cstart) / bs, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetType(Ms, MATAIJ));
  PetscCall(MatSeqAIJSetPreallocation(Ms, 0, rows.ownCount.data()));
  PetscCall(MatMPIAIJSetPreallocation(Ms, 0, rows.ownCount.data(), 0, rows.otherCount.data()));
  for (PetscInt r = 0; r < blockRows; ++r) {
    const PetscInt row = rstart / bs + r;
    PetscCall(MatSetValues(Ms, 1, &row, static_cast<PetscInt>(rows.cols[r].size()), rows.cols[r].data(),
                           rows.vals[r].data(), INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(Ms, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Ms, MAT_FINAL_ASSEMBLY));
  PetscMPIInt size;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (size == 1) PetscCall(MatCreateMAIJ(Ms, bs, op));
  else PetscCall(splitIsotropicProduct(Ms, bs, op));
  PetscCall(MatDestroy(&Ms));
  PetscFunctionReturn(0);
}

}  // namespace strand::solvers
