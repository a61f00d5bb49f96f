// The discrete model built from a scene: bodies, DOF blocks, element groups, supports and loads.
// No PETSc here.
//
// Every unknown belongs to a block of `dim` coordinates. A node of a body owns the blocks its element
// kind lays out (elements::KindInfo::layout: the cable's position and slope, a shear beam's position,
// r_x and r_y); a junction makes several bodies' nodes share one position block. Blocks are numbered
// here in scene order ("model numbering"); DofMap renumbers them for the parallel layout.
#pragma once
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "strand/elements/Constraint.hpp"
#include "strand/elements/ElementRegistry.hpp"
#include "strand/model/HubMotion.hpp"
#include "strand/model/SceneDescription.hpp"

namespace strand::model {

struct PointMass {
  int element;  // element index within the body
  double eta;   // local coordinate in [0, 1]
  double mass;  // [kg]
};

// A flexible body: `elements` equal elements of one kind along its initial curve.
struct Body {
  std::string name;
  int kind = 0;  // elements::kindInfo(kind)
  int elements = 0;
  double length = 0.0, elementLength = 0.0;  // the initial curve's length; an element's reference length
                                             // (length / elements, divided by the initial stretch
                                             // for kinds without material coordinates)
  elements::SectionValues section;             // the kind's section keys and options
  elements::BeamProperties properties;         // EA, EI, rho A of the section
  elements::BodyDiscretization discretization; // element length, slope scale, Gauss points
  bool velocityDependent = false;              // its internal force depends on velocities (damping)
  bool closed = false;                         // a loop: its last node is its first (the same blocks)
  int blocksPerNode = 0;
  std::vector<int> nodeBlocks;          // per node, blocksPerNode blocks in the kind's layout (model numbering)
  std::vector<int> posBlock;            // per node: its position block
  std::vector<double> nodeArc;          // per node: its arc length on the initial geometry (n elementLength
                                        // but for an ALE body's material_nodes)
  std::vector<double> referenceValues;  // stress_free: initial: kind-defined values per element (empty: none)
  std::vector<PointMass> pointMasses;
  Vec3 loadPerLength{};                 // gravity rho A g plus distributed loads [N/m]
  double spinTorquePerLength = 0.0;     // distributed torque on the spin angle [N m/m] (AleBeamShaft3d)

