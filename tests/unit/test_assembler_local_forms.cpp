// requirement: the assembler reads a vector of its own layout in place (its ghosts updated, no copy)
// and sums a residual straight into such a vector (Assembler::beginLocal, beginLocalSum); any
// other vector goes through a work copy. Both ways must give the same numbers, bit for bit, and
// leave the inputs' owned values alone, at -n 1 and -n 2 (where the ghosts are real):
//  1. vectors from DofMap::createVector and their duplicates share the layout's ghosts; a plain
//     vector of the same sizes does not, even when given the layout's local-to-global mapping;
//  2. the damped dynamic residual, the strain energy and the Newton matrix of a cable with rigid
//     bodies, joints and a nodal moment (every term that reads X and V) are equal both ways;
//  3. a joint product whose output is one of its inputs (R = W) gives the result of a separate R;
//  4. the element matrices that ElementInserter puts straight into an MPIBAIJ's diagonal part (the
//     elements whose blocks are all owned) make the same Newton, damping and mass matrices as
//     MatSetValuesBlocked into an AIJ matrix, which always takes the general path.
#include <gtest/gtest.h>
#include <petscmat.h>

#include "strand/solvers/Problem.hpp"
#include "support/Scenes.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

MPI_Comm comm() { return PETSC_COMM_WORLD; }

// a random vector of the problem's layout, entries in [-scale/2, scale/2]
Vec randomVector(solvers::Problem& p, unsigned seed, double scale) {
  Vec v;
  PetscRandom r;
  PetscCallAbort(comm(), p.dofs().createVector(&v));
  PetscCallAbort(comm(), PetscRandomCreate(comm(), &r));
  PetscCallAbort(comm(), PetscRandomSetSeed(r, seed));
  PetscCallAbort(comm(), PetscRandomSeed(r));
  PetscCallAbort(comm(), VecSetRandom(v, r));
  PetscCallAbort(comm(), PetscRandomDestroy(&r));
  PetscCallAbort(comm(), VecShift(v, -0.5));
  PetscCallAbort(comm(), VecScale(v, scale));
  return v;
}

// a plain (unghosted) MPI vector with v's values
Vec plainCopy(Vec v) {
  PetscInt n, N;
  Vec w;
  PetscCallAbort(comm(), VecGetLocalSize(v, &n));
  PetscCallAbort(comm(), VecGetSize(v, &N));
  PetscCallAbort(comm(), VecCreateMPI(comm(), n, N, &w));
  PetscCallAbort(comm(), VecCopy(v, w));
  return w;
}

PetscReal maxDifference(Vec a, Vec b) {
  Vec d;
  PetscReal r;
  PetscCallAbort(comm(), VecDuplicate(a, &d));
  PetscCallAbort(comm(), VecWAXPY(d, -1.0, b, a));
  PetscCallAbort(comm(), VecNorm(d, NORM_INFINITY, &r));
  PetscCallAbort(comm(), VecDestroy(&d));
  return r;
}

PetscReal norm(Vec a) {
  PetscReal r;
  PetscCallAbort(comm(), VecNorm(a, NORM_INFINITY, &r));
  return r;
}

TEST(AssemblerLocalForms, VectorsOfTheLayoutShareItsGhostsAndOthersDoNot) {
  solvers::Problem p(comm(), cableWithTwoBodies3d(2e9));
  Vec a, b, plain;
  bool shares;
  PetscCallAbort(comm(), p.dofs().createVector(&a));
  PetscCallAbort(comm(), VecDuplicate(a, &b));
  plain = plainCopy(a);
  PetscCallAbort(comm(), p.dofs().sharesGhosts(a, &shares));
  EXPECT_TRUE(shares);
  PetscCallAbort(comm(), p.dofs().sharesGhosts(b, &shares));
  EXPECT_TRUE(shares);
  PetscCallAbort(comm(), p.dofs().sharesGhosts(plain, &shares));
  EXPECT_FALSE(shares);
  // the layout's mapping alone does not make a vector ours: it needs the ghost slots
  ISLocalToGlobalMapping mapping;
  PetscCallAbort(comm(), VecGetLocalToGlobalMapping(a, &mapping));
  PetscCallAbort(comm(), VecSetLocalToGlobalMapping(plain, mapping));
  PetscCallAbort(comm(), p.dofs().sharesGhosts(plain, &shares));
  EXPECT_FALSE(shares);
  for (Vec* v : {&a, &b, &plain}) VecDestroy(v);
}

