// The only place where elements meet PETSc (design section 1).
//
// Gathers element displacements from a ghosted Vec, calls the pure kernels, and scatters residuals
// and tangents into Vec/Mat. Unknowns are displacements u = q - q0 from the reference shape (see
// AncfCable.hpp). Convention: everything on the left-hand side,
//   R(u) = f_int(u, v) - lambda f_ext(u)   (statics: lambda is the load factor),
// rows of supported DOFs are replaced by u_i with unit diagonal.
#pragma once
#include <petscmat.h>

#include <functional>
#include <initializer_list>
#include <memory>
#include <utility>
#include <vector>

#include "strand/contact/PulleyContact.hpp"
#include "strand/model/DofMap.hpp"
#include "strand/model/Model.hpp"

namespace strand::assembly {

class ElementFamily;
class Multibody;
class NodalMomentLoads;
class PulleyContacts;
class Reels;

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
  // Initial velocities of the scene (rigid bodies' velocity keys; zero elsewhere).
  PetscErrorCode initialVelocity(Vec V) const;

  // Joints (Lagrange multipliers, src/assembly/Multibody.hpp): the multiplier unknowns are
  // mu = lambda / s, their residual rows s g(q), the constraint forces s G^T mu. The integrator sets
  // s (default 1) so that the constrained Newton matrix stays well conditioned.
  void setConstraintScale(PetscReal s) { _constraintScale = s; }
  PetscReal constraintScale() const { return _constraintScale; }
  bool hasConstraints() const { return _model.hasConstraints(); }
  // 1 on owned multiplier DOFs, 0 elsewhere.
  PetscErrorCode multiplierMask(Vec mask) const;
  // 1 on owned supported DOFs (held or prescribed), 0 elsewhere.
  PetscErrorCode supportMask(Vec mask) const;
  // Saddle-point matrix [M G^T; G 0] (masked mass, s = 1, unit rows and columns at supports): the
  // consistent initial accelerations and multipliers, and the projection of initial velocities.
  PetscErrorCode saddleMatrix(Vec X, Mat S);
  // R = 0 except on multiplier rows, where R = v^T (d^2 g_k / dq^2) v (acceleration-level
  // constraint G a = -R).
  PetscErrorCode constraintVelocityTerm(Vec X, Vec V, Vec R);
  // The GGL stabilization of the first-order form (solvers/ConstrainedStateSpace.hpp), with W's
  // coordinate entries velocities and its multiplier entries the GGL multipliers:
  // R = s G^T W on coordinate rows, s G W on multiplier rows (s the constraint scale; every column,
  // supports included; supported rows not overwritten).
  PetscErrorCode constraintGradientProduct(Vec X, Vec W, Vec R);
  // Its Newton matrices: C = [0, s G^T; s G, 0] (the derivative in W) and dC = its derivative in X
  // (each may be null; rows and columns of supported DOFs left out, no unit diagonal).
  PetscErrorCode constraintGradientMatrices(Vec X, Vec W, Mat C, Mat dC);
  // Largest |g(q)| and |G v| over all joints (all ranks get them; 0 without joints).
  PetscErrorCode constraintViolation(Vec X, Vec V, PetscReal* position, PetscReal* velocity);
  // Static residual R(X) = f_int(X) - loadFactor f_ext(X); supported rows X.
  PetscErrorCode staticResidual(Vec X, PetscReal loadFactor, Vec R);
  // Its Jacobian dR/dX (unit rows and columns at supports).
  PetscErrorCode staticJacobian(Vec X, PetscReal loadFactor, Mat J);
  // Dynamic residual R(X, V, t) = f_int(X, V) - f_ext(t) (elastic + Kelvin-Voigt damping, the loads
  // at time t: the constant ones times Model::loadFactor(t) plus the timed nodal forces; joint forces
  // and equations); V may be null (no damping force). The inertia term M A is the integrator's.
  PetscErrorCode residual(Vec X, Vec V, PetscReal t, Vec R, SupportRows rows = SupportRows::Value);
  // Newton matrix of an implicit integrator: K + shiftV D + shiftA M with K = dR/dX at time t
  // (elastic, joints, and the configuration-dependent loads: nodal moments, 3D torques),
  // D = df_int/dV (Kelvin-Voigt), M the consistent mass; unit rows and columns at supports. With
  // D non-null (and V given), D alone is assembled there too (zero rows and columns at supports).
  // With A given, the inertia of kinds whose mass depends on the coordinates is included too
  // (shiftA M(X) + shiftV dF/dV + dF/dX, addInertia).
  PetscErrorCode dynamicJacobian(Vec X, Vec V, PetscReal t, PetscReal shiftV, PetscReal shiftA, Mat J, Mat D = nullptr,
                                 Vec A = nullptr);
  // Kinds whose mass depends on the coordinates (the ALE elements, K::kConstantMass false): their
  // inertia is not in massMatrix(); R += F = M(X) A + Q_p(X, V) adds it (every row, supported ones
  // included). hasVariableMass() tells whether the model has such kinds.
  bool hasVariableMass() const { return !_model.constantMass(); }
  PetscErrorCode addInertia(Vec X, Vec V, Vec A, Vec R);
  // residual(X, damped ? V : null, t, R, rows) + F(X, V, A) in one pass over the elements (the
  // dynamic residual of a model with variable mass; addInertia's F included).
  PetscErrorCode residualWithInertia(Vec X, Vec V, Vec A, bool damped, PetscReal t, Vec R,
                                     SupportRows rows = SupportRows::Value);
  // Its derivatives alone: J = shiftA dF/dA + shiftV dF/dV + dF/dX of the variable-mass kinds at
  // (X, V, A) (supported rows and columns left out, no unit diagonal): the linearized modes about
  // a steady material flow (solvers/ModalSolver.hpp).
  PetscErrorCode inertiaJacobian(Vec X, Vec V, Vec A, PetscReal shiftV, PetscReal shiftA, Mat J);
  // The mass at X: massMatrix() plus M(X) of the variable-mass kinds (the consistent start).
  PetscErrorCode massMatrixAt(Vec X, Mat M, bool maskSupports = true);
  // 1/2 V^T M(X) V of the variable-mass kinds (all ranks; 0 without them); with loadPower, also
  // V . configurationLoads(X) in the same pass (the power of their unscaled loads).
  PetscErrorCode variableKineticEnergy(Vec X, Vec V, PetscReal* T, PetscReal* loadPower = nullptr);
  // The constant applied loads f_ext (gravity, distributed and nodal forces) at the reference state,
  // on every row, supported ones included; nodal moments are evaluated there too (they follow the
  // slope, so they are not constant).
  PetscErrorCode externalForce(Vec F);
  // Time-dependent nodal forces (Model::timedLoads): R += scale * sum_k g_k(t) f_k on owned rows
  // (residual() includes them; the energy monitor uses this for their power).
  bool hasTimedLoads() const { return !_model.timedLoads().empty(); }
  // Distributed loads that depend on the coordinates (the ALE kinds'): whether there are any, and
  // F = Q(X), unscaled by the load factor (ElementFamily::addConfigurationLoads).
  bool hasConfigurationLoads() const;
  PetscErrorCode configurationLoads(Vec X, Vec F);
  PetscErrorCode addTimedLoads(PetscReal t, Vec R, PetscReal scale, bool skipSupported = false) const;
  // Consistent mass matrix with point masses; supported rows and columns are zero unless
  // maskSupports is false (prescribed motion: the inertia of moving supports loads the free DOFs).
  PetscErrorCode massMatrix(Mat M, bool maskSupports = true);
  // Sets the supported entries of X, V, A (each may be null) to the prescribed motion at time t:
  // hub supports follow their rotation (model/HubMotion.hpp), driven rigid bodies' phi their
  // rotation(t), the others stay at zero.
  PetscErrorCode prescribedMotion(PetscReal t, Vec X, Vec V, Vec A) const;
  // Zeroes the supported rows of R.
  PetscErrorCode zeroSupportedRows(Vec R) const;
  // to = R and R = 0 on the supported rows (to's other rows untouched): a residual's support force.
  PetscErrorCode moveSupportedRows(Vec R, Vec to) const;
  // Coriolis matrix G = 2 Omega int rho A N^T [e]x N dx of the rotating frame (skew-symmetric);
  // supported rows and columns are zero. The static residual and Jacobian already contain the
  // centrifugal load and its softening -Omega^2 M_P (Model::rotation()).
  PetscErrorCode gyroscopicMatrix(Mat G);
  // |q0|, the 2-norm of the reference coordinates (all ranks): the scale of round-off in q0 + u.
  PetscReal coordinateNorm() const;
  // Strain energy (all ranks get the sum).
  PetscErrorCode strainEnergy(Vec X, PetscReal* U);
  // The belt-pulley contact points this rank assembles near a pulley (Model::contacts(); V may be
  // null: at rest; statics use t = 0): per body, element, pulley and Gauss point, what the law
  // found there.
  struct ContactPointOut {
    int body, element, pulley, point;
    double r[2];  // position
    contact::ContactPoint state;
  };
  PetscErrorCode contactPoints(Vec X, Vec V, PetscReal t, std::vector<ContactPointOut>& out);
  // F = Q, the contact forces on the belts (every row; V may be null: at rest). residual() holds -Q.
  bool hasContact() const { return !_model.contacts().empty(); }
  PetscErrorCode contactForce(Vec X, Vec V, PetscReal t, Vec F);
  // The contact's stored energy (the normal penalty's potential) and the power of the rest of its
  // force (friction, normal damping, driven pulleys' input): contact::pointEnergy summed over the
  // belts (collective; V may be null).
  PetscErrorCode contactEnergy(Vec X, Vec V, PetscReal t, PetscReal* stored, PetscReal* power);
  // What the belts exert on each pulley (Model::pulleys()): force [N] and torque about its centre
  // [N m, counterclockwise], its speed [rad/s] (a free pulley's from V, null: 0) and a tensioner's
  // slide displacement [m]; collective, every rank gets the sums.
  struct PulleyLoad {
    double fx = 0.0, fy = 0.0, torque = 0.0, speed = 0.0, slide = 0.0;
  };
  PetscErrorCode pulleyLoads(Vec X, Vec V, PetscReal t, std::vector<PulleyLoad>& load);
  // The bristle friction law's history (contact::BristleHistory, docs/contact.md): dynamics
  // commits each accepted state at its time t. For checkpoints, contactHistory() gathers it to every
  // rank as 5 numbers per deflected point (body, element, pulley, Gauss point, z) and the time it
  // belongs to; restoreContactHistory() takes that list on any number of ranks.
  bool hasContactHistory() const;
  PetscErrorCode commitContact(Vec X, Vec V, PetscReal t);
  // The frozen-state iteration (PulleyContacts::settle): *changed = the points, on all ranks, whose
  // stick/slip state at the converged (X, V, t) differs from the one held while Newton solved.
  PetscErrorCode settleContact(Vec X, Vec V, PetscReal t, bool release, PetscInt* changed);
  PetscErrorCode contactHistory(std::vector<double>& packed, double* tn) const;
  void restoreContactHistory(const std::vector<double>& packed, double tn);
  // Index set of the free (unsupported) DOFs owned by this rank, global numbering.
  PetscErrorCode freeDofs(IS* is) const;
  // Coordinates q = q0 + X as a full-length array in model numbering on rank 0 (empty elsewhere).
  PetscErrorCode gatherToRoot(Vec X, std::vector<double>& modelOrdered);
  // X itself in model numbering on rank 0 (empty elsewhere), and back (`in` read on rank 0 only):
  // checkpoints that any number of ranks can read.
  PetscErrorCode toModelOrder(Vec X, std::vector<double>& modelOrdered);
  PetscErrorCode fromModelOrder(const std::vector<double>& modelOrdered, Vec X);

private:
  // The ghosted local form of a global vector, read only. A vector of our DofMap (from
  // DofMap::createVector or a duplicate of one: the solvers' vectors but the first-order state's
  // halves) has its ghosts updated in place; any other is copied into a work vector (_xWork or
  // _vWork) first. endLocal restores it.
  struct LocalRead {
    Vec owner = nullptr, local = nullptr;
    const PetscScalar* a = nullptr;
  };
  PetscErrorCode beginLocal(Vec from, Vec work, LocalRead* view);
  PetscErrorCode endLocal(LocalRead* view);
  // Element sums into a zeroed ghosted local form: R's own when R is a vector of our DofMap and not
  // one of the inputs, else _rWork's. endLocalSum adds the ghosts to their owners (owner then holds the owned result, for
  // edits of owned rows); deliver copies it into R when _rWork was used.
  struct LocalSum {
    Vec owner = nullptr, local = nullptr;
    PetscScalar* a = nullptr;
  };
  PetscErrorCode beginLocalSum(Vec R, std::initializer_list<Vec> inputs, LocalSum* sum);
  PetscErrorCode endLocalSum(LocalSum* sum);
  PetscErrorCode deliver(const LocalSum& sum, Vec R);
  // Owned values to the ghosts, and the ghosts' contributions added to their owners; no-ops when no
  // rank has ghosts (one rank): a scatter costs 1.4 us, 8 per step of a small dynamic run.
  PetscErrorCode updateGhosts(Vec work);
  PetscErrorCode addGhostsToOwners(Vec work);
  // R = the owned sum of add(x, w, r) over the ghosted local forms of X and W (joint terms).
  PetscErrorCode jointVector(Vec X, Vec W, const std::function<void(const double*, const double*, double*)>& add, Vec R);
  // With A: the inertia of the variable-mass kinds too, V then its velocities (and the damping's
  // when damped).
  PetscErrorCode assembleResidual(Vec X, Vec V, PetscReal t, PetscReal loadFactor, Vec R, SupportRows rows,
                                  Vec A = nullptr, bool damped = true);
  PetscErrorCode assembleWithSupportDiagonal(Mat J) const;

