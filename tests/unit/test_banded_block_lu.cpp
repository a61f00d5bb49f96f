// requirement: BandedBlockLu (src/solvers/BandedBlockLu.hpp), the factor of the split sweeps of
// PC strand_interface_schur, is an exact LU of a block matrix with a narrow profile, for every
// block size it has a kernel for (1-6), in the matrix's block order or reversed, with fill inside
// the profile (also when factored again); its sweeps solve A x = b and A^T x = b; its trailing factors give the Schur
// complement of the trailing rows; and a singular diagonal block is reported, not divided by.
// Reference: the same matrix dense, solved by Eigen's LU with partial pivoting. Bounds: Gaussian
// elimination is backward stable (Higham, "Accuracy and Stability of Numerical Algorithms", 2nd ed.
// 2002, Thm. 9.3); these matrices are block diagonally dominant (no growth, condition number below
// 10), so the backward error is a few unit round-offs (1e-14 asserted) and the forward error
// against the dense solve below 1e-13. The trailing factors satisfy
// L_GG U_GG = A_GG - A_GI A_II^{-1} A_IG (Saad, "Iterative Methods for Sparse Linear Systems", 2nd
// ed. 2003, sec. 14.2) to 1e-13 relative.
#include <gtest/gtest.h>
#include <petscmat.h>

#include <Eigen/Dense>
#include <random>

#include "solvers/BandedBlockLu.hpp"

using strand::solvers::BandedBlockLu;

