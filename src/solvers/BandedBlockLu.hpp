#pragma once
// A block LU of a sequential BAIJ matrix with a narrow profile (a chain segment's local block),
// held in our own storage so that its trailing blocks can be read: the split sweeps of PC
// strand_interface_schur (InterfaceSchurSweeps.cpp) need L_GG and U_GG of the interface, which
// PETSc's factor hides (reading them through its forward and backward sweeps cost nine sweeps of
// the whole segment per factorization, a third of the two-rank set-up at 1e5 elements).
//
// A = L U with L unit lower block triangular and U upper block triangular (bs x bs blocks), no
// pivoting across blocks (like PETSc's BAIJ LU; within a diagonal block its inverse is exact).
// Doolittle's row-by-row elimination (Golub & Van Loan, "Matrix Computations", 4th ed. 2013,
// sec. 3.2 and 4.3, band and profile storage): block row i holds the blocks of columns
// first(i)..last(i), where first(i) is A's first block column in row i (L has no fill before it)
// and last(i) = max(A's last block column in row i, last(k) for first(i) <= k < i) (U's fill),
// so a block tridiagonal chain keeps its band. L's and U's blocks are held apart, each row's
// contiguous, so that each sweep streams only its own factor; U's diagonal blocks are held
// inverted.
//
// The factor's block row i is A's block row i, or n-1-i when `reversed` (a segment numbered with
// its interface first; the blocks' own unknowns keep their order). Vectors passed to the sweeps
// are in factor order.
#include <petscmat.h>

#include <Eigen/Dense>
#include <vector>

namespace strand::solvers {

class BandedBlockLu {
 public:
  BandedBlockLu() = default;
  BandedBlockLu(const BandedBlockLu&) = delete;  // _slot and _fill point into the object's own arrays
  BandedBlockLu& operator=(const BandedBlockLu&) = delete;
  BandedBlockLu(BandedBlockLu&&) = default;  // a vector's move keeps its array
  BandedBlockLu& operator=(BandedBlockLu&&) = default;

  // block sizes with a compiled kernel
  static bool supports(PetscInt bs) { return bs >= 1 && bs <= 6; }

  // The profile of A (MATSEQBAIJ, block size supported) in factor order.
  PetscErrorCode analyze(Mat A, bool reversed);
  // A's values (same nonzero pattern as analyzed) factored. *zeroPivot = -1, or the first block row
  // (factor order) whose diagonal block is singular (the factor is then unusable).
  PetscErrorCode factor(Mat A, PetscInt* zeroPivot);

  // y = L^{-1} b and x = U^{-1} y (in place allowed), and x = A^{-T} b in place.
  void forward(const PetscScalar* b, PetscScalar* y) const;
  void backward(const PetscScalar* y, PetscScalar* x) const;
  void solveTransposeInPlace(PetscScalar* x) const;

  // The trailing m x m parts of L and U (m a multiple of the block size), in factor order.
  void trailingFactors(PetscInt m, Eigen::MatrixXd* L, Eigen::MatrixXd* U) const;


 private:
  PetscInt _bs = 0, _n = 0;
  // per block row: first and last block column held, and the first block of its L and U parts
  std::vector<PetscInt> _first, _last, _lowerStart, _upperStart;
  std::vector<PetscScalar> _lower, _upper;  // bs x bs blocks, column-major: L_ij (j < i), U_ij (j >= i)
  std::vector<PetscScalar*> _slot;          // where A's k-th stored block goes
  std::vector<PetscScalar*> _fill;          // the blocks A has none for

  PetscScalar* block(PetscInt i, PetscInt j) {
    const PetscInt bs2 = _bs * _bs;
    return j < i ? &_lower[bs2 * (_lowerStart[i] + j - _first[i])] : &_upper[bs2 * (_upperStart[i] + j - i)];
  }
  const PetscScalar* block(PetscInt i, PetscInt j) const { return const_cast<BandedBlockLu*>(this)->block(i, j); }

  // the kernels, for blocks of BS, and the call of one for the block size bs
  template <int BS>
  PetscInt factorBlocks();
  template <int BS>
  void forwardBlocks(const PetscScalar* b, PetscScalar* y) const;
  template <int BS>
  void backwardBlocks(const PetscScalar* y, PetscScalar* x) const;
  template <int BS>
  void solveTransposeBlocks(PetscScalar* x) const;
  template <typename Call>
  static auto dispatch(PetscInt bs, const Call& call);
};

}  // namespace strand::solvers
