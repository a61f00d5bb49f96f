#pragma once
// The mass as time stepping applies it (M v: two to four products per step). When every bs x bs
// block of the assembled mass is a multiple of the identity, M = M_s (x) I_bs: the ANCF cable's
// consistent mass rho A int N^T N dx (x) I_D (docs/elements/ancf-cable.md, "Mass") and point masses
// m N^T N (x) I_D (seed 003 Eq. 53). It is then stored as the scalar M_s, one entry per pair of
// coupled blocks, behind PETSc's MAIJ (M_s (x) I_bs, MatCreateMAIJ) on one rank and behind a shell
// on more, whose off-process part visits only its nonzero rows (src/solvers/IsotropicMassProduct.cpp:
// MPIMAIJ streams every row of it). For a 3D cable that is 12
// bytes per block pair against the BAIJ block's 72 (nine values, six of them zero), so a product,
// bound by memory bandwidth, reads about a sixth of the bytes. Any other block (a rigid body's
// inertia, Euler parameters) keeps the BAIJ matrix, or, when zeros are most of what it stores (the
// ALE kinds keep their M(q) out of it: their rigid bodies' blocks are all that is left), an AIJ
// copy of its nonzero entries.
#include <petscmat.h>

namespace strand::solvers {

// *op: the compact operator (*compact true; MatMult and MatMultAdd), or, when M is not BAIJ with
// bs > 1 or some block is not a multiple of the identity on some rank, M itself, referenced, or its
// nonzero entries as AIJ when zeros are more than half of what it stores. Collective.
PetscErrorCode isotropicMassOperator(Mat M, Mat* op, PetscBool* compact);

}  // namespace strand::solvers
