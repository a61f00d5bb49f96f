#include "strand/solvers/ModalSolver.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "strand/solvers/StaticSolver.hpp"

namespace strand::solvers {

PetscErrorCode solveModes(assembly::Assembler& assembler, Vec X, int nev, ModalResult* result) {
  PetscFunctionBeginUser;
  const model::DofMap& dofs = assembler.dofs();
  MPI_Comm comm = dofs.comm();
  Mat K, M, Kf, Mf;
  IS free;
  PetscCall(dofs.createMatrix(&K, "modal_", MATAIJ));
  PetscCall(dofs.createMatrix(&M, "modal_", MATAIJ));
  PetscCall(assembler.staticJacobian(X, 1.0, K));
  PetscCall(assembler.massMatrix(M));
  PetscCall(assembler.freeDofs(&free));
  PetscCall(MatCreateSubMatrix(K, free, free, MAT_INITIAL_MATRIX, &Kf));
  PetscCall(MatCreateSubMatrix(M, free, free, MAT_INITIAL_MATRIX, &Mf));

  EPS eps;
  ST st;
  KSP ksp;
  PetscCall(EPSCreate(comm, &eps));
  PetscCall(EPSSetOptionsPrefix(eps, "modal_"));
  PetscCall(EPSSetOperators(eps, Kf, Mf));
  PetscCall(EPSSetProblemType(eps, EPS_GHEP));
  PetscCall(EPSSetDimensions(eps, nev, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscCall(EPSSetTarget(eps, 0.0));
  PetscCall(EPSSetWhichEigenpairs(eps, EPS_TARGET_MAGNITUDE));
  PetscCall(EPSSetTolerances(eps, 1e-12, 200));
  PetscCall(EPSGetST(eps, &st));
  PetscCall(STSetType(st, STSINVERT));
  PetscCall(STGetKSP(st, &ksp));
  PetscCall(setDirectSolverDefaults(ksp, comm));
  PetscCall(EPSSetFromOptions(eps));
  PetscCall(EPSSolve(eps));

  PetscInt nconv;
  PetscCall(EPSGetConverged(eps, &nconv));
  nconv = std::min<PetscInt>(nconv, nev);
  Vec xr, kx, mx;
  PetscCall(MatCreateVecs(Kf, &xr, &kx));
  PetscCall(VecDuplicate(kx, &mx));
  struct Pair { double omega; Vec shape; double res; };
  std::vector<Pair> pairs;
  const PetscInt* idx;
  PetscInt nFree;
  PetscCall(ISGetLocalSize(free, &nFree));
  PetscCall(ISGetIndices(free, &idx));
  for (PetscInt k = 0; k < nconv; ++k) {
    PetscScalar lambda;
    PetscCall(EPSGetEigenpair(eps, k, &lambda, nullptr, xr, nullptr));
    // residual check, independent of SLEPc's own estimate
    PetscReal nk, nr;
    PetscCall(MatMult(Kf, xr, kx));
    PetscCall(MatMult(Mf, xr, mx));
    PetscCall(VecNorm(kx, NORM_2, &nk));
    PetscCall(VecAXPY(kx, -lambda, mx));
    PetscCall(VecNorm(kx, NORM_2, &nr));
    Vec full;
    PetscCall(dofs.createVector(&full));
    PetscCall(VecSet(full, 0.0));
    const PetscScalar* a;
    PetscCall(VecGetArrayRead(xr, &a));
    PetscCall(VecSetValues(full, nFree, idx, a, INSERT_VALUES));
    PetscCall(VecRestoreArrayRead(xr, &a));
    PetscCall(VecAssemblyBegin(full));
    PetscCall(VecAssemblyEnd(full));
    pairs.push_back({std::sqrt(std::max(0.0, PetscRealPart(lambda))), full, nr / nk});
  }
  PetscCall(ISRestoreIndices(free, &idx));
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.omega < b.omega; });
  for (const Pair& p : pairs) {
    result->omega.push_back(p.omega);
    result->shapes.push_back(p.shape);
    result->relativeResidual.push_back(p.res);
  }
  PetscCall(VecDestroy(&xr));
  PetscCall(VecDestroy(&kx));
  PetscCall(VecDestroy(&mx));
  PetscCall(EPSDestroy(&eps));
  PetscCall(ISDestroy(&free));
  PetscCall(MatDestroy(&Kf));
  PetscCall(MatDestroy(&Mf));
  PetscCall(MatDestroy(&K));
  PetscCall(MatDestroy(&M));
  PetscFunctionReturn(0);
}

void destroyModes(ModalResult* result) {
  for (Vec& v : result->shapes) VecDestroy(&v);
  result->shapes.clear();
  result->omega.clear();
  result->relativeResidual.clear();
}

}  // namespace strand::solvers
