#pragma once
// When to assemble and factor the Newton matrix again: a modified Newton method whose matrix is
// kept across iterations and time steps while it still contracts the residual fast, and rebuilt at
// the current iterate when it does not (Deuflhard, "Newton Methods for Nonlinear Problems",
// Springer 2004, sec. 2.1.4: simplified Newton with a monitored contraction rate; the same idea as
// the Jacobian reuse of SUNDIALS' CVODE/IDA). The residual stays exact, so the converged state is
// the same as full Newton's to the Newton tolerance; only the path to it changes.
//
// Why it pays for slender structures: the dynamic Newton matrix J = c_A M + c_V D + K(q) is
// dominated by the stiff axial and bending terms, which change with the deformation far more
// slowly than one time step, while an assembly of J costs three residuals (docs/performance.md).
//
// The matrix is never rebuilt at a step's first iterate: the predictor of a stiff model carries
// spurious axial forces (residual 1e5-1e6 N on the 3D cantilever), whose geometric stiffness makes
// a matrix built there worse than the one of the previous step.
#include <petscsnes.h>

#include "strand/solvers/NewtonConvergence.hpp"

namespace strand::solvers {

class NewtonMatrixReuse {
public:
  // contraction: rebuild when the Newton corrections shrink by less than this factor per
  // iteration (|du_k| / |du_{k-1}|; after the first correction |R_1| / |R_0|); 0 rebuilds at every
  // iterate (full Newton).
  explicit NewtonMatrixReuse(PetscReal contraction = 0.1) : _contraction(contraction) {}
  void setContraction(PetscReal c) { _contraction = c; }
  PetscReal contraction() const { return _contraction; }
  // Called from the Jacobian callback at every Newton iterate: whether to rebuild the matrix for
  // the Newton shifts (c_A, c_V) of this step. Leaving the Mat untouched keeps its factorization
  // (PCSetUp refactors only a Mat whose state changed).
  // history: the stopping test's record of this solve (roundoffFloorConvergence).
  PetscErrorCode decide(SNES snes, const NewtonFloor& history, PetscReal shiftA, PetscReal shiftV, bool* rebuild);
  // After a failed solve: whether that solve used a kept matrix, so that a retry with full Newton
  // (a fresh matrix at every iterate, which the next solve then gets) may succeed where it failed.
  bool retryWithFullNewton();
  long rebuilds() const { return _rebuilds; }

private:
  PetscReal _contraction;
  bool _valid = false;
  PetscReal _shiftA = 0.0, _shiftV = 0.0;
  long _rebuilds = 0;
  bool _reusedThisSolve = false, _fullThisSolve = false, _fullNextSolve = false;
};

}  // namespace strand::solvers
