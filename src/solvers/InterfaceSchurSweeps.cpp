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
// order is banded, so with the interface at one end of the segment the band has no fill. The
// factor is our own (BandedBlockLu.hpp), whose trailing blocks L_GG and U_GG are read off it.
// DofMap numbers an end segment with its interface last, so the factor's order is A_d's; a
// segment numbered with its interface first (another numbering) is factored in reverse block
// order, at the price of reordering b and x at every apply. A segment with the interface at both
// ends (a middle rank) keeps the interior solve: putting both ends last would fill a whole column,
// which is Z.
#include <algorithm>
#include <vector>

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

}  // namespace

// Split sweeps when the matrix is blocked with a block size BandedBlockLu has a kernel for, they
// are not switched off, the interface is the first or the last blocks of the segment or there is
// none (one rank: the sweeps are then a plain solve with the banded LU), and the natural order is
// banded: the envelope (per row, the distance from the diagonal to the first and the last entry)
// at most twice the number of blocks held, and the profile the natural-order LU holds (per row
// first(i)..last(i), last(i) the running maximum over rows first(i)..i-1: BandedBlockLu.hpp) at
// most three times, so that it fills almost nothing (a chain: 5 against 6 blocks per row). The
// profile test keeps out a closed loop (a belt): numbered in order, its last row couples to its
// first, every row then fills to the end, and the factor held O(n^2) blocks (a 10,000-element loop:
// 30 s per factorization against a fraction of a second with PETSc's LU in RCM order).
PetscErrorCode splitSweepsFit(SchurData* d, Mat Ad, PetscBool blocked) {
  PetscFunctionBeginUser;
  d->sweeps = false;
  if (!blocked || d->sweepsRefused || !d->sweepsAllowed) PetscFunctionReturn(0);
  PetscCall(MatGetBlockSize(Ad, &d->bs));
  if (!BandedBlockLu::supports(d->bs)) PetscFunctionReturn(0);
  const PetscInt blocks = d->rows / d->bs;
  const PetscInt interfaceBlocks = static_cast<PetscInt>(d->interface.size()) / d->bs;
  // d->interface holds whole blocks, ascending; an empty one counts as last
  const bool last = d->interface.empty() || d->interface.front() == (blocks - interfaceBlocks) * d->bs;
  const bool first = !d->interface.empty() && d->interface.back() == interfaceBlocks * d->bs - 1;
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
  bool narrow = envelope <= 2 * held;
  if (narrow) {  // the factor's profile; the work stays O(held) (the scan over rows first(i)..i-1
                 // is the lower envelope)
    std::vector<PetscInt> lastFill(n, 0);
    PetscInt profile = 0;
    for (PetscInt i = 0; i < n && narrow; ++i) {
      const PetscInt first = ia[i + 1] > ia[i] ? std::min(ja[ia[i]], i) : i;
      PetscInt last = ia[i + 1] > ia[i] ? std::max(ja[ia[i + 1] - 1], i) : i;
      for (PetscInt k = first; k < i; ++k) last = std::max(last, lastFill[k]);
      lastFill[i] = last;
      profile += last - first + 1;
      narrow = profile <= 3 * held;
    }
  }
  PetscCall(MatRestoreRowIJ(Ad, 0, PETSC_FALSE, PETSC_TRUE, &n, &ia, &ja, &done));
  if (!narrow) PetscFunctionReturn(0);

  d->sweeps = true;
  d->reversed = !last;
  d->factorRow.resize(d->interface.size());
  for (size_t i = 0; i < d->interface.size(); ++i) d->factorRow[i] = factorPosition(*d, d->interface[i]);
  PetscCall(d->lu.analyze(Ad, d->reversed));
  d->work.assign(d->rows, 0.0);
  PetscFunctionReturn(0);
}

