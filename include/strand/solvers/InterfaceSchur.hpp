#pragma once
// An exact parallel direct solve for chains (cables, belts, tethers): the PETSc PC type
// "strand_interface_schur", the default of setDirectSolverDefaults (multipliers in dynamics too).
//
// Each rank owns a contiguous segment of the chain. A row is an *interface* row when it couples to
// a column owned by another rank (a non-empty row of the off-process block of the MPI matrix);
// every other row is *interior*. With the rows ordered interior (I) then interface (G),
//   A = [A_II A_IG; A_GI A_GG],
// an interior row couples only to columns of its own rank, so A_II is block diagonal by rank and,
// for a structurally symmetric matrix, A_IG and A_GI couple each rank's interior only to its own
// interface rows. The block elimination (Saad, "Iterative Methods for Sparse Linear Systems",
// 2nd ed. 2003, sec. 14.2.1: the Schur complement on the interface unknowns) then needs
//   - one sequential banded LU per rank, of its own interior, and
//   - the interface Schur complement S = A_GG - sum_ranks A_GI A_II^{-1} A_IG, a dense matrix of
//     the interface size only (12-18 unknowns per cut between two ranks of a 3D cable), held on
//     every rank and factored redundantly:
//   solve A x = b:  y_I = A_II^{-1} b_I;  S x_G = b_G - A_GI y_I;  x_I = A_II^{-1} (b_I - A_IG x_G).
// Each rank solves its own segment one of two ways (src/solvers/InterfaceSchurData.hpp):
//   - split sweeps, when its interface is at one end of the segment (the two end segments of the
//     chain; every rank of a two-rank run): one LU of the whole local block with the interface
//     last (our BandedBlockLu, src/solvers/BandedBlockLu.hpp, whose trailing blocks give L_GG and
//     U_GG), and the interface solve between its forward and backward sweep, so an apply costs
//     one local solve. DofMap numbers an end segment with its interface last, so the local block
//     is factored in its own order; a segment numbered the other way (interface first) is
//     factored with its blocks reversed. Without an interface (one rank) this is a plain banded LU;
//   - the interior solve otherwise (a middle segment, a block not banded in its own order, blocks
//     of more than 6 unknowns): PETSc's LU of A_II (RCM), Z = A_II^{-1} A_IG kept, and an apply is
//     one interior solve plus x_I -= Z x_G.
// Hubs: a block row that reaches more than 16 blocks of other ranks (a free pulley's row reaches
// every element of its belt) is an interface row, and a row that reaches another rank only
// through hub columns stays interior: the interface stays the chain's cuts plus the hubs. An
// interior row may then couple to another rank's interface unknown, so every rank takes the
// interior solve, each rank's part of S (over the interface unknowns its interior touches, a hub's
// row entries sent by its owner) is summed over the ranks, and so is the interface right-hand side.
// Why: a chain's matrix is banded and a one-rank banded LU is already near-optimal; MUMPS's
// distributed nested dissection adds its overheads for almost no parallel work (on two ranks its
// solves took 20 times the one-rank LU's, docs/performance.md).
//
// Its banded part does not pivot, like PETSc's own LU. A row with a zero on the diagonal (a
// Lagrange multiplier's) is put on the interface, whose dense Schur complement is factored with
// partial pivoting: a saddle-point matrix is solved exactly when the rest of it is regular (a
// dynamics Newton matrix K + c_v D + c_a M; setDirectSolverDefaults' regularInterior), else the
// interior LU or S reports a zero pivot (PC failure); a nearly singular rest is caught by a probe
// solve at each set-up (relative residual above 1e-8: PC failure, InterfaceSchurProbeFailed).
// Static mechanisms: MUMPS. The interior solve's local solver has the options prefix <pc prefix>schur_interior_
// (default: preonly, LU, RCM ordering); -<pc prefix>pc_strand_interface_schur_split_sweeps false
// makes every rank use it.
#include <petscpc.h>

namespace strand::solvers {

inline constexpr const char* kPcInterfaceSchur = "strand_interface_schur";

// Registers the PC type (idempotent; call after PetscInitialize).
PetscErrorCode InterfaceSchurRegister();

// Sizes after PCSetUp: interface unknowns (all ranks) and this rank's interior unknowns.
PetscErrorCode InterfaceSchurGetSizes(PC pc, PetscInt* interface, PetscInt* localInterior);

// How a rank solves its own segment (see above).
enum class SegmentSolve { InteriorSolve, SplitSweeps, ReversedSplitSweeps };

// Whether the last set-up's saddle-point probe failed (multiplier rows on the interface of a matrix
// whose rest is nearly singular; the PC then reports PC_SUBPC_ERROR). False for another PC type.
PetscErrorCode InterfaceSchurProbeFailed(PC pc, PetscBool* failed);

// After PCSetUp: how this rank solves its segment.
PetscErrorCode InterfaceSchurGetSegmentSolve(PC pc, SegmentSolve* how);

}  // namespace strand::solvers
