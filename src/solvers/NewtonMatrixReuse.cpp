#include "strand/solvers/NewtonMatrixReuse.hpp"

#include <algorithm>
#include <cmath>

namespace strand::solvers {

PetscErrorCode NewtonMatrixReuse::decide(SNES snes, const NewtonFloor& history, PetscReal shiftA, PetscReal shiftV,
                                         bool* rebuild) {
  PetscFunctionBeginUser;
  PetscInt it;
  PetscCall(SNESGetIterationNumber(snes, &it));
  *rebuild = decideAt(it, history, shiftA, shiftV);
  PetscFunctionReturn(0);
}

bool NewtonMatrixReuse::decideAt(PetscInt it, const NewtonFloor& history, PetscReal shiftA, PetscReal shiftV) {
  bool rebuild;
  if (it == 0) {
    settleRent();
    _reusedThisSolve = false;
    _fullThisSolve = _fullNextSolve;
    _fullNextSolve = false;
  }
  const auto differs = [](PetscReal a, PetscReal b) { return std::abs(a - b) > 1e-12 * std::abs(b); };
  if (_fullThisSolve || !_valid || differs(shiftA, _shiftA) || differs(shiftV, _shiftV) || _contraction <= 0.0 || history.iteration != it)
    rebuild = true;
  else if (it == 0) rebuild = false;  // the predictor: keep the last step's matrix
  else if (!(history.fnorm <= history.fnorm0)) rebuild = true;  // grown (or NaN)
  else if (it == 1) {
    rebuild = history.fnorm > _contraction * history.fnorm0;
    if (!rebuild && _price > 0.0 && _rent >= _currentPrice) rebuild = _boughtThisSolve = true;  // (the header)
  }
  // Later the corrections, not the residual, measure the contraction: near the residual's
  // round-off floor |R| stalls while the corrections still shrink.
  else rebuild = history.contraction() > _contraction;
  _lastIterate = it;
  if (!rebuild) _reusedThisSolve = true;
  if (rebuild) {
    _rebuiltThisSolve = true;
    _rent = 0.0;
    _valid = true;
    _shiftA = shiftA;
    _shiftV = shiftV;
    ++_rebuilds;
  }
  return rebuild;
}

void NewtonMatrixReuse::settleRent() {
  if (_lastIterate >= 0) {
    const PetscInt iterations = _lastIterate + 1;  // one Jacobian call per correction
    if (!_rebuiltThisSolve) _rent += std::max<PetscInt>(0, iterations - 2);
    // a solve that rebuilt the matrix itself (new shifts, the contraction rule, full Newton) says
    // nothing of the bought one
    if (_judgeThisSolve && !_rebuiltThisSolve)
      _currentPrice = iterations > 2 ? std::min(2.0 * _currentPrice, kMaxPriceFactor * _price) : _price;
  }
  _judgeThisSolve = _boughtThisSolve;  // the solve after a bought matrix is the first to use it whole
  _boughtThisSolve = _rebuiltThisSolve = false;
  _lastIterate = -1;
}

bool NewtonMatrixReuse::retryWithFullNewton() {
  _valid = false;
  _boughtThisSolve = _judgeThisSolve = false;  // a failed solve judges no price, and the retry uses no bought matrix
  _fullNextSolve = true;     // whoever retries gets full Newton
  return _reusedThisSolve;   // full Newton failed: from the same start a retry would repeat it
}

}  // namespace strand::solvers