// The factor of A_d's values; with a zero pivot *factored = false, else L_GG, U_GG and
// S00 = L_GG U_GG of the own interface, read off the factor's trailing blocks (the interface is
// last) and permuted to the interface's order.
PetscErrorCode factorSegment(SchurData* d, Mat Ad, bool* factored) {
  PetscInt zeroPivot;
  PetscFunctionBeginUser;
  PetscCall(d->lu.factor(Ad, &zeroPivot));
  *factored = zeroPivot < 0;
  if (!*factored) PetscFunctionReturn(0);
  const PetscInt m = static_cast<PetscInt>(d->interface.size()), base = d->rows - m;
  Eigen::MatrixXd L, U;
  d->lu.trailingFactors(m, &L, &U);
  d->Lgg.resize(m, m);
  d->Ugg.resize(m, m);
  for (PetscInt i = 0; i < m; ++i)
    for (PetscInt j = 0; j < m; ++j) {
      d->Lgg(i, j) = L(d->factorRow[i] - base, d->factorRow[j] - base);
      d->Ugg(i, j) = U(d->factorRow[i] - base, d->factorRow[j] - base);
    }
  d->S00 = d->Lgg * d->Ugg;
  PetscFunctionReturn(0);
}

PetscErrorCode applySweeps(SchurData* d, MPI_Comm comm, const PetscScalar* b, PetscScalar* x) {
  PetscFunctionBeginUser;
  const PetscInt m = static_cast<PetscInt>(d->interface.size());
  PetscScalar* f = x;  // in the natural order the sweeps read b and work in x
  if (d->reversed) {
    f = d->work.data();
    reorder(*d, b, f);
    d->lu.forward(f, f);
  } else {
    d->lu.forward(b, f);
  }
  Eigen::VectorXd yG(m), xG;
  for (PetscInt i = 0; i < m; ++i) yG[i] = f[d->factorRow[i]];
  const Eigen::VectorXd gOwn = d->Lgg * yG;
  const std::vector<PetscScalar> g(gOwn.data(), gOwn.data() + m);
  PetscCall(interfaceSolve(*d, comm, g, false, &xG));
  const Eigen::VectorXd zG = d->Ugg * xG.segment(d->ownOffset, m);
  for (PetscInt i = 0; i < m; ++i) f[d->factorRow[i]] = zG[i];
  d->lu.backward(f, f);
  if (d->reversed) reorder(*d, f, x);
  PetscFunctionReturn(0);
}

// A^{-T} b with the local factor's full transposed solves (no split transposed sweeps; not on a
// hot path). With S00 = A_GG - A_GI A_II^{-1} A_IG for the own interface:
//   A_loc^T u = [b_I; 0]  gives  S00^T u_G = -A_IG^T A_II^{-T} b_I, so g = b_G + S00^T u_G;
//   S^T x_G = g (all ranks);
//   A_loc^T v = [b_I; S00^T (x_G - u_G)]  gives  v_G = x_G and v_I = A_II^{-T} (b_I - A_GI^T x_G).
PetscErrorCode applyTransposeSweeps(SchurData* d, MPI_Comm comm, const PetscScalar* b, PetscScalar* x) {
  PetscFunctionBeginUser;
  const PetscInt m = static_cast<PetscInt>(d->interface.size());
  PetscScalar* f = d->work.data();
  Eigen::VectorXd uG(m), bG(m), xG;
  for (PetscInt i = 0; i < m; ++i) bG[i] = b[d->interface[i]];
  reorder(*d, b, f);
  for (PetscInt i = 0; i < m; ++i) f[d->factorRow[i]] = 0.0;
  d->lu.solveTransposeInPlace(f);
  for (PetscInt i = 0; i < m; ++i) uG[i] = f[d->factorRow[i]];
  const Eigen::VectorXd gOwn = bG + d->S00.transpose() * uG;
  PetscCall(interfaceSolve(*d, comm, std::vector<PetscScalar>(gOwn.data(), gOwn.data() + m), true, &xG));
  const Eigen::VectorXd xOwn = xG.segment(d->ownOffset, m), c = d->S00.transpose() * (xOwn - uG);

  reorder(*d, b, f);
  for (PetscInt i = 0; i < m; ++i) f[d->factorRow[i]] = c[i];
  d->lu.solveTransposeInPlace(f);
  reorder(*d, f, x);
  for (PetscInt i = 0; i < m; ++i) x[d->interface[i]] = xOwn[i];
  PetscFunctionReturn(0);
}

}  // namespace strand::solvers::schur
