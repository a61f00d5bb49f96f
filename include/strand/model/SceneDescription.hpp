// A validated scene: what the YAML file says, in SI units, before any DOF exists.
//
// io/SceneReader fills it and checks every value it can check alone (types, ranges, required keys,
// names that must exist); model/Model builds bodies, nodes and DOFs from it. Each item keeps the
// place it came from (file:line) so that errors found later still point into the scene file.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "strand/contact/PulleyContact.hpp"
#include "strand/elements/ElementKind.hpp"
#include "strand/model/TimeFunction.hpp"

namespace strand::model {

using Vec3 = std::array<double, 3>;

// Where something came from in the scene file, for error messages: "scene.yaml:12: bodies[0].geometry".
struct SourceMark {
  std::string file;
  int line = 0;        // 1-based; 0 when unknown
  std::string key;     // dotted path, e.g. "bodies[0].section.E"
  std::string where() const { return file + ":" + std::to_string(line) + ": " + key; }
};

enum class Analysis { Static, Modes, Dynamic };
enum class GeometryKind { Line, Arc, Polyline, Catenary, Wrap };

// One circle a `wrap` path turns around: centre, the radius of the path on it (a pulley's radius
// plus the wrap's offset), its sense and the full turns it adds to the arc.
struct WrapTurn {
  Vec3 center{};
  double radius = 0.0;
  int sense = 1;  // +1 counterclockwise, -1 clockwise (seen from +z)
  int turns = 0;  // extra full turns on this circle
};

struct GeometryDesc {
  GeometryKind kind = GeometryKind::Line;
  SourceMark mark;
  // line, catenary: end points; catenary: total cable length (> span), hanging along `sag_direction`
  Vec3 start{}, end{};
  double length = 0.0;
  Vec3 sagDirection{0.0, 0.0, 0.0};  // zero: use the gravity direction, else -y (2D) / -z (3D)
  // arc: center, radius, angles in radians, in the plane normal to `normal` (3D; 2D uses the xy plane)
  Vec3 center{};
  double radius = 0.0, startAngle = 0.0, endAngle = 0.0;
  Vec3 normal{0.0, 0.0, 1.0};
  // polyline: corner points (from `points`, or from a CSV `file` of x,y[,z] rows)
  std::vector<Vec3> points;
  // wrap (2D): from `start`, along tangent lines and arcs around each circle in turn, to `end`;
  // closed: around the circles and back to the first (no start, end): a belt loop, whose body's
  // last node is its first
  std::vector<WrapTurn> wrap;
  bool closed = false;
};

struct PointMassDesc {
  double at = 0.0;    // arc length from the body's first node [m] (scene: `at`, or `location` = at / L)
  double mass = 0.0;  // [kg] (scene: `mass`, or `mass_ratio` = mass / (rho A L))
  SourceMark mark;
};

// An ALE body's node whose material coordinate the scene sets: its arc length `at` on the initial
// geometry (default: where equal spacing puts it) and, optionally, a motion: its material
// coordinate moves by motion(t) - motion(0) [m] (else it is held).
struct MaterialNodeDesc {
  long node = 0;  // -1: the last node
  bool hasAt = false;
  double at = 0.0;
  bool hasMotion = false;
  TimeFunction motion;
  SourceMark mark;
};

struct BodyDesc {
  std::string name;
  int kind = 1;  // element kind: an index of elements::kindInfo (elements::findKind("AncfCable3d") = 1)
  int elements = 0;
  GeometryDesc geometry;
  // the kind's section keys (SI) and formulation options, as the kind declares them (ElementKind.hpp)
  elements::SectionValues section;
  bool stressFreeInitial = false;  // true: the initial shape is stress free (kinds that allow it)
  std::vector<PointMassDesc> pointMasses;
  // initial velocity field of a rigid motion (dynamics): v = linear + angular x (r - center) for
  // positions, angular x r' for slopes; 2D: angular about z (angularVelocity[2])
  // ALE bodies (a kind with material coordinates): every node's material coordinate moves by
  // material_motion(t) - material_motion(0) [m] (material flowing through the nodes at the rate
  // material_motion'); without it the material coordinates are held (a Lagrangian mesh)
  bool hasMaterialMotion = false;
  TimeFunction materialMotion;
  // ALE bodies: payout(t) - payout(0) [m] of material enters at node 0 (a reel or a feeder there):
  // node 0's material coordinate falls by it, the last node's is held, the others stay equally
  // spaced between them (seed 000 Eq. 51), so the body's unstretched length grows by the payout
  bool hasPayout = false;
  TimeFunction payout;
  // The initial shape is the material stretched by this factor (lambda0 > 0; a pretension, e.g. a
  // belt's reference strain eps_ref: lambda0 = 1 / (1 + eps_ref)). ALE bodies: material
  // coordinates p = s / lambda0 at arc length s, slopes dr/dp = lambda0 t; the other kinds:
  // elements of reference length L / (N lambda0), slopes dr/dx = lambda0 t
  double initialStretch = 1.0;
  // ALE bodies: nodes whose material coordinate is set one by one (a load point riding on the
  // material, a feeder at an inner node); the nodes between two listed ones stay equally spaced in
  // material (seed 000 Eq. 51). Node 0 and the last node are held at the body's ends unless listed.
  std::vector<MaterialNodeDesc> materialNodes;
  bool hasInitialVelocity = false;
  Vec3 linearVelocity{}, angularVelocity{}, velocityCenter{};
  SourceMark mark;
};

// A node of a body: index 0..elements, or -1 for the last node.
struct NodeRef {
  std::string body;
  long node = 0;
  SourceMark mark;
};

// A support that turns with a hub (rheonomic): the held coordinates follow the rigid rotation by
// the angle psi(t) about `axis` through `center`, r(t) = c + R(psi) (r0 - c), r'(t) = R(psi) r0'.
// Dynamic analysis only; the hub of seed 001 with the spin-up profile Eq. 57 is psi = spin_up.
struct HubDesc {
  bool present = false;
  Vec3 center{};
  Vec3 axis{0.0, 0.0, 1.0};  // unit vector; 2D: z
  TimeFunction angle;        // psi(t) [rad]
  SourceMark mark;
};

// clamped: position and the orientation's direction (a cable's slope keeps its direction, its
// length, the axial stretch, is free; a shear beam's cross-section vector is held whole);
// clamped_unstretched: position and the whole orientation block (zero axial strain at the node);
// pinned: position; fixed: listed coordinates.
enum class SupportType { Clamped, ClampedUnstretched, Pinned, Fixed, Sliding };
struct SupportDesc {
  NodeRef at;
  SupportType type = SupportType::Clamped;
  std::vector<int> dofs;  // Fixed: node coordinate indices 0 .. blocks per node * dim - 1, block by block
  HubDesc hub;            // clamped / pinned only
  SourceMark mark;
};

// Bodies whose listed nodes share one position (their slopes stay independent): cable networks.
struct JunctionDesc {
  std::vector<NodeRef> nodes;
  SourceMark mark;
};

// A rigid body (design section 3). 2D: x, y of the centre of mass and the angle phi, mass matrix
// diag(m, m, J). 3D: the centre of mass and the body frame's axes (natural coordinates, see
// model::RigidBody); the body axes are principal axes of inertia.
struct RigidBodyDesc {
  std::string name;
  double mass = 0.0, inertia = 0.0;      // [kg]; 2D: about the centre of mass [kg m^2]
  Vec3 principalInertia{};                // 3D: about the body axes through the centre of mass [kg m^2]
  Vec3 position{};                        // centre of mass [m]
  double angle = 0.0;                     // [rad]; 3D: the body axes are the world axes turned by angle about axis
  Vec3 axis{0.0, 0.0, 1.0};               // 3D: unit rotation axis of the initial orientation
  Vec3 velocity{};                        // initial velocity of the centre of mass [m/s]
  Vec3 angularVelocity{};                 // [rad/s], world frame (2D: the z entry)
  Vec3 force{};                           // constant applied force at the centre of mass [N]
  Vec3 torque{};                          // constant applied torque [N m], world frame (2D: the z entry)
  std::vector<int> fixed;                 // held coordinates: 0 x, 1 y, 2 phi (2D) or z (3D)
  // driven: the orientation is prescribed, turned by rotation(t) - rotation(0) from the initial one
  // (2D: phi = angle + that; 3D: about rotation_axis, a world direction); a driven hub
  bool driven = false;
  TimeFunction rotation;                  // dynamics only; e.g. spin_up (seed 001 Eq. 57)
  Vec3 rotationAxis{0.0, 0.0, 1.0};       // 3D: unit axis of the driven rotation
  SourceMark mark;
};

// One end of a joint: the ground (a fixed point), a cable node, or a point of a rigid body given
// in the body frame (relative to the centre of mass).
struct JointEndDesc {
  enum class Kind { Ground, CableNode, RigidPoint } kind = Kind::Ground;
  std::string body;
  long node = 0;   // cable node (-1: the last)
  Vec3 point{};    // ground: world point; rigid body: body-frame offset
  SourceMark mark;
};

// Joints held by Lagrange multipliers (index 3, design section 3):
//   pin       the two ends coincide (revolute in 2D, spherical in 3D; two cable nodes: node-to-node);
//   distance  the ends keep the distance `length` (default: the initial distance);
//   clamp     end a (a cable node) coincides with end b and its slope keeps its direction in b's
//             frame (position and slope direction; the slope's length, the axial strain, stays free).
enum class JointType { Pin, Distance, Clamp };
struct JointDesc {
  JointType type = JointType::Pin;
  JointEndDesc a, b;
  double length = -1.0;  // distance: < 0 means the initial distance
  SourceMark mark;
};

struct NodalLoadDesc {
  NodeRef at;
  Vec3 force{}, moment{};  // 2D uses x, y of force and z of moment
  double spinTorque = 0.0;  // [N m] about the centerline, on the spin angle (AleBeamShaft3d, Eq. 45-46)
  bool timed = false;      // force scaled by `function` (dynamics only; no moment then)
  TimeFunction function;
  SourceMark mark;
};

struct DistributedLoadDesc {
  std::string body;
  Vec3 forcePerLength{};  // [N/m], constant along the body
  double spinTorquePerLength = 0.0;  // [N m/m] about the centerline, on the spin angle (AleBeamShaft3d)
  SourceMark mark;
};

struct LoadsDesc {
  Vec3 gravity{};  // [m/s^2]; zero by default
  std::vector<NodalLoadDesc> nodal;
  std::vector<DistributedLoadDesc> distributed;
  bool timed = false;     // dynamics: every constant load above (and rigid bodies' weight, force,
  TimeFunction function;  // torque) scaled by function(t), e.g. a ramp that applies gravity gently
};

struct StaticDesc {
  int loadSteps = 1;  // equal load increments for large deflection
};

// Steady rotation of the frame in which the scene is described (rotating beams, seed 003): the
// bodies feel the centrifugal load Omega^2 rho A P (r - c) (P projects onto the plane normal to
// the axis, c a point on the axis) and, in modal analysis, optionally the Coriolis coupling.
struct RotationDesc {
  bool present = false;
  double omega = 0.0;     // angular speed [rad/s] (the scene may give gamma; the reader converts)
  Vec3 axis{0, 0, 1};     // unit vector; 2D: z
  Vec3 center{};          // a point on the axis [m]
  SourceMark mark;
};

enum class ModalMethod { Auto, Eps, Pep, Projected };
struct ModesDesc {
  int count = 6;          // number of eigenpairs
  bool coriolis = false;  // include the gyroscopic matrix G (quadratic eigenproblem)
  ModalMethod method = ModalMethod::Auto;  // auto: eps without Coriolis; pep up to 5000 DOFs, else projected
  int projectionModes = 0;                 // projected: basis size (0: max(2 count, count + 10))
  bool warmStart = false;  // sweeps: start eps from the previous eigenvectors (can skip a mode, docs/performance.md)
};

// TransportSpeed: the speed v [m/s] of the material through every ALE body's nodes (each body's
// material_motion becomes linear with rate -v / initial_stretch: material flows from node 0 on).
enum class SweepParameter { Gamma, Omega, MassRatio, MassLocation, TransportSpeed };
struct SweepDesc {
  bool present = false;
  SweepParameter parameter = SweepParameter::Gamma;
  double from = 0.0, to = 0.0;
  int points = 2;
  int mass = 0;  // point mass of the first body that mass_ratio / mass_location move
  int refine = 20;  // points of a local sweep around each detected event (0: report the coarse event)
  SourceMark mark;
};

// Time integration (analysis: dynamic). Two families (docs/user-guide.md, "Dynamics"):
//  - generalized-alpha for second-order systems (Arnold & Bruls 2007), fixed step, index-3 joints;
//    Newmark's average acceleration and HHT are parameter choices of it;
//  - the first-order form y = (u, v) (solvers/StateSpace.hpp), no joints: BDF orders 1-5 (PETSc
//    TSBDF, fixed or adaptive step), the classical explicit Runge-Kutta RK4 (TSRK) and the
//    4th-order Adams-Bashforth-Moulton predictor-corrector of seed 001 (solvers/AdamsBashforthMoulton.hpp).
enum class Integrator { GeneralizedAlpha, Newmark, Hht, Bdf, Rk4, Abm4 };
struct DynamicsDesc {
  Integrator integrator = Integrator::GeneralizedAlpha;
  double rhoInf = 0.9;    // spectral radius at infinite frequency (generalized_alpha), 1 = no dissipation
  double hhtAlpha = 0.05; // HHT: alpha in [0, 1/3]; alpha_f = 1 - alpha, gamma = 1/2 + alpha, beta = (1 + alpha)^2 / 4
  int bdfOrder = 2;       // BDF: 1..5
  bool adaptive = false;  // BDF: step size from the local error estimate (rtol, atol); dt is the first step
  double rtol = 1e-4, atol = 1e-6;  // BDF adaptive: weighted error norm of (u [m], v [m/s])
  // BDF with joints: the stabilized index-2 form (GGL; multipliers out of the error norm), or the
  // plain index-3 form with every unknown in the error norm (fails: kept to show why, issue 3)
  enum class ConstraintForm { Ggl, Index3 } constraintForm = ConstraintForm::Ggl;
  double dt = 0.0;        // fixed step [s] (required; adaptive: the first step)
  double tEnd = 0.0;      // final time [s] (required)
  int outputEvery = 1;    // write a frame every k steps (and the last step)
  double dtOut = 0.0;     // > 0: a frame at the first step at or after each multiple of dt_out instead
  int stepCuts = 0;       // second-order integrators: halvings of dt a failed Newton may take (GeneralizedAlphaSetStepCuts)
  SourceMark mark;
};

// Whether the integrator works on the first-order form y = (u, v).
inline bool isFirstOrder(Integrator i) { return i == Integrator::Bdf || i == Integrator::Rk4 || i == Integrator::Abm4; }
inline bool isExplicit(Integrator i) { return i == Integrator::Rk4 || i == Integrator::Abm4; }

struct DiscretizationDesc {
  bool slopeScaling = false;  // slope coordinates times the element length; off: measured more accurate (docs/validation.md)
  int gaussPoints = 5;       // elastic forces; mass uses 4 points (exact)
};

// Probes (scene key `probes`): a point whose position and velocity (and, at a support, the
// support's force on the body) are written every step as /series/probe_<name>_<component>, in a
// chosen frame. The point: a body node, a fraction `at` of a body's length, or a point of a rigid
// body (body-frame offset). The frame: the world, the rotating frame of the hub that turns the
// probe's body (`hub`), or a rigid body's frame (its name).
struct ProbeDesc {
  enum class Kind { Node, Along, RigidPoint };
  std::string name;
  Kind kind = Kind::Node;
  std::string body;     // a body (Node, Along) or a rigid body (RigidPoint)
  long node = 0;        // Node: -1 is the last
  double along = 0.0;   // Along: in [0, 1] of the body's reference length
  Vec3 point{};         // RigidPoint: offset in the body frame
  std::string frame = "world";
  bool force = false;   // the support force on a held node
  SourceMark mark, frameMark;
};

struct OutputDesc {
  std::string file;          // empty: <scene stem>.h5 in the working directory
  int samplesPerElement = 4; // centerline points per element in the output
};

// Floating-frame hub-beam (seed 001; issue 5; src/ffr): a rigid hub turning in its plane about a
// fixed axis, an Euler-Bernoulli beam clamped to it at radius `hubRadius`, its axial and bending
// deformation in the hub's frame discretized by assumed modes, FEM or RPIM. Small dense system;
// scene key `hub_beam` (docs/scene-reference.md), alone in its scene.
enum class HubBeamMethod { AssumedModes, Fem, Rpim };
enum class HubBeamCoupling { FirstOrder, ZeroOrder };  // with / without the foreshortening w_c (Eq. 7)
struct HubBeamDesc {
  bool present = false;
  // beam (SI): length, Young's modulus, area, second moment of area, density
  double length = 0.0, E = 0.0, A = 0.0, I = 0.0, rho = 0.0;
  // hub: radius a; driven (angle prescribed) or free (inertia J_oh about the axis, applied torque)
  double hubRadius = 0.0;
  bool driven = true;
  TimeFunction angle;         // driven: theta(t)
  double hubInertia = 0.0;    // free [kg m^2]
  TimeFunction torque;        // free: tau(t) [N m] (default zero)
  double initialRate = 0.0;   // free: theta'(0) [rad/s]
  HubBeamCoupling coupling = HubBeamCoupling::FirstOrder;
  HubBeamMethod method = HubBeamMethod::Fem;
  int elements = 10;                      // fem: elements (linear axial, Hermite cubic bending)
  int axialModes = 3, bendingModes = 3;   // modes: clamped-free axial and bending modes
  int nodes = 11;                         // rpim: field nodes, evenly spaced
  double alphaC = 3.0, q = 1.03;          // rpim: multiquadric (r^2 + (alpha_c d_c)^2)^q, Eq. 14
  double alphaS = 2.5;                    // rpim: support size d_s = alpha_s d_c, Eq. 21
  int gaussPoints = 4;                    // rpim: Gauss points per background cell, Eq. 52
  bool cellSupport = true;                // rpim: one support per background cell (false: per point, seed 001)
  SourceMark mark;
};

// A pulley (issue 34): a rigid circle of `radius` about a fixed `center`. Driven (no inertia): it
// turns at speed(t) [rad/s, counterclockwise; zero: a fixed drum] and has no DOFs. Free (inertia
// J > 0; dynamics): its angle is an unknown, speed is its initial speed, and it feels the belts'
// torque, torque(t) [N m, counterclockwise] and a rotational damping -damping * omega.
// A tensioner: a free pulley whose centre also slides along `direction` from `center` (slide
// displacement x, an unknown), on a spring-damper with a preload: m x'' = F(t) - k x - c x' + the
// belts' force along the slide.
struct SlideDesc {
  SourceMark mark;
  Vec3 direction{};        // unit vector in the xy plane
  double mass = 0.0;       // m > 0 [kg]: the pulley and the slide's moving parts
  double stiffness = 0.0;  // k [N/m]
  double damping = 0.0;    // c [N s/m]
  TimeFunction preload;    // F(t) [N] along direction (pushes the pulley into the belt when positive)
};
struct PulleyDesc {
  std::string name;
  SourceMark mark;
  Vec3 center{};
  double radius = 0.0;
  TimeFunction speed;
  double inertia = 0.0;  // > 0: free to turn [kg m^2]
  double damping = 0.0;  // [N m s/rad]
  TimeFunction torque;   // [N m]
  bool hasSlide = false; // a tensioner (free pulleys only)
  SlideDesc slide;
  bool free() const { return inertia > 0.0; }
};

// Distributed contact between one body and pulleys (contact/PulleyContact.hpp): the law, and the
// Gauss points per element along which it is integrated.
struct ContactDesc {
  SourceMark mark;
  std::string body;
  std::vector<std::string> pulleys;  // every pulley when the scene lists none
  contact::ContactLaw law;
  int points = 4;
};

// A reel (seed 000, issue 35): a drum turning about a fixed axis that pays material of an ALE body
// out of its exit node (node 0 or the last) or takes it in. Its angle phi (starting at 0, paying out
// when it grows) moves the exit node's material coordinate by radius * phi, the body's other nodes
// staying equally spaced in material (Eq. 51); the far end's material is held. Driven (speed
// control): phi(t) = rotation(t) - rotation(0). Free (torque control): its angle is an unknown,
// starting at rest, J(phi) phi'' = torque(t) - damping phi' + what the body exerts, with the inertia of the core plus
// the material wound on it, J = inertia + rho A radius^2 content(phi), content(phi) = content -
// radius phi [m] (material leaves at the drum's surface speed: no thrust, d(J w)/dt = J w' + J' w
// with the outflow carrying J' w).
struct ReelDesc {
  std::string name;
  SourceMark mark;
  std::string body;
  long node = 0;          // the exit: 0 or the last node (-1 in the scene)
  double radius = 0.0;    // [m]
  double inertia = 0.0;   // the core's [kg m^2]
  double content = 0.0;   // material on the reel at t = 0 [m] (unstretched length)
  bool driven = false;
  TimeFunction rotation;  // driven: its angle [rad]
  TimeFunction torque;    // free: the torque that turns it to pay out [N m]
  double damping = 0.0;   // free: [N m s/rad]
};

struct SceneDescription {
  std::string file;  // path of the scene file
  std::vector<std::string> inputFiles;  // the other files it reads (polyline CSV), as opened
  Analysis analysis = Analysis::Static;
  SourceMark analysisMark;  // where `analysis` is given
  int dimension = 3;
  std::vector<BodyDesc> bodies;
  std::vector<SupportDesc> supports;
  std::vector<ProbeDesc> probes;
  std::vector<JunctionDesc> junctions;
  std::vector<RigidBodyDesc> rigidBodies;
  std::vector<JointDesc> joints;
  std::vector<PulleyDesc> pulleys;
  std::vector<ContactDesc> contacts;
  std::vector<ReelDesc> reels;
  LoadsDesc loads;
  StaticDesc statics;
  ModesDesc modes;
  RotationDesc rotation;
  SweepDesc sweep;
  DynamicsDesc dynamics;
  DiscretizationDesc discretization;
  OutputDesc output;
  HubBeamDesc hubBeam;
};

}  // namespace strand::model
