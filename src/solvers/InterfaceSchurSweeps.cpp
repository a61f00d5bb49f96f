// The split sweeps of PC strand_interface_schur (InterfaceSchurData.hpp).
//
// Order a rank's own rows interior (I) first and interface (G) last and factor the whole local
// diagonal block without pivoting across blocks: A_loc = L U with
//   L = [L_II 0; L_GI L_GG],  U = [U_II U_IG; 0 U_GG],
// so A_II = L_II U_II, A_IG = L_II U_IG, A_GI = L_GI U_II and A_GG - A_GI A_II^{-1} A_IG = L_GG U_GG.
// The block elimination of InterfaceSchur.hpp then splits between the two triangular sweeps
// (the substructuring of Saad, "Iterative Methods for Sparse Linear Systems", 2nd ed. 2003,
// sec. 14.2, with the local solve written as L and U):
//   forward   y = L^{-1} b:  y_I = L_II^{-1} b_I, and the interface right-hand side
//             g = b_G - A_GI A_II^{-1} b_I = b_G - L_GI y_I = L_GG y_G;
//   interface S x_G = g (all ranks);
//   backward  with y_G replaced by U_GG x_G, U^{-1} y gives x_G on the interface rows first and
//             then x_I = U_II^{-1} (y_I - U_IG x_G) = A_II^{-1} (b_I - A_IG x_G).
// That is the work of one local solve; the interior solve's Z (|interior| x |own interface|,
// 14 MB per rank at 1e5 elements on two ranks) is neither computed nor read. A chain's natural
// order is banded, so with the interface at one end of the segment the band has no fill. DofMap
// numbers an end segment with its interface last, and the local block A_d is factored as it is;
// a segment numbered with its interface first (another numbering) factors a copy with its blocks
// reversed, at the price of that copy at every factorization and of reordering b and x at every
// apply. A segment with the interface at both ends (a middle rank) keeps the interior solve:
// putting both ends last would fill a whole column, which is Z.
#include <petsc/private/petscimpl.h>

#include <algorithm>
#include <string>

#include "solvers/InterfaceSchurData.hpp"