  const elements::KindInfo& info() const { return elements::kindInfo(kind); }
  int block(int node, int k) const { return nodeBlocks[node * blocksPerNode + k]; }
  // the block a clamp holds with the position and a moment turns (the cable's slope, a beam's r_y)
  int orientationBlock(int node) const { return block(node, info().orientationBlock); }
  // gradient blocks carry gradientScale * dr/dx (AxialGradient) or dr/dy: the scale of block k
  double blockScale(int k) const {
    return info().layout[k] == elements::BlockRole::AxialGradient ? discretization.gradientScale : 1.0;
  }
};

// A rigid body.
// 2D: position block (x, y of the centre of mass) and rotation block (phi, and one unused
// coordinate held at zero); mass matrix diag(m, m, J).
// 3D: natural coordinates (Garcia de Jalon & Bayo 1994, ch. 3), four consecutive blocks: the
// centre of mass r and the body axes a_1, a_2, a_3 (the columns of the rotation matrix, in
// rotBlock and the two blocks after it). A body point is r + c_k a_k, linear in the coordinates,
// and the kinetic energy 1/2 m |r'|^2 + 1/2 Jbar_kl a_k' . a_l' has the constant mass matrix
// diag(m I, Jbar (x) I) with Jbar = int rho c c^T dV = 1/2 tr(I) 1 - I (I: inertia tensor about the
// centre of mass in the body frame). Six equations a_k . a_l = delta_kl (a joint of the model,
// `frameJoint`) keep the frame orthonormal. A torque tau does the virtual work tau . delta theta
// with delta a_k = delta theta x a_k: the generalized force Q_k = 1/2 tau x a_k on a_k.
struct RigidBody {
  std::string name;
  double mass = 0.0, inertia = 0.0;      // 2D: J
  int posBlock = -1, rotBlock = -1;
  std::array<double, 9> frameInertia{};  // 3D: Jbar, row-major
  Vec3 torque{};                         // 3D: world-frame torque [N m] (2D torques are nodal forces)
  int frameJoint = -1;                   // 3D: index of the orthonormality joint
  int blocks(int dim) const { return dim == 2 ? 2 : 4; }
};

// A joint: its constraint equations over the coordinates of `blocks` (concatenated, dim each), and
// the blocks of its multipliers (equations() of them used, the rest held at zero). The unknowns of
// the multiplier rows are mu = lambda / s, with s the constraint scale of the integrator
// (Assembler::setConstraintScale).
struct Joint {
  std::string label;  // "joints[2] (pin)" for messages
  std::vector<int> blocks, lambdaBlocks;
  std::vector<elements::ConstraintEq> equations;
  int count = 0;  // number of scalar equations
};

// A group of blocks coupled by one rigid body, one joint, or a belt element's contact with a free
// pulley (graph, preallocation and ownership: the rank that owns the first block assembles it).
struct Coupling {
  int rigidBody = -1, joint = -1;
  std::vector<int> blocks;  // joint: multiplier blocks first, then the joint's blocks; contact: the
                            // element's blocks, then the pulley's
  int pulley = -1;
};

// The elements of one kind, over all bodies of that kind: per element its body, its index in the
// body and its blocks (node 1's, then node 2's: blocksPerElement per element).
struct ElementGroup {
  int kind = 0;
  int blocksPerElement = 0;
  std::vector<int> body, index;
  std::vector<int> blocks;
  int size() const { return static_cast<int>(body.size()); }
  const int* blocksOf(int e) const { return &blocks[static_cast<size_t>(e) * blocksPerElement]; }
};

// Scales of the first body for dimensionless input and output (seed 003): length L, rho A, E I,
// E A; T* = sqrt(rho A L^4 / (E I)) turns omega into gamma = omega T* and omega_bar = omega T*.
struct ReferenceScales {
  double length = 1.0, rhoA = 1.0, EI = 1.0, EA = 1.0;
  double time() const;
  double slenderness() const;  // mu = sqrt(A L^2 / I) = sqrt(EA L^2 / EI)
};

// A nodal force scaled by a time function (dynamics): f(t) = function(t) * values on dofs.
struct TimedLoad {
  TimeFunction function;
  std::vector<int> dofs;  // model numbering
  std::vector<double> values;
};

// A moment at a node, acting on its orientation block (Body::orientationBlock).
struct NodalMomentLoad {
  int block;
  Vec3 moment;
};

// Distributed contact of one body with pulleys (issue 34, contact/PulleyContact.hpp): the law,
// integrated with `points` Gauss points per element against each listed pulley.
struct PulleyContactSet {
  int body = 0;                // index into Model::bodies()
  std::vector<int> pulleys;    // indices into Model::pulleys()
  contact::ContactLaw law;
  int points = 4;
};

class Model {
public:
  explicit Model(const SceneDescription& scene);