namespace {

// A block matrix of n block rows whose row i reaches from block i - lower(i) to i + upper(i), with
// lower and upper drawn from 0..3 (a variable band: U fills where a row reaches less far than one
// above it), random entries and a dominant diagonal; as PETSc SeqBAIJ and dense.
struct BandedMatrix {
  Mat A = nullptr;
  Eigen::MatrixXd dense;
  BandedMatrix(PetscInt bs, PetscInt n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> reach(0, 3);
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    dense = Eigen::MatrixXd::Zero(bs * n, bs * n);
    for (PetscInt i = 0; i < n; ++i) {
      const PetscInt lo = std::max<PetscInt>(0, i - reach(rng)), hi = std::min<PetscInt>(n - 1, i + reach(rng));
      for (PetscInt j = lo; j <= hi; ++j)
        for (PetscInt a = 0; a < bs; ++a)
          for (PetscInt b = 0; b < bs; ++b) dense(bs * i + a, bs * j + b) = value(rng);
    }
    for (PetscInt r = 0; r < bs * n; ++r) dense(r, r) = 1.0 + dense.row(r).cwiseAbs().sum();
    PetscCallAbort(PETSC_COMM_SELF, MatCreateSeqBAIJ(PETSC_COMM_SELF, bs, bs * n, bs * n, 7, nullptr, &A));
    for (PetscInt r = 0; r < bs * n; ++r)
      for (PetscInt c = 0; c < bs * n; ++c)
        if (dense(r, c) != 0.0 || (r / bs == c / bs))
          PetscCallAbort(PETSC_COMM_SELF, MatSetValue(A, r, c, dense(r, c), INSERT_VALUES));
    PetscCallAbort(PETSC_COMM_SELF, MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
    PetscCallAbort(PETSC_COMM_SELF, MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  }
  ~BandedMatrix() { MatDestroy(&A); }
};

// P with (P v)[factor position of r] = v[r]: the block order reversed, unknowns in a block kept
Eigen::MatrixXd factorOrder(PetscInt bs, PetscInt n, bool reversed) {
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(bs * n, bs * n);
  for (PetscInt r = 0; r < bs * n; ++r) P(reversed ? (n - 1 - r / bs) * bs + r % bs : r, r) = 1.0;
  return P;
}

double backwardError(const Eigen::MatrixXd& A, const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
  return (b - A * x).lpNorm<Eigen::Infinity>() /
         (A.cwiseAbs().rowwise().sum().maxCoeff() * x.lpNorm<Eigen::Infinity>());
}

}  // namespace

TEST(BandedBlockLu, SolvesEveryBlockSizeInEitherOrderLikeADenseLu) {
  for (PetscInt bs = 1; bs <= 6; ++bs)
    for (bool reversed : {false, true}) {
      const PetscInt n = 40;
      BandedMatrix m(bs, n, static_cast<unsigned>(10 * bs + reversed));
      BandedBlockLu lu;
      PetscInt zeroPivot;
      ASSERT_EQ(lu.analyze(m.A, reversed), 0);
      for (int refactor = 0; refactor < 2; ++refactor) {  // the second starts from the first's fill
        ASSERT_EQ(lu.factor(m.A, &zeroPivot), 0);
        ASSERT_EQ(zeroPivot, -1);
      }
      const Eigen::MatrixXd P = factorOrder(bs, n, reversed), F = P * m.dense * P.transpose();
      const Eigen::VectorXd b = Eigen::VectorXd::Random(bs * n);
      for (bool transpose : {false, true}) {
        Eigen::VectorXd x(bs * n);
        if (transpose) {
          x = b;
          lu.solveTransposeInPlace(x.data());
        } else {
          lu.forward(b.data(), x.data());
          lu.backward(x.data(), x.data());
        }
        const Eigen::MatrixXd op = transpose ? Eigen::MatrixXd(F.transpose()) : F;
        const Eigen::VectorXd ref = op.partialPivLu().solve(b);
        const double eta = backwardError(op, x, b), error = (x - ref).lpNorm<Eigen::Infinity>() / ref.lpNorm<Eigen::Infinity>();
        EXPECT_LT(eta, 1e-14) << "bs " << bs << " reversed " << reversed << " transpose " << transpose;
        EXPECT_LT(error, 1e-13) << "bs " << bs << " reversed " << reversed << " transpose " << transpose;
      }
    }
}

TEST(BandedBlockLu, TrailingFactorsGiveTheSchurComplementOfTheTrailingRows) {
  for (PetscInt bs : {2, 3})
    for (bool reversed : {false, true}) {
      const PetscInt n = 30, m = 2 * bs, N = bs * n, I = N - m;
      BandedMatrix a(bs, n, static_cast<unsigned>(100 + bs + reversed));
      BandedBlockLu lu;
      PetscInt zeroPivot;
      ASSERT_EQ(lu.analyze(a.A, reversed), 0);
      ASSERT_EQ(lu.factor(a.A, &zeroPivot), 0);
      const Eigen::MatrixXd P = factorOrder(bs, n, reversed), F = P * a.dense * P.transpose();
      Eigen::MatrixXd L, U;
      lu.trailingFactors(m, &L, &U);
      const Eigen::MatrixXd S = F.bottomRightCorner(m, m) -
                                F.bottomLeftCorner(m, I) * F.topLeftCorner(I, I).partialPivLu().solve(F.topRightCorner(I, m));
      EXPECT_LT((L * U - S).norm() / S.norm(), 1e-13) << "bs " << bs << " reversed " << reversed;
      EXPECT_TRUE(L.isLowerTriangular()) << "bs " << bs;
      EXPECT_TRUE(U.bottomLeftCorner(bs, bs).isZero()) << "bs " << bs;  // block upper triangular
    }
}

TEST(BandedBlockLu, ASingularDiagonalBlockIsReported) {
  const PetscInt bs = 3, n = 20, row = 7;
  BandedMatrix m(bs, n, 7u);
  const PetscInt zeroRow = bs * row;  // block row 7's first row, its diagonal included
  PetscCallAbort(PETSC_COMM_SELF, MatZeroRows(m.A, 1, &zeroRow, 0.0, nullptr, nullptr));
  BandedBlockLu lu;
  PetscInt zeroPivot;
  ASSERT_EQ(lu.analyze(m.A, false), 0);
  ASSERT_EQ(lu.factor(m.A, &zeroPivot), 0);
  EXPECT_EQ(zeroPivot, row);
}