namespace strand::solvers::schur {

namespace {

// the local row r in factor order
PetscInt factorPosition(const SchurData& d, PetscInt r) {
  if (!d.reversed) return r;
  const PetscInt blocks = d.rows / d.bs;
  return (blocks - 1 - r / d.bs) * d.bs + r % d.bs;
}

// to[factorPosition(r)] = from[r] (the reversal is its own inverse: also from factor order back)
void reorder(const SchurData& d, const PetscScalar* from, PetscScalar* to) {
  if (!d.reversed) {
    std::copy(from, from + d.rows, to);
    return;
  }
  const PetscInt bs = d.bs, last = d.rows - bs;  // an element loop, not a copy call per block
  for (PetscInt r = 0; r < d.rows; r += bs)
    for (PetscInt j = 0; j < bs; ++j) to[last - r + j] = from[r + j];
}

// w = b in factor order, its interface rows then set to `interface` when given
PetscErrorCode toFactorOrder(const SchurData& d, const PetscScalar* b, const Eigen::VectorXd* interface, Vec w) {
  PetscScalar* a;
  PetscFunctionBeginUser;
  PetscCall(VecGetArray(w, &a));
  reorder(d, b, a);
  if (interface)
    for (size_t i = 0; i < d.factorRow.size(); ++i) a[d.factorRow[i]] = (*interface)[static_cast<Eigen::Index>(i)];
  PetscCall(VecRestoreArray(w, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode fromFactorOrder(const SchurData& d, Vec t, PetscScalar* x) {
  const PetscScalar* a;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(t, &a));
  reorder(d, a, x);
  PetscCall(VecRestoreArrayRead(t, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode factorOf(const SchurData& d, Mat* F) {
  PC lu;
  PetscFunctionBeginUser;
  PetscCall(KSPGetPC(d.interiorSolver, &lu));
  PetscCall(PCFactorGetMatrix(lu, F));
  PetscFunctionReturn(0);
}

}  // namespace

// Split sweeps when the matrix is blocked (bs <= 3), this rank has an interface, the interface is
// the first or the last blocks of the segment, and the natural order is banded: the envelope (per
// row, the distance from the diagonal to the first and the last entry) at most twice the number of
// blocks held, so the natural-order LU fills almost nothing (a chain: 5 against 6 blocks per row).
PetscErrorCode splitSweepsFit(SchurData* d, Mat Ad, PetscBool blocked) {
  PetscFunctionBeginUser;
  d->sweeps = false;
  if (!blocked || d->interface.empty() || d->sweepsRefused) PetscFunctionReturn(0);
  PetscCall(MatGetBlockSize(Ad, &d->bs));
  if (d->bs > 3) PetscFunctionReturn(0);  // PETSc's BAIJ LU has split sweeps for bs 1-3 only
  const PetscInt blocks = d->rows / d->bs;
  const PetscInt interfaceBlocks = static_cast<PetscInt>(d->interface.size()) / d->bs;
  // d->interface holds whole blocks, ascending
  const bool last = d->interface.front() == (blocks - interfaceBlocks) * d->bs;
  const bool first = d->interface.back() == interfaceBlocks * d->bs - 1;
  if (!last && !first) PetscFunctionReturn(0);

  PetscInt n;
  const PetscInt *ia, *ja;
  PetscBool done;
  PetscCall(MatGetRowIJ(Ad, 0, PETSC_FALSE, PETSC_TRUE, &n, &ia, &ja, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "no block row structure of the local block");
  PetscInt envelope = 0;
  for (PetscInt i = 0; i < n; ++i)
    if (ia[i + 1] > ia[i])
      envelope += std::max<PetscInt>(0, i - ja[ia[i]]) + std::max<PetscInt>(0, ja[ia[i + 1] - 1] - i);
  const PetscInt held = ia[n];
  PetscCall(MatRestoreRowIJ(Ad, 0, PETSC_FALSE, PETSC_TRUE, &n, &ia, &ja, &done));
  if (envelope > 2 * held) PetscFunctionReturn(0);

  d->sweeps = true;
  d->reversed = !last;
  d->factorRow.resize(d->interface.size());
  for (size_t i = 0; i < d->interface.size(); ++i) d->factorRow[i] = factorPosition(*d, d->interface[i]);
  PetscFunctionReturn(0);
}

// The segment's block structure: block row i' of A_d's block row i = (reversed ? n-1-i : i), its
// columns likewise, ascending; blockMap sends each block of A_d's value array to its place.
PetscErrorCode buildSegment(SchurData* d, Mat Ad) {
  PetscInt n;
  const PetscInt *ia, *ja;
  PetscBool done;
  PetscFunctionBeginUser;
  PetscCall(MatGetRowIJ(Ad, 0, PETSC_FALSE, PETSC_TRUE, &n, &ia, &ja, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "no block row structure of the local block");
  std::vector<PetscInt> ri(n + 1, 0), rj(ia[n]);
  d->blockMap.assign(ia[n], 0);
  for (PetscInt row = 0; row < n; ++row) {
    const PetscInt i = d->reversed ? n - 1 - row : row, count = ia[i + 1] - ia[i];
    ri[row + 1] = ri[row] + count;
    for (PetscInt e = 0; e < count; ++e) {
      const PetscInt k = d->reversed ? ia[i + 1] - 1 - e : ia[i] + e;
      rj[ri[row] + e] = d->reversed ? n - 1 - ja[k] : ja[k];
      d->blockMap[k] = ri[row] + e;
    }
  }
  PetscCall(MatRestoreRowIJ(Ad, 0, PETSC_FALSE, PETSC_TRUE, &n, &ia, &ja, &done));
  PetscCall(MatCreate(PETSC_COMM_SELF, &d->segment));
  PetscCall(MatSetSizes(d->segment, d->rows, d->rows, d->rows, d->rows));
  PetscCall(MatSetType(d->segment, MATSEQBAIJ));
  PetscCall(MatSeqBAIJSetPreallocationCSR(d->segment, d->bs, ri.data(), rj.data(), nullptr));
  PetscFunctionReturn(0);
}

PetscErrorCode fillSegment(SchurData* d, Mat Ad) {
  PetscScalar *from, *to;
  PetscFunctionBeginUser;
  const PetscInt bs2 = d->bs * d->bs;
  PetscCall(MatSeqBAIJGetArray(Ad, &from));
  PetscCall(MatSeqBAIJGetArray(d->segment, &to));
  for (size_t k = 0; k < d->blockMap.size(); ++k)
    for (PetscInt j = 0; j < bs2; ++j) to[bs2 * d->blockMap[k] + j] = from[bs2 * k + j];
  PetscCall(MatSeqBAIJRestoreArray(d->segment, &to));
  PetscCall(MatSeqBAIJRestoreArray(Ad, &from));
  PetscCall(PetscObjectStateIncrease(reinterpret_cast<PetscObject>(d->segment)));  // new values: refactor
  PetscFunctionReturn(0);
}

// PETSc's own LU (another PC or package may lack the sweeps, or register sweeps that only raise an
// error, as SBAIJ's in-place Cholesky does), and its factor has both sweeps (natural order).
PetscErrorCode sweepsAvailable(SchurData* d, PetscBool* available) {
  PC lu;
  PetscBool isLu, forward, backward;
  MatSolverType package;
  PetscFunctionBeginUser;
  *available = PETSC_FALSE;
  PetscCall(KSPGetPC(d->interiorSolver, &lu));
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(lu), PCLU, &isLu));
  if (!isLu) PetscFunctionReturn(0);
  PetscCall(PCFactorGetMatSolverType(lu, &package));
  if (package && std::string(package) != MATSOLVERPETSC) PetscFunctionReturn(0);
  Mat F;
  PetscCall(factorOf(*d, &F));
  PetscCall(MatHasOperation(F, MATOP_FORWARD_SOLVE, &forward));
  PetscCall(MatHasOperation(F, MATOP_BACKWARD_SOLVE, &backward));
  *available = static_cast<PetscBool>(forward && backward);
  PetscFunctionReturn(0);
}

// L_GG^{-1} e_j and U_GG^{-1} e_j are the interface rows of the forward and the backward sweep of a
// unit vector on interface row j (L and U are triangular and the interface is last); S00 = L_GG U_GG.
// L's diagonal blocks are the identity (block LU), so the forward sweeps of the last block's unit
// vectors are the unit vectors themselves and are not run: 3 of a 3D node's 12 sweeps.
PetscErrorCode segmentSchur(SchurData* d) {
  PetscFunctionBeginUser;
  Mat F;
  PetscCall(factorOf(*d, &F));
  const PetscInt m = static_cast<PetscInt>(d->interface.size()), lastBlock = d->rows / d->bs - 1;
  Eigen::MatrixXd Linv(m, m), Uinv(m, m);
  for (PetscInt j = 0; j < m; ++j) {
    const PetscScalar* t;
    PetscCall(VecSet(d->w, 0.0));
    PetscCall(VecSetValue(d->w, d->factorRow[j], 1.0, INSERT_VALUES));
    PetscCall(VecAssemblyBegin(d->w));
    PetscCall(VecAssemblyEnd(d->w));
    for (Eigen::MatrixXd* inverse : {&Linv, &Uinv}) {
      if (inverse == &Linv && d->factorRow[j] / d->bs == lastBlock) {
        Linv.col(j) = Eigen::VectorXd::Unit(m, j);
        continue;
      }
      PetscCall(inverse == &Linv ? MatForwardSolve(F, d->w, d->t) : MatBackwardSolve(F, d->w, d->t));
      PetscCall(VecGetArrayRead(d->t, &t));
      for (PetscInt i = 0; i < m; ++i) (*inverse)(i, j) = t[d->factorRow[i]];
      PetscCall(VecRestoreArrayRead(d->t, &t));
    }
  }
  d->Lgg = Linv.partialPivLu().inverse();
  d->Ugg = Uinv.partialPivLu().inverse();
  d->S00 = d->Lgg * d->Ugg;
  PetscFunctionReturn(0);
}

PetscErrorCode applySweeps(SchurData* d, MPI_Comm comm, const PetscScalar* b, PetscScalar* x) {
  PetscFunctionBeginUser;
  Mat F;
  PetscCall(factorOf(*d, &F));
  const PetscInt m = static_cast<PetscInt>(d->interface.size());
  Vec in = d->u, out = d->u;  // in the natural order the sweeps read b's and write x's arrays
  if (d->reversed) {
    PetscCall(toFactorOrder(*d, b, nullptr, d->w));
    in = out = d->w;
  } else {
    PetscCall(VecPlaceArray(d->u, b));
  }
  PetscCall(MatForwardSolve(F, in, d->t));
  if (!d->reversed) PetscCall(VecResetArray(d->u));

  PetscScalar* t;
  PetscCall(VecGetArray(d->t, &t));
  Eigen::VectorXd yG(m), xG;
  for (PetscInt i = 0; i < m; ++i) yG[i] = t[d->factorRow[i]];
  const Eigen::VectorXd gOwn = d->Lgg * yG;
  const std::vector<PetscScalar> g(gOwn.data(), gOwn.data() + m);
  PetscCall(interfaceSolve(*d, comm, g, false, &xG));
  const Eigen::VectorXd zG = d->Ugg * xG.segment(d->ownOffset, m);
  for (PetscInt i = 0; i < m; ++i) t[d->factorRow[i]] = zG[i];
  PetscCall(VecRestoreArray(d->t, &t));

  if (!d->reversed) PetscCall(VecPlaceArray(d->u, x));
  PetscCall(MatBackwardSolve(F, d->t, out));
  if (d->reversed) PetscCall(fromFactorOrder(*d, d->w, x));
  else PetscCall(VecResetArray(d->u));
  PetscFunctionReturn(0);
}

// A^{-T} b with the local factor's full transposed solves (no split transposed sweeps in PETSc;
// not on a hot path). With S00 = A_GG - A_GI A_II^{-1} A_IG for the own interface:
//   A_loc^T u = [b_I; 0]  gives  S00^T u_G = -A_IG^T A_II^{-T} b_I, so g = b_G + S00^T u_G;
//   S^T x_G = g (all ranks);
//   A_loc^T v = [b_I; S00^T (x_G - u_G)]  gives  v_G = x_G and v_I = A_II^{-T} (b_I - A_GI^T x_G).
PetscErrorCode applyTransposeSweeps(SchurData* d, MPI_Comm comm, const PetscScalar* b, PetscScalar* x) {
  PetscFunctionBeginUser;
  Mat F;
  PetscCall(factorOf(*d, &F));
  const PetscInt m = static_cast<PetscInt>(d->interface.size());
  const PetscScalar* t;
  Eigen::VectorXd uG(m), bG(m), xG;
  for (PetscInt i = 0; i < m; ++i) bG[i] = b[d->interface[i]];
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(m);
  PetscCall(toFactorOrder(*d, b, &zero, d->w));
  PetscCall(MatSolveTranspose(F, d->w, d->t));
  PetscCall(VecGetArrayRead(d->t, &t));
  for (PetscInt i = 0; i < m; ++i) uG[i] = t[d->factorRow[i]];
  PetscCall(VecRestoreArrayRead(d->t, &t));
  const Eigen::VectorXd gOwn = bG + d->S00.transpose() * uG;
  PetscCall(interfaceSolve(*d, comm, std::vector<PetscScalar>(gOwn.data(), gOwn.data() + m), true, &xG));
  const Eigen::VectorXd xOwn = xG.segment(d->ownOffset, m), c = d->S00.transpose() * (xOwn - uG);

  PetscCall(toFactorOrder(*d, b, &c, d->w));
  PetscCall(MatSolveTranspose(F, d->w, d->t));
  PetscCall(fromFactorOrder(*d, d->t, x));
  for (PetscInt i = 0; i < m; ++i) x[d->interface[i]] = xOwn[i];
  PetscFunctionReturn(0);
}

}  // namespace strand::solvers::schur
