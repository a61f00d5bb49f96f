// A scene made ready to solve: the model, its parallel DOF layout and its assembler, in the
// order they must be built. Solvers and writers are separate objects that borrow from it.
#pragma once
#include <memory>

#include "strand/assembly/Assembler.hpp"
#include "strand/model/DofMap.hpp"
#include "strand/model/Model.hpp"

namespace strand::solvers {

class Problem {
public:
  Problem(MPI_Comm comm, const model::SceneDescription& scene)
      : _scene(scene), _model(scene), _dofs(comm, _model), _asm(_model, _dofs) {}
  const model::SceneDescription& scene() const { return _scene; }
  const model::Model& model() const { return _model; }
  const model::DofMap& dofs() const { return _dofs; }
  assembly::Assembler& assembler() { return _asm; }
  // New vectors X, V (the caller destroys them) at the scene's initial state: the displacement from
  // the reference shape and the initial velocities (Assembler::initialState, initialVelocity).
  PetscErrorCode createInitialState(Vec* X, Vec* V) {
    PetscFunctionBeginUser;
    PetscCall(_dofs.createVector(X));
    PetscCall(VecDuplicate(*X, V));
    PetscCall(_asm.initialState(*X));
    PetscCall(_asm.initialVelocity(*V));
    PetscFunctionReturn(0);
  }
  // Angular speed of the rotating frame for the next solves (sweeps).
  void setAngularSpeed(double omega) { _model.setAngularSpeed(omega); }

private:
  model::SceneDescription _scene;
  model::Model _model;
  model::DofMap _dofs;
  assembly::Assembler _asm;
};

}  // namespace strand::solvers