  int dim() const { return _dim; }
  int numBlocks() const { return _numBlocks; }
  int numDofs() const { return _numBlocks * _dim; }
  const std::vector<Body>& bodies() const { return _bodies; }
  // the elements, one group per element kind present
  const std::vector<ElementGroup>& groups() const { return _groups; }
  int numElements() const;
  // whether some body's internal force depends on velocities (Kelvin-Voigt damping)
  bool velocityDependent() const;
  // whether every body's mass matrix is constant (the integrators and the compact mass need it)
  bool constantMass() const;
  // Reference coordinates q0 (model numbering): the initial shape, axially unstretched; the
  // unknowns are displacements u = q - q0.
  const std::vector<double>& initialCoordinates() const { return _q0; }
  const std::vector<char>& fixedDofs() const { return _fixed; }          // 1 where a support holds the DOF
  const std::vector<RigidBody>& rigidBodies() const { return _rigid; }
  const std::vector<Joint>& joints() const { return _joints; }
  const std::vector<Coupling>& couplings() const { return _couplings; }
  // 1 on the multiplier DOFs that carry an equation (algebraic unknowns of the dynamics)
  const std::vector<char>& multiplierDofs() const { return _multiplier; }
  bool hasConstraints() const { return !_joints.empty(); }
  // whether some ALE node's material coordinate is free (a sliding support): then a node's motion
  // along its tangent and its material coordinate nearly describe the same motion, and only the
  // spacing joints make the Newton matrix regular (its interior without them: cond 1.5e12 on an
  // 8-element rope), so the multipliers cannot be split off (solvers: MUMPS)
  bool freeMaterialCoordinates() const { return _freeMaterial; }
  // Initial velocities per DOF (model numbering; rigid bodies' velocity keys, zero elsewhere).
  const std::vector<double>& initialVelocities() const { return _v0; }
  // Supports on turning hubs (their DOFs are among fixedDofs; the others stay at zero displacement).
  const std::vector<HubMotion>& hubMotions() const { return _hubs; }
  // Single prescribed coordinates (a driven rigid body's phi): u = function(t) - function(0), among
  // fixedDofs (the scene's angle is the one at t = 0).
  struct PrescribedCoordinate {
    int dof;  // model numbering
    TimeFunction function;
    double scale = 1.0;  // u = scale (function(t) - function(0))
  };
  const std::vector<PrescribedCoordinate>& prescribedCoordinates() const { return _prescribed; }
  bool hasPrescribedMotion() const { return !_hubs.empty() || !_prescribed.empty(); }
  const std::vector<double>& nodalForces() const { return _nodalForce; } // constant nodal forces per DOF
  const std::vector<NodalMomentLoad>& nodalMoments() const { return _moments; }
  const std::vector<TimedLoad>& timedLoads() const { return _timed; }  // not in nodalForces()
  // loads.function: the factor of every constant load at time t (1 without one)
  bool hasLoadFunction() const { return _loadFunction.has_value(); }
  double loadFactor(double t) const { return _loadFunction ? _loadFunction->at(t).f : 1.0; }
  const Vec3& gravity() const { return _gravity; }  // also acts on point masses
  // Pulleys and the bodies in contact with them. A free pulley (PulleyDesc::free) has a block of
  // its own, (phi, x): its angle and a tensioner's slide displacement (held at zero without a
  // slide): pulleyBlock(p), -1 for a driven one.
  const std::vector<PulleyDesc>& pulleys() const { return _pulleys; }
  int pulleyBlock(int p) const { return _pulleyBlock[p]; }
  const std::vector<PulleyContactSet>& contacts() const { return _contacts; }
  // Reels (ReelDesc): each has a block of its own (phi, padding held at zero), phi starting at 0;
  // reelBody(r): the index of the body it pays out
  const std::vector<ReelDesc>& reels() const { return _reels; }
  int reelBlock(int r) const { return _reelBlock[r]; }
  int reelBody(int r) const { return _reelBodyIndex[r]; }
  // Rotating frame (absent: omega 0). The angular speed may be changed between solves (sweeps).
  const RotationDesc& rotation() const { return _rotation; }
  void setAngularSpeed(double omega) { _rotation.omega = omega; }
  const ReferenceScales& scales() const { return _scales; }

private:
  struct Build;  // the scene and the name tables while the model is built (Model.cpp)
  void addBodies(Build& b);
  void mergeJunctions(Build& b);
  void addRigidBodiesAndMultipliers(Build& b);
  void placeInitialState(Build& b);
  void addSupports(Build& b);
  bool clampsSlopeDirection(const SupportDesc& s, const Body& b) const;
  std::vector<Vec3> normalsOf(const Vec3& t) const;
  struct ClampDirections {  // per scene support
    std::vector<std::vector<int>> heldSlopeComponents;  // slope components held (a slope along an axis)
    std::vector<std::vector<int>> turningNormals;       // the blocks of the normals a hub turns
  };
  ClampDirections addClampDirectionJoints(Build& b);
  // Sliding supports and reels of ALE bodies: the material dofs left free (model numbering), their
  // spacing joints and the reels' payout joints appended to _joints, the reels' blocks allocated
  std::vector<int> addMaterialJoints(Build& b);
  void addLoads(Build& b);
  void addInitialVelocities(Build& b);
  void addJointEquations(Build& b);
  void addCouplings();
  void addPulleyBlocks(Build& b);
  void addContacts(const SceneDescription& scene);
  void addReelDrives();

  int _dim = 3, _numBlocks = 0;
  bool _freeMaterial = false;
  std::vector<Body> _bodies;
  std::vector<ElementGroup> _groups;
  std::vector<double> _q0, _nodalForce;
  std::vector<char> _fixed, _multiplier;
  std::vector<RigidBody> _rigid;
  std::vector<Joint> _joints;
  std::vector<Coupling> _couplings;
  std::vector<double> _v0;
  std::vector<NodalMomentLoad> _moments;
  std::vector<TimedLoad> _timed;
  std::optional<TimeFunction> _loadFunction;
  std::vector<HubMotion> _hubs;
  std::vector<PrescribedCoordinate> _prescribed;
  Vec3 _gravity{};
  std::vector<PulleyDesc> _pulleys;
  std::vector<int> _pulleyBlock;
  std::vector<PulleyContactSet> _contacts;
  std::vector<ReelDesc> _reels;
  std::vector<int> _reelBlock, _reelBodyIndex;
  RotationDesc _rotation;
  ReferenceScales _scales;
};

}  // namespace strand::model