TEST(AssemblerLocalForms, InPlaceAndCopiedInputsGiveTheSameResidualEnergyAndMatrix) {
  solvers::Problem p(comm(), cableWithTwoBodies3d(2e9));
  assembly::Assembler& a = p.assembler();
  Vec X = randomVector(p, 1, 1e-2), V = randomVector(p, 2, 1.0);
  Vec Xp = plainCopy(X), Vp = plainCopy(V), X0 = plainCopy(X), V0 = plainCopy(V);
  Vec R, Rp;
  PetscCallAbort(comm(), p.dofs().createVector(&R));
  Rp = plainCopy(R);
  const double t = 0.3;
  PetscCallAbort(comm(), a.residual(X, V, t, R));    // in place, summed into R itself
  PetscCallAbort(comm(), a.residual(Xp, Vp, t, Rp)); // through the work copies
  EXPECT_GT(norm(R), 1.0);
  EXPECT_EQ(maxDifference(R, Rp), 0.0);
  EXPECT_EQ(maxDifference(X, X0), 0.0);  // the inputs' owned values untouched
  EXPECT_EQ(maxDifference(V, V0), 0.0);
  PetscCallAbort(comm(), a.residual(X, V, t, Rp, assembly::SupportRows::Reaction));  // mixed
  PetscCallAbort(comm(), a.residual(Xp, Vp, t, R, assembly::SupportRows::Reaction));
  EXPECT_EQ(maxDifference(R, Rp), 0.0);

  PetscReal U, Up;
  PetscCallAbort(comm(), a.strainEnergy(X, &U));
  PetscCallAbort(comm(), a.strainEnergy(Xp, &Up));
  EXPECT_GT(U, 0.0);
  EXPECT_EQ(U, Up);

  Mat J, Jp;
  PetscBool equal;
  PetscCallAbort(comm(), p.dofs().createMatrix(&J, nullptr));
  PetscCallAbort(comm(), p.dofs().createMatrix(&Jp, nullptr));
  PetscCallAbort(comm(), a.dynamicJacobian(X, V, t, 2e3, 4e6, J, nullptr));
  PetscCallAbort(comm(), a.dynamicJacobian(Xp, Vp, t, 2e3, 4e6, Jp, nullptr));
  PetscCallAbort(comm(), MatEqual(J, Jp, &equal));
  EXPECT_TRUE(equal);
  for (Mat* m : {&J, &Jp}) MatDestroy(m);
  for (Vec* v : {&X, &V, &Xp, &Vp, &X0, &V0, &R, &Rp}) VecDestroy(v);
}

TEST(AssemblerLocalForms, AJointProductIntoOneOfItsInputsIsThatOfASeparateOutput) {
  solvers::Problem p(comm(), cableWithTwoBodies3d(2e9));
  assembly::Assembler& a = p.assembler();
  ASSERT_TRUE(a.hasConstraints());
  Vec X = randomVector(p, 3, 1e-2), W = randomVector(p, 4, 1.0), R;
  PetscCallAbort(comm(), p.dofs().createVector(&R));
  PetscCallAbort(comm(), a.constraintGradientProduct(X, W, R));
  PetscCallAbort(comm(), a.constraintGradientProduct(X, W, W));  // W overwritten by its own product
  EXPECT_GT(norm(R), 0.0);
  EXPECT_EQ(maxDifference(R, W), 0.0);
  for (Vec* v : {&X, &W, &R}) VecDestroy(v);
}

// m converted to AIJ equals ref (AIJ), bit for bit
bool equalAsAij(Mat m, Mat ref) {
  Mat c;
  PetscBool equal;
  PetscCallAbort(comm(), MatConvert(m, MATAIJ, MAT_INITIAL_MATRIX, &c));
  PetscCallAbort(comm(), MatEqual(c, ref, &equal));
  PetscCallAbort(comm(), MatDestroy(&c));
  return equal;
}

TEST(AssemblerLocalForms, ElementsInsertedIntoTheDiagonalPartGiveTheGeneralPathsMatrices) {
  solvers::Problem p(comm(), cableWithTwoBodies3d(2e9));  // damped: the damping matrix too
  assembly::Assembler& a = p.assembler();
  Vec X = randomVector(p, 5, 1e-2), V = randomVector(p, 6, 1.0);
  Mat J, D, M, Ja, Da, Ma;  // default BAIJ (MPIBAIJ on two ranks) and AIJ
  for (Mat* m : {&J, &D, &M}) PetscCallAbort(comm(), p.dofs().createMatrix(m, nullptr));
  for (Mat* m : {&Ja, &Da, &Ma}) PetscCallAbort(comm(), p.dofs().createMatrix(m, nullptr, MATAIJ));
  for (int pass = 0; pass < 2; ++pass) {  // the first assembly fixes the structure, the second reuses it
    PetscCallAbort(comm(), a.dynamicJacobian(X, V, 0.3, 2e3, 4e6, J, D));
    PetscCallAbort(comm(), a.dynamicJacobian(X, V, 0.3, 2e3, 4e6, Ja, Da));
    PetscCallAbort(comm(), a.massMatrix(M));
    PetscCallAbort(comm(), a.massMatrix(Ma));
    PetscReal nJ, nD, nM;
    PetscCallAbort(comm(), MatNorm(J, NORM_FROBENIUS, &nJ));
    PetscCallAbort(comm(), MatNorm(D, NORM_FROBENIUS, &nD));
    PetscCallAbort(comm(), MatNorm(M, NORM_FROBENIUS, &nM));
    EXPECT_GT(nJ, 1e6);
    EXPECT_GT(nD, 0.0);
    EXPECT_GT(nM, 0.0);
    EXPECT_TRUE(equalAsAij(J, Ja)) << "Newton matrix, pass " << pass;
    EXPECT_TRUE(equalAsAij(D, Da)) << "damping matrix, pass " << pass;
    EXPECT_TRUE(equalAsAij(M, Ma)) << "mass matrix, pass " << pass;
  }
  for (Mat* m : {&J, &D, &M, &Ja, &Da, &Ma}) MatDestroy(m);
  for (Vec* v : {&X, &V}) VecDestroy(v);
}

}  // namespace
