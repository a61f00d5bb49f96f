// Moments at nodes (internal to the Assembler): each acts on its node's orientation block (the
// cable's slope, a beam's cross-section vector r_y) as the configuration-dependent generalized
// force Q of elements::NodalMoment, scaled by the load factor like the other constant loads.
#pragma once
#include <petscmat.h>

#include <vector>

#include "strand/model/DofMap.hpp"
#include "strand/model/Model.hpp"

namespace strand::assembly {

class NodalMomentLoads {
public:
  NodalMomentLoads(const model::Model& model, const model::DofMap& dofs, const std::vector<double>& q0Local);
  // r -= loadFactor Q on the owned orientation blocks (ghosted-local arrays; x displacements).
  void residual(const double* x, double loadFactor, double* r) const;
  // J += -loadFactor dQ/de, a diagonal block (rows and columns of fixed DOFs left out).
  PetscErrorCode jacobian(const double* x, double loadFactor, Mat J, const std::vector<char>& fixed) const;

private:
  struct Owned {
    PetscInt localBlock;
    model::Vec3 moment;
  };
  int _dim;
  PetscInt _ownedBegin;
  const std::vector<double>& _q0;
  std::vector<Owned> _owned;
};

}  // namespace strand::assembly
