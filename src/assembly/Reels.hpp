// Reels in the assembly (internal to the Assembler; model::ReelDesc, issue 35, docs/elements/ale.md).
//
// A reel's unknown is its angle phi (component 0 of its block). Its own terms, added by the rank
// that owns the block:
//   inertia   J(phi) phi'',  J(phi) = J_core + rho A R^2 c(phi),  c(phi) = c0 - R phi  (the material
//             wound on it, while c > 0). The material leaves at the drum's surface speed, so it
//             takes its angular momentum with it and no thrust acts: d(J w)/dt - (dJ/dt) w = J w'
//             (the reel as an open system, as the ALE body that takes the material in is one: seed
//             000's mass-transport terms carry the material's momentum across the exit node; the
//             Lagrangian form J phi'' + J' phi'^2 / 2 would count that momentum twice, and moved the
//             braked reel of tests/verification/test_reel.cpp off its closed form by 1.2e-3). The
//             term is configuration-dependent (dJ/dphi = -rho A R^3), like the ALE kinds' M(q) a,
//             and is assembled with them (Assembler::addInertia).
//   damping   c_r phi' on the residual (its torque -c_r w).
// The applied torque is a timed load (Model::timedLoads) and the payout a joint (Model::joints).
#pragma once
#include <petscmat.h>

#include <vector>

#include "strand/model/DofMap.hpp"
#include "strand/model/Model.hpp"

namespace strand::assembly {

class Reels {
public:
  Reels(const model::Model& model, const model::DofMap& dofs);

  // The inertia J(phi) and dJ/dphi at angle phi of reel r.
  double inertia(int r, double phi, double* dJ = nullptr) const;

  // r += c_r phi' (ghosted-local arrays; v null: at rest).
  void residual(const double* v, double* r) const;
  // J += shiftV c_r, D += c_r (rows of fixed DOFs left out; either matrix may be null).
  PetscErrorCode dampingMatrices(double shiftV, Mat J, Mat D, const std::vector<char>& fixed) const;
  // r += J(phi) phi''; J += shiftA J(phi) + dJ/dphi phi'' (fixed rows left out); M += J(phi).
  void inertiaResidual(const double* x, const double* a, double* r) const;
  PetscErrorCode inertiaJacobian(const double* x, const double* a, double shiftA, Mat J, const std::vector<char>& fixed) const;
  PetscErrorCode massAt(const double* x, Mat M, const std::vector<char>& fixed) const;
  // 1/2 J(phi) phi'^2 over this rank's reels.
  double kineticEnergy(const double* x, const double* v) const;

private:
  struct Owned {
    int reel;
    PetscInt local, global;  // the phi row: ghosted-local index and global row
  };
  const model::Model& _model;
  std::vector<Owned> _owned;
  std::vector<double> _rhoA;  // per reel: the mass per length of the body it pays out
};

}  // namespace strand::assembly
