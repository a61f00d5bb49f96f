// requirement: the parallel default direct solver (PC strand_interface_schur, InterfaceSchur.hpp)
// solves A x = b and A^T x = b exactly, on any number of ranks, for the Newton matrices of chains,
// and a zero pivot on one rank stops the solve on all of them with a PC failure (no hang). Both
// ways a rank solves its segment are exercised (split sweeps on the end ranks, in the local
// block's order or reversed; the interior solve in the middle at -n 3 and with the sweeps switched
// off), with blocks of 3 (3D) and 2 (2D), and after a refactorization with new values.
// Source of the bound: a direct solve by Gaussian elimination is backward stable, the computed x
// solves (A + dA) x = b with |dA| <= gamma_n |L| |U| (Higham, "Accuracy and Stability of Numerical
// Algorithms", 2nd ed. 2002, Thm. 9.3); for these banded matrices without growth the normwise
// backward error ||b - A x|| / (||A|| ||x||) is a few unit round-offs, and 1e-14 is asserted.
// The same system solved by MUMPS (pivoting, any partition) must give the same x to the forward
// error bound kappa(A) * 1e-14 (kappa estimated by the ratio of extreme diagonal entries, a lower
// bound, times 10).
#include <gtest/gtest.h>
#include <petscksp.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "strand/solvers/InterfaceSchur.hpp"
#include "strand/solvers/StaticSolver.hpp"
#include "support/Belts.hpp"
#include "support/Scenes.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

// The generalized-alpha Newton matrix K + c_V D + c_A M of a cantilever of 60 elements (3D: the
// steel cantilever, blocks of 3; 2D: blocks of 2) at h = 1 ms (c_A = 1 / (beta h^2)) at a bent
// state, its columns scaled by 1 + 0.3 sin(i) so that A != A^T (structure unchanged).
model::SceneDescription cantileverOf(int dim) { return dim == 3 ? steelCantileverUnderGravity(60) : cantilever(2, 60); }

// A closed 2D loop (a belt around two circles, 200 elements, no supports needed for the Newton
// matrix of a dynamic step): its last node is its first, so the natural order is a ring.
model::SceneDescription beltLoop() {
  model::SceneDescription sc = cantilever(2, 200);
  sc.supports.clear();
  model::GeometryDesc& g = sc.bodies[0].geometry;
  g.kind = model::GeometryKind::Wrap;
  g.closed = true;
  for (double x : {0.0, 2.0}) {
    model::WrapTurn w;
    w.center = {x, 0.0, 0.0};
    w.radius = 0.3;
    g.wrap.push_back(w);
  }
  return sc;
}

struct NewtonCantilever {
  solvers::Problem problem;
  Mat A = nullptr;
  Vec X = nullptr, V = nullptr;
  explicit NewtonCantilever(int dim = 3) : NewtonCantilever(cantileverOf(dim)) {}
  explicit NewtonCantilever(const model::SceneDescription& scene) : problem(PETSC_COMM_WORLD, scene) {
    MPI_Comm comm = PETSC_COMM_WORLD;
    PetscCallAbort(comm, problem.createInitialState(&X, &V));
    PetscInt lo, hi;
    PetscCallAbort(comm, VecGetOwnershipRange(X, &lo, &hi));
    for (PetscInt i = lo; i < hi; ++i) PetscCallAbort(comm, VecSetValue(X, i, 1e-3 * std::sin(0.1 * i), INSERT_VALUES));
    PetscCallAbort(comm, VecAssemblyBegin(X));
    PetscCallAbort(comm, VecAssemblyEnd(X));
    PetscCallAbort(comm, problem.dofs().createMatrix(&A, nullptr));
    PetscCallAbort(comm, problem.assembler().dynamicJacobian(X, V, 0.0, 2.0e3, 4.0e6, A));
    Vec scale;
    PetscCallAbort(comm, VecDuplicate(X, &scale));
    for (PetscInt i = lo; i < hi; ++i) PetscCallAbort(comm, VecSetValue(scale, i, 1.0 + 0.3 * std::sin(1.0 * i), INSERT_VALUES));
    PetscCallAbort(comm, VecAssemblyBegin(scale));
    PetscCallAbort(comm, VecAssemblyEnd(scale));
    PetscCallAbort(comm, MatDiagonalScale(A, nullptr, scale));
    PetscCallAbort(comm, VecDestroy(&scale));
  }
  ~NewtonCantilever() {
    MatDestroy(&A);
    VecDestroy(&X);
    VecDestroy(&V);
  }
};

