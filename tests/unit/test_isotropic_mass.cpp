// requirement: the compact mass operator of time stepping (solvers/IsotropicMass.hpp) is the
// assembled mass: M x, y + M x into y and into another vector through it equal the BAIJ products
// to round-off (every row sums the same nonzero products; |dy| <= 1e-14 |M| |x| asserted), at -n 1
// (PETSc's MAIJ) and -n 2 (the split product of IsotropicMassProduct.cpp, whose off-process part
// visits only its nonzero rows). It is compact (M_s (x) I) exactly when every block is a multiple
// of the identity, which the theory fixes:
//  - a 3D ANCF cable with a point mass: M = rho A int N^T N dx (x) I_3 + m N^T N (x) I_3
//    (docs/elements/ancf-cable.md "Mass", seed 003 Eq. 53): compact;
//  - 3D rigid bodies in natural coordinates (a point and three unit vectors, each moving as a
//    particle, so their mass is a scalar matrix (x) I_3): compact;
//  - a 2D rigid body (x, y, phi): the mass block of phi is J, not a multiple of the identity of
//    its block: not compact, the BAIJ matrix is kept.
#include <gtest/gtest.h>
#include <petscmat.h>

#include "strand/solvers/IsotropicMass.hpp"
#include "strand/solvers/Problem.hpp"
#include "support/Scenes.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

// builds M, the operator, and returns whether it is compact; asserts the products agree
bool checkOperator(const model::SceneDescription& scene) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  solvers::Problem problem(comm, scene);
  Mat M, op;
  Vec x, y, z;
  PetscBool compact;
  PetscCallAbort(comm, problem.dofs().createMatrix(&M, nullptr));
  PetscCallAbort(comm, problem.assembler().massMatrix(M, false));
  PetscCallAbort(comm, solvers::isotropicMassOperator(M, &op, &compact));
  PetscCallAbort(comm, MatCreateVecs(M, &x, &y));
  PetscCallAbort(comm, VecDuplicate(y, &z));
  PetscCallAbort(comm, VecSetRandom(x, nullptr));
  PetscCallAbort(comm, MatMult(M, x, y));
  PetscCallAbort(comm, MatMult(op, x, z));
  PetscCallAbort(comm, VecAXPY(z, -1.0, y));
  PetscReal diff, mNorm, xNorm;
  PetscCallAbort(comm, VecNorm(z, NORM_INFINITY, &diff));
  PetscCallAbort(comm, MatNorm(M, NORM_INFINITY, &mNorm));
  PetscCallAbort(comm, VecNorm(x, NORM_INFINITY, &xNorm));
  EXPECT_LE(diff, 1e-14 * mNorm * xNorm);
  // MatMultAdd too (time stepping's M a + f)
  PetscCallAbort(comm, VecCopy(y, z));
  PetscCallAbort(comm, MatMultAdd(op, x, z, z));
  PetscCallAbort(comm, VecAXPY(z, -2.0, y));
  PetscCallAbort(comm, VecNorm(z, NORM_INFINITY, &diff));
  EXPECT_LE(diff, 2e-14 * mNorm * xNorm);
  // and into another vector: w = y + M x
  Vec w;
  PetscCallAbort(comm, VecDuplicate(y, &w));
  PetscCallAbort(comm, MatMultAdd(op, x, y, w));
  PetscCallAbort(comm, VecAXPY(w, -2.0, y));
  PetscCallAbort(comm, VecNorm(w, NORM_INFINITY, &diff));
  EXPECT_LE(diff, 2e-14 * mNorm * xNorm);
  for (Vec* v : {&x, &y, &z, &w}) VecDestroy(v);
  MatDestroy(&M);
  MatDestroy(&op);
  return compact == PETSC_TRUE;
}

}  // namespace

TEST(IsotropicMass, CableWithAPointMassIsCompact) {
  model::SceneDescription sc = steelCantileverUnderGravity(20);
  model::PointMassDesc pm;
  pm.at = 0.37;
  pm.mass = 0.2;
  sc.bodies[0].pointMasses.push_back(pm);
  EXPECT_TRUE(checkOperator(sc));
}

TEST(IsotropicMass, RigidBodiesInNaturalCoordinatesAreCompact) {
  EXPECT_TRUE(checkOperator(cableWithTwoBodies3d(1e7)));
}

TEST(IsotropicMass, PlanarRigidBodiesKeepTheBlockMatrix) {
  EXPECT_FALSE(checkOperator(rigidChain(3, 0.5, 1.0)));
}
