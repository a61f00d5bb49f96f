// The assembly of the elements of one kind (internal to the Assembler): one object per element
// group of the model, one virtual call per assembly pass (none per element). KernelFamily<K>
// (KernelFamily.hpp) implements it for every kind K of elements::AllKinds.
//
// All arrays are ghosted-local forms (model::DofMap): x displacements u = q - q0, v velocities
// (null: none), r a zeroed local residual that the Assembler sums over ranks afterwards. Matrices
// get element blocks with the rows and columns of supported DOFs (`fixed`, per local DOF) zeroed.
#pragma once
#include <petscmat.h>

#include <memory>
#include <vector>

#include "strand/model/DofMap.hpp"
#include "strand/model/Model.hpp"

namespace strand::assembly {

class ElementFamily {
public:
  virtual ~ElementFamily() = default;
  // r += f_int(x, v) - loadFactor (distributed loads and point-mass weights), and the centrifugal
  // load of a rotating frame (scaled by loadFactor as the other loads).
  virtual void residual(const double* x, const double* v, double loadFactor, double* r) const = 0;
  // J += K (and the rotating frame's softening -loadFactor Omega^2 M_P).
  virtual PetscErrorCode jacobian(const double* x, double loadFactor, Mat J, const std::vector<char>& fixed) const = 0;
  // J += K + shiftV D + shiftA M (K with the loads' tangent at loadFactor); Dmat (if not null) += D.
  // With a (and v) for kinds with M(q): their inertia's derivatives too, shiftA M(x) + shiftV dF/dv
  // + dF/dx (inertiaJacobian's) in the same element matrices.
  virtual PetscErrorCode dynamicJacobian(const double* x, const double* v, double loadFactor, double shiftV,
                                         double shiftA, Mat J, Mat Dmat, const std::vector<char>& fixed,
                                         const double* a = nullptr) const = 0;
  // M += the consistent mass with point masses.
  virtual PetscErrorCode mass(Mat M, const std::vector<char>& fixed) const = 0;
  // G += 2 Omega (m (x) [e]x): the Coriolis matrix of the rotating frame.
  virtual PetscErrorCode gyroscopic(Mat G, const std::vector<char>& fixed) const = 0;
  virtual double strainEnergy(const double* x) const = 0;

  // Kinds whose mass depends on the coordinates (K::kConstantMass false, the ALE elements of seed
  // 000) keep their inertia out of mass() and assemble it here; for the others these do nothing.
  virtual bool constantMass() const = 0;
  // r += F = M(x) a + Q_p(x, v), the inertial force of the moving material.
  virtual void inertia(const double* x, const double* v, const double* a, double* r) const = 0;
  // J += shiftA M(x) + shiftV dF/dv + dF/dx.
  virtual PetscErrorCode inertiaJacobian(const double* x, const double* v, const double* a, double shiftV,
                                         double shiftA, Mat J, const std::vector<char>& fixed) const = 0;
  // residual() and inertia() in one pass over the elements (the dynamic residual of a model with
  // M(q)): r += f_int(x, damped ? v : none) - loadFactor f_ext + F(x, v, a).
  virtual void residualWithInertia(const double* x, const double* v, const double* a, bool damped, double loadFactor,
                                   double* r) const = 0;
  // M += M(x) (the consistent start's mass).
  virtual PetscErrorCode massAt(const double* x, Mat M, const std::vector<char>& fixed) const = 0;
  // 1/2 v^T M(x) v; with loadPower, *loadPower += v . Q(x) of the configuration-dependent loads
  // (unscaled) in the same pass.
  virtual double kineticEnergy(const double* x, const double* v, double* loadPower = nullptr) const = 0;

  // Kinds whose distributed loads depend on the coordinates (K::kConfigurationLoads: the ALE kinds'
  // load on the material between their nodes): r += Q(x), unscaled (the energy balance counts its
  // work, v . Q, as it has no potential of the body alone: material enters and leaves with its
  // potential). Nothing for the others.
  virtual bool configurationLoads() const = 0;
  virtual void addConfigurationLoads(const double* x, double* r) const = 0;
};

// The family of the model's element group `local.group` (its kind's KernelFamily).
std::unique_ptr<ElementFamily> makeElementFamily(const model::Model& model, const model::DofMap& dofs,
                                                 const model::DofMap::LocalGroup& local,
                                                 const std::vector<double>& q0Local);

}  // namespace strand::assembly
