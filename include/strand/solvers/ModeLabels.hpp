// What a mode is, by where its kinetic energy lies (issue 36 item 4): each mode shape x (and its
// imaginary part for quadratic problems) is split by direction, x = x_a + x_f + x_c (+ x_t), the
// projections of every position and gradient block onto three orthonormal directions, and the
// spin angles of beam-shafts; each part's share of the kinetic energy is T_d = x_d^T M x_d /
// sum_d. The element masses are isotropic (M = M_s (x) I for positions and gradients), so the
// parts are M-orthogonal and the shares add to one; the spin's polar inertia is its own block.
// Directions: axial a = the first body's chord; in a rotating frame f = the rotation axis
// ("flapwise", out of the plane of rotation) and c = a x f ("lead-lag", in the plane); without
// rotation, the two transverse directions are named by the global axis they lie closest to
// ("bending y", "bending z"; 2D: one in-plane "bending"). Rigid-body modes are "rigid".
#pragma once
#include <string>
#include <vector>

#include "strand/assembly/Assembler.hpp"
#include "strand/solvers/ModalSolver.hpp"

namespace strand::solvers {

struct ModeLabel {
  std::string name;   // the direction with the largest share, or "rigid"
  double share = 0.0;  // that share of the kinetic energy (1 for rigid)
};

// Labels of the modes in `result`; M is the mass matrix they were computed with
// (ModalSolver::massMatrix). Collective.
PetscErrorCode labelModes(assembly::Assembler& assembler, Mat M, const ModalResult& result,
                          std::vector<ModeLabel>* labels);

}  // namespace strand::solvers
