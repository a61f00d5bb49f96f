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
//
// A matrix that still contracts (by less than `contraction`, but by more than the kept matrix's
// stopping test asks, NewtonConvergence.cpp) costs an extra iteration at every step, for ever: a
// tether paying out under gravity, its matrix formed at rest, needs 3 iterations a step where a
// fresh one needs 2. Whether a new matrix pays is the ski-rental problem (Karlin, Manasse, Rudolph,
// Sleator, Algorithmica 3, 1988): keep paying the rent (the extra iterations since the last
// matrix, those beyond the 2 a kept matrix needs at least) until it reaches the price of a new
// matrix (`price`, in Newton iterations), then buy one, at the next step's second iterate; this
// never costs more than twice the best choice made in hindsight. A matrix bought so that does not
// bring the next solve back to 2 iterations (the extra ones come from the nonlinearity within the
// step, not from an old matrix) doubles the price, up to kMaxPriceFactor times `price` (so that a
// transient's doublings cost a later stale matrix at most that many times the rent), and one that
// does restores it. The rent is counted per Newton solve: a contact step solved more than once
// (held stick/slip states) counts each solve.
#include <petscsnes.h>

#include "strand/solvers/NewtonConvergence.hpp"

namespace strand::solvers {

class NewtonMatrixReuse {
public:
  // contraction: rebuild when the Newton corrections shrink by less than this factor per
  // iteration (|du_k| / |du_{k-1}|; after the first correction |R_1| / |R_0|); 0 rebuilds at every
  // iterate (full Newton).
  // price: a new matrix's cost in Newton iterations (assembly and factorization against a residual
  // and a solve: 6 on the 10,000-element cable, 8 on its ALE tether; docs/performance.md); 0 never
  // buys one for the rent.
  explicit NewtonMatrixReuse(PetscReal contraction = 0.1, PetscReal price = 8.0)
      : _contraction(contraction), _price(price), _currentPrice(price) {}
  void setContraction(PetscReal c) { _contraction = c; }
  PetscReal contraction() const { return _contraction; }
  void setPrice(PetscReal p) { _price = _currentPrice = p; }
  PetscReal price() const { return _price; }
  // Called from the Jacobian callback at every Newton iterate: whether to rebuild the matrix for
  // the Newton shifts (c_A, c_V) of this step. Leaving the Mat untouched keeps its factorization
  // (PCSetUp refactors only a Mat whose state changed).
  // history: the stopping test's record of this solve (roundoffFloorConvergence).
  PetscErrorCode decide(SNES snes, const NewtonFloor& history, PetscReal shiftA, PetscReal shiftV, bool* rebuild);
  // The same at Newton iterate it (decide's logic, without an SNES: unit tests feed it histories).
  bool decideAt(PetscInt it, const NewtonFloor& history, PetscReal shiftA, PetscReal shiftV);
  // After a failed solve: whether that solve used a kept matrix, so that a retry with full Newton
  // (a fresh matrix at every iterate, which the next solve then gets) may succeed where it failed.
  bool retryWithFullNewton();
  long rebuilds() const { return _rebuilds; }
  PetscReal currentPrice() const { return _currentPrice; }

  static constexpr PetscReal kMaxPriceFactor = 8.0;

private:
  // At a solve's first iterate: the last solve's iterations as rent, and the judgment of a matrix
  // bought for the rent two solves ago.
  void settleRent();

  PetscReal _contraction;
  PetscReal _price, _currentPrice;  // the price asked now: doubled after a bought matrix did not pay
  PetscReal _rent = 0.0;            // extra iterations with the current matrix
  PetscInt _lastIterate = -1;       // of the current solve
  bool _rebuiltThisSolve = false, _boughtThisSolve = false, _judgeThisSolve = false;
  bool _valid = false;
  PetscReal _shiftA = 0.0, _shiftV = 0.0;
  long _rebuilds = 0;
  bool _reusedThisSolve = false, _fullThisSolve = false, _fullNextSolve = false;
};

}  // namespace strand::solvers
