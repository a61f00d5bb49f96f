// Large-deflection statics: SNES Newton with load stepping (options prefix "static_").
//
// The load factor goes from 0 to 1 in `loadSteps` equal increments; a step whose Newton solve
// fails is retried with half the increment, up to kMaxCutbacks times, before the solve stops and
// reports (solve()'s failure text) the step, the load factor and what to try; the driver turns
// that into exit code 3.
#pragma once
#include <petscsnes.h>

#include <functional>
#include <string>

#include "strand/assembly/Assembler.hpp"
#include "strand/solvers/NewtonConvergence.hpp"

namespace strand::solvers {

struct StaticStep {
  int step = 0;              // accepted load steps so far
  PetscReal loadFactor = 0;  // in (0, 1]
  PetscInt newtonIterations = 0;
  PetscReal residualNorm = 0;
  // The energy of the last Newton correction over the test's reference, e_k / e_ref (NewtonFloor):
  // the squared relative error of the accepted state in the energy norm; -1 if another line search ran.
  PetscReal energyRatio = -1;
};

class StaticSolver {
public:
  using StepCallback = std::function<PetscErrorCode(const StaticStep&, Vec X)>;

  StaticSolver(assembly::Assembler& assembler, int loadSteps);
  ~StaticSolver();
  StaticSolver(const StaticSolver&) = delete;
  StaticSolver& operator=(const StaticSolver&) = delete;

  PetscErrorCode setFromOptions();
  PetscErrorCode view(PetscViewer viewer) const;
  // Solves from the state in X (updated in place); calls onStep after every accepted load step.
  // *failure is empty on success, else it says where and why the solve stopped and what to try;
  // X then holds the last converged state.
  PetscErrorCode solve(Vec X, const StepCallback& onStep, std::string* failure);
  SNES snes() const { return _snes; }
  // A check run after every accepted load step on every rank; when it returns true on any rank the
  // solve stops there (no failure; stoppedByRequest() is then true): a stop signal of a batch job.
  void setStopCheck(std::function<bool()> check) { _stopCheck = std::move(check); }
  bool stoppedByRequest() const { return _stopped; }

private:
  static constexpr int kMaxCutbacks = 8;
  static PetscErrorCode formFunction(SNES, Vec X, Vec R, void* ctx);
  static PetscErrorCode formJacobian(SNES, Vec X, Mat J, Mat P, void* ctx);
  assembly::Assembler& _asm;
  int _loadSteps;
  PetscReal _loadFactor = 0.0;
  NewtonFloor _floor;
  SNES _snes = nullptr;
  Mat _J = nullptr;
  Vec _R = nullptr;
  // A steady material flow (ALE bodies whose material coordinates move at t = 0): the static state
  // is the flow's, its inertia F(X, V0, 0) with the nodes at rest and the material rates V0 in the
  // residual and dF/dX in the Newton matrix (the transport's centripetal rho A v^2 kappa)
  bool _flow = false;
  Vec _V0 = nullptr, _A0 = nullptr, _F = nullptr;
  Mat _Kq = nullptr;
  std::function<bool()> _stopCheck;
  bool _stopped = false;
};

// Direct-solver defaults used by every Strand solver, set only where the user gave no option: the
// interface Schur complement over per-rank banded LUs (InterfaceSchur.hpp; MUMPS in parallel until
// session 13, design section 3), on one rank too (no interface: the banded LU of a chain, or
// PETSc's LU with RCM ordering for another matrix; PETSc's LU with RCM was the serial default until
// session 18).
// saddlePoint: the matrix has zero diagonal entries (Lagrange multipliers), so the factorization
// must pivot. With regularInterior (the matrix without its multiplier rows and columns is regular:
// a dynamics Newton matrix K + c_v D + c_a M, or [M G^T; G 0]) the interface Schur PC takes the
// multiplier rows onto its interface, whose dense Schur complement is factored with pivoting; else
// MUMPS on any number of ranks (PETSc's own LU does not pivot; a static mechanism's K is singular).
PetscErrorCode setDirectSolverDefaults(KSP ksp, bool saddlePoint = false, bool regularInterior = false);

}  // namespace strand::solvers