KSP solverFor(Mat A, bool mumps) {
  KSP ksp;
  PC pc;
  PetscCallAbort(PETSC_COMM_WORLD, KSPCreate(PETSC_COMM_WORLD, &ksp));
  PetscCallAbort(PETSC_COMM_WORLD, KSPSetOperators(ksp, A, A));
  PetscCallAbort(PETSC_COMM_WORLD, KSPSetType(ksp, KSPPREONLY));
  PetscCallAbort(PETSC_COMM_WORLD, KSPGetPC(ksp, &pc));
  if (mumps) {
    PetscCallAbort(PETSC_COMM_WORLD, PCSetType(pc, PCLU));
    PetscCallAbort(PETSC_COMM_WORLD, PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  } else {
    PetscCallAbort(PETSC_COMM_WORLD, solvers::InterfaceSchurRegister());
    PetscCallAbort(PETSC_COMM_WORLD, PCSetType(pc, solvers::kPcInterfaceSchur));
  }
  return ksp;
}

double backwardError(Mat A, Vec x, Vec b, bool transpose) {
  Vec r;
  PetscReal rn, an, xn;
  PetscCallAbort(PETSC_COMM_WORLD, VecDuplicate(b, &r));
  PetscCallAbort(PETSC_COMM_WORLD, transpose ? MatMultTranspose(A, x, r) : MatMult(A, x, r));
  PetscCallAbort(PETSC_COMM_WORLD, VecAYPX(r, -1.0, b));
  PetscCallAbort(PETSC_COMM_WORLD, VecNorm(r, NORM_INFINITY, &rn));
  PetscCallAbort(PETSC_COMM_WORLD, MatNorm(A, NORM_INFINITY, &an));
  PetscCallAbort(PETSC_COMM_WORLD, VecNorm(x, NORM_INFINITY, &xn));
  PetscCallAbort(PETSC_COMM_WORLD, VecDestroy(&r));
  return rn / (an * xn);
}

// max |a_ii| / min |a_ii|: a lower bound of the condition number
double diagonalSpread(Mat A) {
  Vec d;
  PetscReal big, small;
  PetscCallAbort(PETSC_COMM_WORLD, MatCreateVecs(A, &d, nullptr));
  PetscCallAbort(PETSC_COMM_WORLD, MatGetDiagonal(A, d));
  PetscCallAbort(PETSC_COMM_WORLD, VecAbs(d));
  PetscCallAbort(PETSC_COMM_WORLD, VecMax(d, nullptr, &big));
  PetscCallAbort(PETSC_COMM_WORLD, VecMin(d, nullptr, &small));
  PetscCallAbort(PETSC_COMM_WORLD, VecDestroy(&d));
  return big / small;
}

int size() {
  PetscMPIInt n;
  MPI_Comm_size(PETSC_COMM_WORLD, &n);
  return n;
}

// The number of ranks that solve their segment `how`, after the set-up of ksp.
int ranksSolving(KSP ksp, solvers::SegmentSolve how) {
  PC pc;
  solvers::SegmentSolve mine;
  PetscCallAbort(PETSC_COMM_WORLD, KSPSetUp(ksp));
  PetscCallAbort(PETSC_COMM_WORLD, KSPGetPC(ksp, &pc));
  PetscCallAbort(PETSC_COMM_WORLD, solvers::InterfaceSchurGetSegmentSolve(pc, &mine));
  int here = mine == how ? 1 : 0, ranks;
  MPI_Allreduce(&here, &ranks, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
  return ranks;
}

// P A P^T for the permutation P that reverses the order of the blocks owned by each rank (each
// rank keeps its rows; unknowns within a block keep their order).
Mat reversedOnEachRank(Mat A) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  PetscInt bs, lo, hi, n;
  const PetscInt* ranges;
  PetscCallAbort(comm, MatGetBlockSize(A, &bs));
  PetscCallAbort(comm, MatGetOwnershipRange(A, &lo, &hi));
  PetscCallAbort(comm, MatGetSize(A, &n, nullptr));
  PetscCallAbort(comm, MatGetOwnershipRanges(A, &ranges));
  const int ranks = size();
  const auto reversed = [&](PetscInt i) {
    const PetscInt p = static_cast<PetscInt>(std::upper_bound(ranges, ranges + ranks + 1, i) - ranges) - 1;
    const PetscInt first = ranges[p], blocks = (ranges[p + 1] - first) / bs;
    return first + (blocks - 1 - (i - first) / bs) * bs + (i - first) % bs;
  };
  Mat R;
  PetscCallAbort(comm, MatCreateBAIJ(comm, bs, hi - lo, hi - lo, n, n, 8, nullptr, 8, nullptr, &R));
  PetscCallAbort(comm, MatSetOption(R, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  for (PetscInt i = lo; i < hi; ++i) {
    PetscInt nc;
    const PetscInt* c;
    const PetscScalar* v;
    PetscCallAbort(comm, MatGetRow(A, i, &nc, &c, &v));
    std::vector<PetscInt> cols(nc);
    for (PetscInt k = 0; k < nc; ++k) cols[k] = reversed(c[k]);
    const PetscInt row = reversed(i);
    PetscCallAbort(comm, MatSetValues(R, 1, &row, nc, cols.data(), v, INSERT_VALUES));
    PetscCallAbort(comm, MatRestoreRow(A, i, &nc, &c, &v));
  }
  PetscCallAbort(comm, MatAssemblyBegin(R, MAT_FINAL_ASSEMBLY));
  PetscCallAbort(comm, MatAssemblyEnd(R, MAT_FINAL_ASSEMBLY));
  return R;
}

// A x = b and A^T x = b by `schur` (set up on A) against MUMPS: the backward and the forward error.
void expectExactSolves(KSP schur, Mat A, const char* label) {
  Vec b, x, ref;
  PetscCallAbort(PETSC_COMM_WORLD, MatCreateVecs(A, &x, &b));
  PetscCallAbort(PETSC_COMM_WORLD, VecDuplicate(x, &ref));
  PetscCallAbort(PETSC_COMM_WORLD, VecSetRandom(b, nullptr));
  const double kappaBound = 10.0 * diagonalSpread(A);
  for (bool transpose : {false, true}) {
    KSP mumps = solverFor(A, true);
    PetscCallAbort(PETSC_COMM_WORLD, transpose ? KSPSolveTranspose(schur, b, x) : KSPSolve(schur, b, x));
    PetscCallAbort(PETSC_COMM_WORLD, transpose ? KSPSolveTranspose(mumps, b, ref) : KSPSolve(mumps, b, ref));
    const double eta = backwardError(A, x, b, transpose);
    PetscReal diff, norm;
    PetscCallAbort(PETSC_COMM_WORLD, VecNorm(ref, NORM_INFINITY, &norm));
    PetscCallAbort(PETSC_COMM_WORLD, VecAXPY(ref, -1.0, x));
    PetscCallAbort(PETSC_COMM_WORLD, VecNorm(ref, NORM_INFINITY, &diff));
    PetscPrintf(PETSC_COMM_WORLD, "%s, transpose %d: backward error %.3e, |x - x_mumps| / |x| = %.3e (bound %.3e)\n",
                label, static_cast<int>(transpose), eta, diff / norm, kappaBound * 1e-14);
    EXPECT_LT(eta, 1e-14) << label;
    EXPECT_LT(diff / norm, kappaBound * 1e-14) << label;
    KSPDestroy(&mumps);
  }
  VecDestroy(&b);
  VecDestroy(&x);
  VecDestroy(&ref);
}

}  // namespace

TEST(InterfaceSchur, SolvesTheNewtonMatrixOfAChainLikeMumps) {
  for (int dim : {3, 2}) {
    NewtonCantilever c(dim);
    KSP schur = solverFor(c.A, false);
    expectExactSolves(schur, c.A, dim == 3 ? "3D (blocks of 3)" : "2D (blocks of 2)");
    KSPDestroy(&schur);
  }
}

// A saddle point: the Newton matrix of seed 001's beam (40 elements) clamped to a turning hub,
// whose slope direction a multiplier holds (r'.n(t) = 0). The multiplier row has a zero diagonal:
// it joins the interface, and the dense Schur complement, factored with partial pivoting, takes it
// (the rest, K + c_V D + c_A M, is regular). Exact as MUMPS, on one rank and two.
TEST(InterfaceSchur, TakesTheMultiplierRowsOfASaddlePointOntoItsInterface) {
  NewtonCantilever c(seed001Beam(7e10, 40, 4.0, 15.0));
  ASSERT_TRUE(c.problem.model().hasConstraints());
  KSP schur = solverFor(c.A, false);
  expectExactSolves(schur, c.A, "hub clamp (one multiplier)");
  PC pc;
  PetscInt interface, interior;
  PetscCallAbort(PETSC_COMM_WORLD, KSPGetPC(schur, &pc));
  PetscCallAbort(PETSC_COMM_WORLD, solvers::InterfaceSchurGetSizes(pc, &interface, &interior));
  EXPECT_GE(interface, 1);  // the multiplier (and, on two ranks, the cut)
  KSPDestroy(&schur);
}

// New values in the same structure (a Newton matrix rebuilt): the set-up refactors (split sweeps:
// the local block itself, whose state changed) and solves exactly again.
TEST(InterfaceSchur, RefactorsWhenTheValuesChange) {
  NewtonCantilever c;
  KSP schur = solverFor(c.A, false);
  expectExactSolves(schur, c.A, "first values");
  PetscCallAbort(PETSC_COMM_WORLD, MatShift(c.A, 3.0e6));  // a larger mass shift
  PetscCallAbort(PETSC_COMM_WORLD, MatScale(c.A, 0.5));
  PetscCallAbort(PETSC_COMM_WORLD, KSPSetOperators(schur, c.A, c.A));
  expectExactSolves(schur, c.A, "new values");
  KSPDestroy(&schur);
}

// With the split sweeps switched off every rank solves by the interior solve (PETSc's LU of A_II,
// here under another ordering set under schur_interior_), exactly.
TEST(InterfaceSchur, SplitSweepsSwitchedOffSolveByTheInteriorSolve) {
  NewtonCantilever c;
  PetscCallAbort(PETSC_COMM_WORLD, PetscOptionsSetValue(nullptr, "-pc_strand_interface_schur_split_sweeps", "false"));
  PetscCallAbort(PETSC_COMM_WORLD, PetscOptionsSetValue(nullptr, "-schur_interior_pc_factor_mat_ordering_type", "nd"));
  KSP schur = solverFor(c.A, false);
  PetscCallAbort(PETSC_COMM_WORLD, KSPSetFromOptions(schur));
  EXPECT_EQ(ranksSolving(schur, solvers::SegmentSolve::InteriorSolve), size());
  expectExactSolves(schur, c.A, "split sweeps off, ND ordering");
  KSPDestroy(&schur);
  PetscCallAbort(PETSC_COMM_WORLD, PetscOptionsClearValue(nullptr, "-pc_strand_interface_schur_split_sweeps"));
  PetscCallAbort(PETSC_COMM_WORLD, PetscOptionsClearValue(nullptr, "-schur_interior_pc_factor_mat_ordering_type"));
}

// The option switched after the set-up, the operator unchanged: the next solve rebuilds the PC the
// other way (both ways exact), instead of applying the cleared one (PCApply sets up a PC whose
// set-up was undone).
TEST(InterfaceSchur, SplitSweepsSwitchedAfterTheSetUpRebuildTheSolve) {
  NewtonCantilever c;
  KSP schur = solverFor(c.A, false);
  const int interiorByDefault = ranksSolving(schur, solvers::SegmentSolve::InteriorSolve);  // middle segments
  EXPECT_LT(interiorByDefault, size());  // the end segments sweep
  PetscCallAbort(PETSC_COMM_WORLD, PetscOptionsSetValue(nullptr, "-pc_strand_interface_schur_split_sweeps", "false"));
  PetscCallAbort(PETSC_COMM_WORLD, KSPSetFromOptions(schur));
  expectExactSolves(schur, c.A, "split sweeps switched off after the set-up");
  EXPECT_EQ(ranksSolving(schur, solvers::SegmentSolve::InteriorSolve), size());
  PetscCallAbort(PETSC_COMM_WORLD, PetscOptionsSetValue(nullptr, "-pc_strand_interface_schur_split_sweeps", "true"));
  PetscCallAbort(PETSC_COMM_WORLD, KSPSetFromOptions(schur));
  expectExactSolves(schur, c.A, "split sweeps switched on again");
  EXPECT_EQ(ranksSolving(schur, solvers::SegmentSolve::InteriorSolve), interiorByDefault);
  KSPDestroy(&schur);
  PetscCallAbort(PETSC_COMM_WORLD, PetscOptionsClearValue(nullptr, "-pc_strand_interface_schur_split_sweeps"));
}

// 61 nodes of two 3-unknown blocks (r, r'), partitioned by METIS by block: a cut between two nodes
// is spanned by one element, whose two nodes are the interface (12 unknowns); a cut between a
// node's r and r' blocks by the two elements at that node (three nodes, 18 unknowns). Every other
// row is interior.
TEST(InterfaceSchur, TheInterfaceIsTheTwoNodesOfEachCutElement) {
  NewtonCantilever c;
  KSP ksp = solverFor(c.A, false);
  PC pc;
  PetscInt interface, interior, total;
  PetscCallAbort(PETSC_COMM_WORLD, KSPSetUp(ksp));
  PetscCallAbort(PETSC_COMM_WORLD, KSPGetPC(ksp, &pc));
  PetscCallAbort(PETSC_COMM_WORLD, solvers::InterfaceSchurGetSizes(pc, &interface, &interior));
  MPI_Allreduce(&interior, &total, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD);
  EXPECT_GE(interface, 12 * (size() - 1));
  EXPECT_LE(interface, 18 * (size() - 1));
  EXPECT_EQ(interface % 3, 0);
  EXPECT_EQ(total + interface, 61 * 6);
  KSPDestroy(&ksp);
}

// A free pulley's block couples to every element of its belt (the two-pulley drive, 100 elements):
// its rows are a hub, the belt rows that reach another rank only through the pulley's columns stay
// interior, so the interface is the pulley's block and the loop's cuts, not the belt (a rank's
// belt rows would all be interface otherwise); the solves are exact, on any number of ranks.
TEST(InterfaceSchur, AFreePulleysBlockIsAHubNotAWholeBeltOfInterface) {
  NewtonCantilever c(twoPulleyDrive(100));
  KSP ksp = solverFor(c.A, false);
  PC pc;
  PetscInt interface, interior;
  PetscCallAbort(PETSC_COMM_WORLD, KSPSetUp(ksp));
  PetscCallAbort(PETSC_COMM_WORLD, KSPGetPC(ksp, &pc));
  PetscCallAbort(PETSC_COMM_WORLD, solvers::InterfaceSchurGetSizes(pc, &interface, &interior));
  PetscPrintf(PETSC_COMM_WORLD, "two-pulley drive on %d ranks: %d interface unknowns\n", size(), static_cast<int>(interface));
  if (size() > 1) {
    EXPECT_LE(interface, 2 + 16 * size());  // the pulley's block; a closed loop has one cut per rank
  }
  expectExactSolves(ksp, c.A, "two-pulley drive, a free pulley");
  KSPDestroy(&ksp);
}

// A zero row in rank 0's interior (the middle of its segment): the segment's LU and then PETSc's LU
// of A_II find an exact zero pivot there; every rank must return from the solve (the interface
// solve is collective) with KSP_DIVERGED_PC_FAILED.
TEST(InterfaceSchur, AZeroPivotOnOneRankFailsTheSolveOnAll) {
  NewtonCantilever c;
  PetscInt lo, hi;
  PetscCallAbort(PETSC_COMM_WORLD, MatGetOwnershipRange(c.A, &lo, &hi));
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const PetscInt row = lo + 6 * ((hi - lo) / 12);  // a node in the middle of rank 0's segment
  PetscCallAbort(PETSC_COMM_WORLD, MatZeroRows(c.A, rank == 0 ? 1 : 0, &row, 0.0, nullptr, nullptr));
  KSP ksp = solverFor(c.A, false);
  Vec b, x;
  PetscCallAbort(PETSC_COMM_WORLD, MatCreateVecs(c.A, &x, &b));
  PetscCallAbort(PETSC_COMM_WORLD, VecSet(b, 1.0));
  PetscCallAbort(PETSC_COMM_WORLD, KSPSolve(ksp, b, x));
  KSPConvergedReason reason;
  PetscCallAbort(PETSC_COMM_WORLD, KSPGetConvergedReason(ksp, &reason));
  EXPECT_EQ(reason, KSP_DIVERGED_PC_FAILED);
  KSPDestroy(&ksp);
  VecDestroy(&b);
  VecDestroy(&x);
}

// The split sweeps (InterfaceSchurSweeps.cpp) serve the segments whose interface is at one end: the
// two end segments of the chain on two or more ranks, never a middle segment (interface at both
// ends); on one rank (no interface) they are a plain solve with the banded LU. DofMap numbers both
// end segments with the interface last, so neither is factored in reverse. The solves above check
// their answers; this checks that those runs took the path meant.
TEST(InterfaceSchur, TheEndSegmentsOfTheChainSolveBySplitSweeps) {
  NewtonCantilever c;
  KSP ksp = solverFor(c.A, false);
  EXPECT_EQ(ranksSolving(ksp, solvers::SegmentSolve::SplitSweeps), size() == 1 ? 1 : 2);
  EXPECT_EQ(ranksSolving(ksp, solvers::SegmentSolve::ReversedSplitSweeps), 0);
  KSPDestroy(&ksp);
}

// The same chain with each rank's blocks numbered in reverse: the end segments now have their
// interface first and solve by split sweeps of the local block factored in reverse block order
// (again at a refactorization), exactly.
TEST(InterfaceSchur, ASegmentNumberedInterfaceFirstSolvesByReversedSweeps) {
  for (int dim : {3, 2}) {
    NewtonCantilever c(dim);
    Mat R = reversedOnEachRank(c.A);
    KSP schur = solverFor(R, false);
    EXPECT_EQ(ranksSolving(schur, solvers::SegmentSolve::ReversedSplitSweeps), size() == 1 ? 0 : 2);
    expectExactSolves(schur, R, dim == 3 ? "3D, reversed" : "2D, reversed");
    PetscCallAbort(PETSC_COMM_WORLD, MatScale(R, 0.5));
    PetscCallAbort(PETSC_COMM_WORLD, KSPSetOperators(schur, R, R));
    expectExactSolves(schur, R, dim == 3 ? "3D, reversed, new values" : "2D, reversed, new values");
    KSPDestroy(&schur);
    MatDestroy(&R);
  }
}

// A closed loop (a belt) numbered in order couples its last block to its first: the natural-order
// banded LU would fill every row to the end (O(n^2) blocks; a 10,000-element loop took 30 s per
// factorization), so its segment is solved by the interior solve in RCM order, exactly.
TEST(InterfaceSchur, AClosedLoopIsNotFactoredInItsNaturalOrder) {
  NewtonCantilever c(beltLoop());
  KSP ksp = solverFor(c.A, false);
  EXPECT_EQ(ranksSolving(ksp, solvers::SegmentSolve::SplitSweeps), 0);
  EXPECT_EQ(ranksSolving(ksp, solvers::SegmentSolve::ReversedSplitSweeps), 0);
  expectExactSolves(ksp, c.A, "closed loop");
  KSPDestroy(&ksp);
}
