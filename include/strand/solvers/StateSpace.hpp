// The first-order (state-space) form of the equations of motion, for integrators of y' = f(t, y)
// or F(t, y, y') = 0: BDF (strand_bdf, StrandBdf.hpp), explicit RK4 (TSRK) and Adams-Bashforth-Moulton
// (AdamsBashforthMoulton.hpp). The state y = (u, v) stacks the displacements and velocities per
// rank, [u_owned; v_owned], so y has twice the parallel layout of the second-order unknowns and the
// halves are viewed in place (no copy) as vectors of that layout.
//
// Implicit form (TS IFunction), with (u_p, v_p, a_p) the prescribed motion of supported DOFs:
//   free rows       u' - v = 0,           M v~' + f_int(u, v) - f_ext = 0,
//   supported rows  u - u_p(t) = 0,       v - v_p(t) = 0,
// where v~' is v' with a_p on supported entries (M keeps supported columns: a turning hub loads
// the body). For y' = sigma y + c (BDF), the Newton matrix is, on free rows,
//   [sigma I, -I; K, sigma M + D]   (unit rows on supported rows),
// and it is solved exactly by eliminating the velocity correction (Schur complement on the
// diagonal block sigma I):
//   (K + sigma D + sigma^2 M) du = r_v + (sigma M + D) r_u,    dv = sigma du - r_u,
// whose matrix is the second-order Newton matrix with shiftV = sigma, shiftA = sigma^2
// (Assembler::dynamicJacobian), factored by the same direct solver. The doubled matrix is never
// assembled: a MatShell applies it and a PCShell inverts it (prefix dyn_reduced_ for the factored
// matrix). Supported columns are dropped from the free rows, as in the second-order path; the
// supported rows are linear, so the Newton iteration is exact once they hold (after one iteration).
//
// Explicit form (TS RHSFunction):
//   u' = v on free rows, v_p(t) on supported rows;
//   v' = M_ff^{-1} (f_ext - f_int(u, v) - M_fs a_p(t)) on free rows, a_p(t) on supported rows,
// with M constant and factored once.
#pragma once
#include <petscts.h>

#include "strand/assembly/Assembler.hpp"

namespace strand::solvers {

class StateSpace {
public:
  // M: the mass with supported columns kept (Assembler::massMatrix(M, false)); supported: 1 on
  // supported DOFs; massSolver: a factored solver of the masked mass with unit diagonal on supported
  // rows (borrowed, not owned; the explicit form needs it, the implicit form only for accelerations).
  StateSpace(assembly::Assembler& assembler, Mat M, Vec supported, KSP massSolver, bool damped);
  ~StateSpace();
  StateSpace(const StateSpace&) = delete;
  StateSpace& operator=(const StateSpace&) = delete;

  PetscErrorCode createState(Vec* Y) const;
  PetscErrorCode pack(Vec X, Vec V, Vec Y);    // copies
  PetscErrorCode unpack(Vec Y, Vec X, Vec V);  // copies; allowed while a view is held
  // Read-only views of the halves of Y (valid until releaseView; one view at a time).
  PetscErrorCode view(Vec Y, Vec* X, Vec* V);
  PetscErrorCode releaseView(Vec Y);

  // Sets the TS's IFunction and IJacobian (MatShell) and the SNES's linear solver (PCShell).
  PetscErrorCode setImplicit(TS ts);
  // The implicit residual F(t, Y, Ydot) (TS IFunction) without a TS (ConstrainedStateSpace builds on it).
  PetscErrorCode implicitResidual(PetscReal t, Vec Y, Vec Ydot, Vec F) { return iFunction(nullptr, t, Y, Ydot, F, this); }
  // Sets the TS's RHSFunction.
  PetscErrorCode setExplicit(TS ts);
  // Accelerations of the state (X, V) at time t: free rows from the mass solve, a_p on supported rows.
  PetscErrorCode acceleration(PetscReal t, Vec X, Vec V, Vec A);
  // Overwrites the supported entries of Y with the prescribed motion at t (explicit schemes, after a step).
  PetscErrorCode prescribe(PetscReal t, Vec Y);

private:
  struct Halves {  // vectors of the second-order layout that view the halves of a state vector
    Vec u = nullptr, v = nullptr;
  };
  PetscErrorCode place(Halves& h, const PetscScalar* a);
  PetscErrorCode reset(Halves& h);
  PetscErrorCode prescribedMotion(PetscReal t);  // _up, _vp, _ap at t (zero on free rows)

  static PetscErrorCode iFunction(TS, PetscReal t, Vec Y, Vec Ydot, Vec F, void* ctx);
  static PetscErrorCode iJacobian(TS, PetscReal t, Vec Y, Vec Ydot, PetscReal shift, Mat J, Mat P, void* ctx);
  static PetscErrorCode rhsFunction(TS, PetscReal t, Vec Y, Vec F, void* ctx);
  static PetscErrorCode shellMult(Mat J, Vec x, Vec y);
  static PetscErrorCode shellApply(PC pc, Vec r, Vec x);

  assembly::Assembler& _asm;
  Mat _M;           // borrowed
  Vec _supported;   // borrowed
  KSP _massSolver;  // borrowed
  bool _damped;
  PetscInt _n = 0, _N = 0;  // local and global size of one half
  Mat _shell = nullptr, _reduced = nullptr, _D = nullptr;  // doubled operator; K + sigma D + sigma^2 M; D
  KSP _reducedSolver = nullptr;
  PetscReal _sigma = 0.0;
  Vec _free = nullptr, _up = nullptr, _vp = nullptr, _ap = nullptr, _w1 = nullptr, _w2 = nullptr;
  Halves _a, _b, _c;  // three simultaneous views inside the callbacks (state, rate, result)
  Halves _view;       // view()
  const PetscScalar* _viewed = nullptr;
};

}  // namespace strand::solvers
