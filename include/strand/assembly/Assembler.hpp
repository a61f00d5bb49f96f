// The only place where elements meet PETSc (design section 1).
//
// Gathers element displacements from a ghosted Vec, calls the pure kernels, and scatters residuals
// and tangents into Vec/Mat. Unknowns are displacements u = q - q0 from the reference shape (see
// AncfCable.hpp). Convention (docs/architecture.md): everything on the left-hand side,
//   R(u) = f_int(u, v) - lambda f_ext(u)   (statics: lambda is the load factor),
// rows of supported DOFs are replaced by u_i with unit diagonal.
#pragma once
#include <petscmat.h>

#include <memory>
#include <vector>

#include "strand/model/DofMap.hpp"
#include "strand/model/Model.hpp"

namespace strand::assembly {

// What the rows of supported DOFs hold in a residual: the unit-row convention (the DOF value), or
// the assembled f_int - f_ext, i.e. (with M a added) the force the support exerts on the body.
enum class SupportRows { Value, Reaction };

class Assembler {
public:
  Assembler(const model::Model& model, const model::DofMap& dofs);
  ~Assembler();
  Assembler(const Assembler&) = delete;
  Assembler& operator=(const Assembler&) = delete;

  const model::Model& model() const { return _model; }
  const model::DofMap& dofs() const { return _dofs; }

  // Initial state: zero displacement.
  PetscErrorCode initialState(Vec X) const;
  // Static residual R(X) = f_int(X) - loadFactor f_ext(X); supported rows X.
  PetscErrorCode staticResidual(Vec X, PetscReal loadFactor, Vec R);
  // Its Jacobian dR/dX (unit rows and columns at supports).
  PetscErrorCode staticJacobian(Vec X, PetscReal loadFactor, Mat J);
  // Dynamic residual R(X, V) = f_int(X, V) - f_ext (elastic + Kelvin-Voigt damping, full loads);
  // V may be null (no damping force). The inertia term M A is the integrator's.
  PetscErrorCode residual(Vec X, Vec V, Vec R, SupportRows rows = SupportRows::Value);
  // Newton matrix of an implicit integrator: K + shiftV D + shiftA M with K = df_int/dX,
  // D = df_int/dV (Kelvin-Voigt), M the consistent mass; unit rows and columns at supports.
  PetscErrorCode dynamicJacobian(Vec X, Vec V, PetscReal shiftV, PetscReal shiftA, Mat J);
  // The constant applied loads f_ext (gravity, distributed and nodal forces) at the reference state;
  // nodal moments are evaluated there too (they follow the slope, so they are not constant).
  PetscErrorCode externalForce(Vec F);
  // Consistent mass matrix with point masses; supported rows and columns are zero unless
  // maskSupports is false (prescribed motion: the inertia of moving supports loads the free DOFs).
  PetscErrorCode massMatrix(Mat M, bool maskSupports = true);
  // Sets the supported entries of X, V, A (each may be null) to the prescribed motion at time t:
  // hub supports follow their rotation (model/HubMotion.hpp), the others stay at zero.
  PetscErrorCode prescribedMotion(PetscReal t, Vec X, Vec V, Vec A) const;
  // Zeroes the supported rows of R.
  PetscErrorCode zeroSupportedRows(Vec R) const;
  // Coriolis matrix G = 2 Omega int rho A N^T [e]x N dx of the rotating frame (skew-symmetric);
  // supported rows and columns are zero. The static residual and Jacobian already contain the
  // centrifugal load and its softening -Omega^2 M_P (Model::rotation()).
  PetscErrorCode gyroscopicMatrix(Mat G);
  // Strain energy (all ranks get the sum).
  PetscErrorCode strainEnergy(Vec X, PetscReal* U);
  // Index set of the free (unsupported) DOFs owned by this rank, global numbering.
  PetscErrorCode freeDofs(IS* is) const;
  // Coordinates q = q0 + X as a full-length array in model numbering on rank 0 (empty elsewhere).
  PetscErrorCode gatherToRoot(Vec X, std::vector<double>& modelOrdered);

  struct Impl;  // dimension-specific kernels (Assembler.cpp)

private:
  // Copy `from` into the ghosted work vector (_xWork or _vWork), update its ghosts, and expose its
  // local form (read only); endLocal restores it.
  PetscErrorCode beginLocal(Vec from, Vec work, Vec* local, const PetscScalar** a);
  PetscErrorCode endLocal(Vec work, Vec* local, const PetscScalar** a);
  PetscErrorCode assembleResidual(Vec X, Vec V, PetscReal loadFactor, Vec R, SupportRows rows);
  PetscErrorCode assembleWithSupportDiagonal(Mat J) const;

  const model::Model& _model;
  const model::DofMap& _dofs;
  std::unique_ptr<Impl> _impl;
  Vec _xWork = nullptr, _rWork = nullptr, _vWork = nullptr;  // ghosted work vectors
  std::vector<char> _fixedLocal;           // per DOF of the ghosted local form
  std::vector<char> _noneFixed;            // all zero, same size
  struct MovedBlock {
    PetscInt owned;  // index of its first coordinate among the owned DOFs
    int hub, block;  // HubMotion and index into its blocks
  };
  std::vector<MovedBlock> _moved;          // owned blocks of hub supports
  std::vector<double> _q0Local;            // initial coordinates, ghosted local form
  std::vector<double> _nodalForceOwned;    // constant nodal forces on owned DOFs
  VecScatter _toRoot = nullptr;
  Vec _rootVec = nullptr;
};

}  // namespace strand::assembly
