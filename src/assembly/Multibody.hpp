// Rigid bodies and joints in the assembly (internal to the Assembler; design section 3).
//
// Rigid bodies add their constant mass (2D diag(m, m, J); 3D diag(m I, Jbar (x) I) on natural
// coordinates, model::RigidBody); their weight and applied forces are nodal forces of the model,
// a 3D body's torque the configuration-dependent force 1/2 tau x a_k on its axes (assembled here). A joint with equations g(q) = 0 and multipliers lambda = s mu adds
//   rows of its coordinates:  s G^T mu          (the constraint force, G = dg/dq),
//   rows of its multipliers:  s g(q),
// and to the Newton matrix s H(mu) = s sum_k mu_k d^2 g_k/dq^2, s G^T and s G. The scale s is the
// integrator's (Arnold & Bruls 2007, Sec. 4: 1/(beta h^2) makes the index-3 Newton matrix as well
// conditioned as the unconstrained one); statics use s = 1.
#pragma once
#include <petscmat.h>

#include <vector>

#include "strand/model/DofMap.hpp"
#include "strand/model/Model.hpp"

namespace strand::assembly {

class Multibody {
public:
  Multibody(const model::Model& model, const model::DofMap& dofs, const std::vector<double>& q0Local);
  bool empty() const { return _dofs.localCouplings().empty(); }

  // r += joint terms and - loadFactor Q of 3D torques (ghosted-local arrays; x holds displacements
  // and mu).
  void residual(const double* x, double scale, double loadFactor, double* r) const;
  // J += s H, s G^T, s G of the joints, shiftA M of the rigid bodies and - loadFactor dQ/dq of 3D
  // torques (rows and columns of fixed DOFs left out; gradientsOnly: only s G^T and s G, the saddle
  // matrix of the initial state).
  PetscErrorCode jacobian(const double* x, double scale, double shiftA, double loadFactor, Mat J,
                          const std::vector<char>& fixed, bool gradientsOnly = false) const;
  // M += the rigid bodies' mass matrices (fixed rows and columns left out).
  PetscErrorCode mass(Mat M, const std::vector<char>& fixed) const;
  // r (multiplier rows) += v^T d^2 g_k/dq^2 v: the velocity term of the acceleration-level
  // constraint G a + (dG/dq v) v = 0.
  void velocityTerm(const double* x, const double* v, double* r) const;
  // The GGL stabilization (solvers/ConstrainedStateSpace.hpp) with a second vector w: r += s G^T w on the joint's
  // coordinate rows (w's multiplier entries are the GGL multipliers) and s G w on its multiplier
  // rows (w's coordinate entries are velocities); all columns, supports included.
  void gradientProduct(const double* x, const double* w, double scale, double* r) const;
  // The Newton matrices of that product: C += s G^T, s G (as jacobian(gradientsOnly)), and
  // dC += d(r)/dx = s H(w) on coordinates and s (H_k w)^T on multiplier rows (fixed rows and columns
  // left out; either matrix may be null).
  PetscErrorCode gradientProductJacobian(const double* x, const double* w, double scale, Mat C, Mat dC,
                                         const std::vector<char>& fixed) const;
  // Largest |g| and |G v| over this rank's joints.
  void violation(const double* x, const double* v, double* position, double* velocity) const;

private:
  // A local joint at x: its coordinates q = q0 + x, g, G (row-major, count x n), and mu.
  struct JointState {
    const model::Joint* joint = nullptr;
    const PetscInt* lb = nullptr;  // ghosted-local blocks: multipliers first
    const PetscInt* qb = nullptr;  // ... then the joint's coordinate blocks
    int n = 0;                     // number of coordinates
    double q[elements::kMaxJointCoordinates];
    static constexpr int kMaxEquations = 6;  // a 3D clamp has 5
    double g[kMaxEquations], G[kMaxEquations * elements::kMaxJointCoordinates], mu[kMaxEquations];
  };
  JointState state(int localCoupling, const double* x) const;
  bool isJoint(int localCoupling) const;
  bool isRigidBody(int localCoupling) const;
  // Adds a joint's element matrix (N x N over its blocks, multipliers first) with fixed rows and
  // columns zeroed.
  PetscErrorCode addJointMatrix(int localCoupling, double* Ke, Mat J, const std::vector<char>& fixed) const;
  // Ke (N x N over the body's blocks) += s M of a rigid body; torqueStiffness: += - loadFactor dQ/dq
  // of a 3D body's torque.
  void rigidMass(int body, double s, double* Ke) const;
  void torqueStiffness(int body, double loadFactor, double* Ke) const;

  const model::Model& _model;
  const model::DofMap& _dofs;
  const std::vector<double>& _q0;
};

}  // namespace strand::assembly
