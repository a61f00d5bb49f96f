// BDF with joints: the first-order form y = (u, v) of StateSpace.hpp with Lagrange multipliers,
// on the stabilized index-2 form of Gear, Gupta & Leimkuhler (J. Comput. Appl. Math. 12, 1985;
// Hairer & Wanner, Solving ODEs II, Sec. VII.1 "index reduction", Eq. 1.23), or on the plain
// index-3 form (issue 3's failing method).
//
// The multiplier slots of the second-order layout hold two unknowns here: the u-half slot the
// constraint force multiplier lambda~ = lambda / s, the v-half slot the GGL multiplier mu~. With
// C(q) = [0, s G^T; s G, 0] (Assembler::constraintGradientProduct) the residual is, on free rows,
//   coordinate rows of u:   u' - v + s G^T mu~           (index 3: u' - v)
//   multiplier rows of u:   s G(q) v                     (index 3: mu~, which stays 0)
//   coordinate rows of v:   M v~' + f_int - f_ext + s G^T lambda~
//   multiplier rows of v:   s g(q)
// and u - u_p, v - v_p on supported rows. GGL holds g = 0 and G v = 0 at every step, so neither
// position nor velocity drifts; mu~ is zero for the exact solution and O(h^p) for BDFp.
//
// The Newton matrix of F(t, y, sigma y + c) has the blocks (second-order layout each)
//   [sigma I_q + dC(q, v) , -I_q + C(q)   ]      dC = d(C(q) v)/dq = [s H(mu~), 0; s (H_k v)^T, 0]
//   [K_T(q, lambda~)      , sigma M + D   ]
// and, unlike the unconstrained form, no cheap Schur complement (the -I_q + C block is singular on
// the multiplier rows), so it is assembled as one 2n x 2n AIJ matrix: per rank the rows [u_owned;
// v_owned] as the state vector, preallocated exactly (MATPREALLOCATOR, first call) from the rows of
// the four blocks, and factored by MUMPS (saddle point: zero diagonal on multiplier rows).
#pragma once
#include <petscts.h>

#include <vector>

#include "strand/assembly/Assembler.hpp"
#include "strand/model/SceneDescription.hpp"
#include "strand/solvers/StateSpace.hpp"

namespace strand::solvers {

class ConstrainedStateSpace {
public:
  using Form = model::DynamicsDesc::ConstraintForm;
  // space: the unconstrained form (its residual and its views); supported: 1 on supported DOFs;
  // multipliers: 1 on owned multiplier DOFs.
  ConstrainedStateSpace(assembly::Assembler& assembler, StateSpace& space, Vec supported, Vec multipliers, bool damped,
                        Form form);
  ~ConstrainedStateSpace();
  ConstrainedStateSpace(const ConstrainedStateSpace&) = delete;
  ConstrainedStateSpace& operator=(const ConstrainedStateSpace&) = delete;

  // Sets the TS's IFunction and IJacobian (the assembled 2n x 2n matrix; the SNES's KSP is the
  // caller's direct solver).
  PetscErrorCode setImplicit(TS ts);
  // Tolerance vectors for the adaptive step: atol, rtol on coordinates and velocities, 0 (left out
  // of PETSc's weighted norm) on both multipliers; Index3 keeps every unknown in.
  PetscErrorCode setTolerances(TS ts, PetscReal atol, PetscReal rtol);

  // Public for the Jacobian tests: F(t, Y, Ydot) and the Newton matrix dF/dY + shift dF/dYdot.
  PetscErrorCode residual(PetscReal t, Vec Y, Vec Ydot, Vec F);
  PetscErrorCode jacobian(PetscReal t, Vec Y, PetscReal shift, Mat* J);

private:
  static PetscErrorCode iFunction(TS, PetscReal t, Vec Y, Vec Ydot, Vec F, void* ctx);
  static PetscErrorCode iJacobian(TS, PetscReal t, Vec Y, Vec Ydot, PetscReal shift, Mat J, Mat P, void* ctx);
  PetscErrorCode place(Vec* h, const PetscScalar* a);  // h[0], h[1] view the halves of a
  PetscErrorCode reset(Vec* h);
  // The rows of the blocks into A (the preallocator on the first call, then _J).
  PetscErrorCode fill(Mat A, PetscReal shift);
  PetscInt doubled(PetscInt col, int half) const;  // second-order global index -> state index

  assembly::Assembler& _asm;
  StateSpace& _space;
  bool _damped;
  Form _form;
  PetscInt _n = 0, _rstart = 0;
  std::vector<PetscInt> _ranges;  // second-order ownership ranges
  std::vector<char> _supportedRow, _multiplierRow;  // owned rows
  // masks of the second-order layout: free rows, free multiplier rows, and 1 - the latter
  Vec _free = nullptr, _multiplierRows = nullptr, _otherRows = nullptr, _w = nullptr;
  Vec _atol = nullptr, _rtol = nullptr;
  Mat _K = nullptr, _D = nullptr, _M = nullptr, _C = nullptr, _dC = nullptr, _J = nullptr;
  Vec _a[2] = {nullptr, nullptr}, _c[2] = {nullptr, nullptr};  // views of the halves of a state and a residual
};

}  // namespace strand::solvers
