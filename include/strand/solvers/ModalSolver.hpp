// Natural frequencies about a static state with SLEPc (options prefix "modal_").
//
// Generalized Hermitian problem K_T phi = omega^2 M phi on the free DOFs (supported DOFs removed
// with MatCreateSubMatrix), shift-and-invert about target 0 (design section 4).
#pragma once
#include <slepceps.h>

#include <vector>

#include "strand/assembly/Assembler.hpp"

namespace strand::solvers {

struct ModalResult {
  std::vector<double> omega;  // angular frequencies [rad/s], ascending
  std::vector<Vec> shapes;    // full-length mode shapes (zero at supports), caller destroys
  std::vector<double> relativeResidual;  // ||K phi - omega^2 M phi|| / ||K phi||
};

// Tangent stiffness at state X (loadFactor 1), consistent mass; nev lowest modes.
PetscErrorCode solveModes(assembly::Assembler& assembler, Vec X, int nev, ModalResult* result);
void destroyModes(ModalResult* result);

}  // namespace strand::solvers
