#pragma once
// The parallel form of the compact mass operator (IsotropicMass.hpp): M_s (x) I_bs as a shell
// whose own-column part is PETSc's SeqMAIJ and whose off-process part visits only its nonzero
// rows (IsotropicMassProduct.cpp says why). MatMult and MatMultAdd only: the operator is for
// products.
#include <petscmat.h>

namespace strand::solvers {

// *op = M_s (x) I_bs for the assembled scalar MPIAIJ M_s (referenced). Collective.
PetscErrorCode splitIsotropicProduct(Mat Ms, PetscInt bs, Mat* op);

}  // namespace strand::solvers