  const model::Model& _model;
  const model::DofMap& _dofs;
  std::vector<std::unique_ptr<ElementFamily>> _families;  // one per element group (kind)
  std::unique_ptr<NodalMomentLoads> _moments;
  std::unique_ptr<Multibody> _multibody;
  std::unique_ptr<PulleyContacts> _contacts;
  std::unique_ptr<Reels> _reels;
  PetscReal _constraintScale = 1.0;
  std::vector<char> _multiplierOwned;       // per owned DOF
  std::vector<double> _v0Owned;             // initial velocities, owned DOFs
  Vec _xWork = nullptr, _rWork = nullptr, _vWork = nullptr;  // ghosted work vectors
  Vec _inertiaWork = nullptr;  // addInertia's sum (made at its first call)
  Vec _aWork = nullptr;        // residualWithInertia's local form of A (made at its first call)
  bool _haveGhosts = true;  // on some rank
  std::vector<char> _fixedLocal;           // per DOF of the ghosted local form
  std::vector<char> _noneFixed;            // all zero, same size
  struct MovedBlock {
    PetscInt owned;  // index of its first coordinate among the owned DOFs
    int hub, block;  // HubMotion and index into its blocks
  };
  std::vector<MovedBlock> _moved;          // owned blocks of hub supports
  // owned prescribed coordinates: u = scale (f(t) - f(0)) of the function _movedFunctions[function]
  // (a payout moves every material coordinate of a body by one function: evaluated once per call).
  // Sorted by coordinate; a coordinate moved by several functions (an ALE node between two
  // material_nodes) sums them, its first entry assigning (`first`), so one pass writes each.
  struct MovedCoordinate {
    PetscInt owned;
    int function;
    double scale;
    bool first;
  };
  std::vector<MovedCoordinate> _movedCoordinates;
  std::vector<const model::TimeFunction*> _movedFunctions;  // distinct functions
  mutable std::vector<model::TimeValue> _movedValues;       // their values in prescribedMotion
  std::vector<double> _q0Local;            // initial coordinates, ghosted local form
  // the constant nodal forces and the supported DOFs among the owned ones, as lists: the residual
  // and zeroSupportedRows visit these few entries instead of passing over every owned DOF
  std::vector<std::pair<PetscInt, double>> _nodalForceOwned;  // (owned index, force)
  std::vector<PetscInt> _fixedOwned;                          // owned indices
  VecScatter _toRoot = nullptr;
  Vec _rootVec = nullptr;
};

}  // namespace strand::assembly
