// Cross-section and material of a cable, shared by all elements of a body (SI units).
#pragma once

namespace strand::elements {

struct CableSection {
  double EA = 0.0;           // axial stiffness [N]
  double EI = 0.0;           // bending stiffness [N m^2]
  double rhoA = 0.0;         // mass per unit length [kg/m]
  double dampAxial = 0.0;    // Kelvin-Voigt coefficient on the axial strain rate [s]
  double dampBending = 0.0;  // Kelvin-Voigt coefficient on the curvature rate [s]
};

}  // namespace strand::elements
