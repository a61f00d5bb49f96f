// Time integration of M a + f_int(u, v) - f_ext = 0 on PETSc TS (options prefix "dyn_").
//
// The scheme is generalized-alpha for second-order systems in the form of Arnold & Bruls (2007),
// fixed step, on our registered TS "strand_alpha" (GeneralizedAlpha.hpp), started from the
// consistent acceleration M a0 = f_ext - f_int(u0, v0). The residual F = M a + f_int(u, v) - f_ext
// holds at the end of each step; the Newton matrix is K + shiftV D + shiftA M, assembled in one pass
// (Assembler::dynamicJacobian). PETSc's TSALPHA2 (Chung & Hulbert at the alpha point, estimated
// start) remains selectable with -dyn_ts_type alpha2 for comparison; GeneralizedAlpha.hpp says
// why it is not the default.
// Parameter choices of the same scheme (docs/user-guide.md, "Dynamics"):
//   generalized_alpha  rho_inf in [0, 1]: alpha_m = (2 rho - 1)/(rho + 1), alpha_f = rho/(rho + 1),
//                      gamma = 1/2 + alpha_f - alpha_m, beta = (gamma + 1/2)^2 / 4;
//                      rho_inf = 1 is the non-dissipative member;
//   newmark            average acceleration: alpha_m = alpha_f = 0, gamma = 1/2, beta = 1/4;
//   hht                Hilber-Hughes-Taylor: alpha_m = 0, alpha_f = alpha, gamma = 1/2 + alpha,
//                      beta = (1 + alpha)^2 / 4.
// All are second order (tests/verification/test_dynamics.cpp).
//
// Joints (index 3, Arnold & Bruls 2007 Sec. 4): the multipliers mu = lambda / s are unknowns of
// the TS marked algebraic; their rows s g(q) hold at the end of every step, s = shiftA. The start
// is consistent: velocities projected onto G v = 0, accelerations and multipliers from the
// saddle-point system. The monitor reports max |g| and max |G v|.
//
// The first-order integrators (BDF 1-5 on strand_bdf, StrandBdf.hpp, fixed or adaptive step;
// explicit RK4 on TSRK; explicit Adams-Bashforth-Moulton 4, AdamsBashforthMoulton.hpp) work on
// y = (u, v) (StateSpace.hpp; with joints BDF on ConstrainedStateSpace.hpp); the same monitors and
// the same blow-up guard apply.
//
// Supports are eliminated: their residual rows are zero and their Jacobian rows unit, and the TS
// sets their values at the end of each step (hub supports turn, model/HubMotion.hpp; the others
// stay at zero). The mass matrix keeps the columns of supported DOFs, so a turning hub's
// acceleration loads the body.
//
// Energy monitor (every step): kinetic T = v.M v / 2, strain U, potential of the constant loads
// P = -f_ext.u, work dissipated by Kelvin-Voigt damping W_d = int v.f_d dt (f_d = f_int(u, v) -
// f_int(u, 0)) and work done by the supports on the body W_s = int v.f_s dt (f_s = M a + f_int -
// f_ext on supported rows; non-zero only for moving supports) and the work of time-dependent loads
// W_t = int v.f(t) dt, all by the trapezoidal rule. Belt-pulley contact: the normal penalty's
// potential C is stored energy, the power of its other forces (friction, normal damping, driven
// pulleys) is in W_t (Assembler::contactEnergy). The balance E = T + U + C + P + W_d - W_s - W_t is
// constant for the exact motion.
#pragma once
#include <petscts.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "strand/assembly/Assembler.hpp"
#include "strand/model/SceneDescription.hpp"
#include "strand/solvers/ConstrainedStateSpace.hpp"
#include "strand/solvers/GeneralizedAlpha.hpp"
#include "strand/solvers/NewtonMatrixReuse.hpp"
#include "strand/solvers/StateSpace.hpp"
#include "strand/solvers/StaticSolver.hpp"

namespace strand::solvers {

struct DynamicsStep {
  int step = 0;      // 0: initial state
  double time = 0.0;
  int newtonIterations = 0;
  int rejectedSteps = 0;  // since the start (adaptive steps: error test or Newton failure)
  double timeStep = 0.0;  // of the step that ended here
  bool suspect = false;   // the blow-up guard has seen energy created here (or a non-finite value)
  double kinetic = 0.0, strain = 0.0, potential = 0.0, dissipated = 0.0, supportWork = 0.0;
  double contact = 0.0;   // belt-pulley contact: the normal penalty's stored energy
  double loadWork = 0.0;  // work of the time-dependent and configuration-dependent loads and the contact's other forces (trapezoidal)
  double constraintPosition = 0.0, constraintVelocity = 0.0;  // max |g(q)|, max |G v| over the joints
  double energy() const { return kinetic + strain + contact + potential + dissipated - supportWork - loadWork; }
};

// What a checkpoint holds besides X and V, to continue a run exactly (Dynamics::saveState,
// resumeFrom): the time, the step, the energy monitor's accumulators, and generalized-alpha's
// accelerations A and a, ABM4's rate history, or BDF's state history and next step (PETSc's own
// TSBDF, chosen by -dyn_ts_type bdf, restarts its start-up instead: not exact).
struct ResumeState {
  double time = 0.0;
  int step = 0;
  DynamicsStep last;
  double e0 = 0.0, energyScale = 0.0, lastDampingPower = 0.0, lastSupportPower = 0.0, lastLoadPower = 0.0;
  Vec A = nullptr, a = nullptr;  // generalized-alpha only; saveState lends them, resumeFrom copies them
  int historyCount = 0;          // ABM4: f_n, f_{n-1}, ... in the first-order layout (state space)
  double historyStep = 0.0;
  std::vector<Vec> history = std::vector<Vec>(8, nullptr);  // ABM4's rates or BDF's states (owned by whoever filled them)
  std::vector<double> historyTimes;  // fixed-step BDF: the times of its states (most recent first)
  int bdfOrder = 1, bdfSteps = 0;    // fixed-step BDF: current order, steps since its start
  int newtonStart = -1;  // generalized-alpha: the Newton start in use (GeneralizedAlphaGetPredictor); -1: none
  int stepCuts = 0;          // generalized-alpha: step cuts in force (GeneralizedAlphaGetStepCuts) ...
  double nominalStep = 0.0;  // ... and the step they cut
  std::vector<double> contactHistory;  // the bristle law's deflections (Assembler::contactHistory)
  double contactTime = 0.0;            // ... and the time they belong to
};

class Dynamics {
public:
  using StepCallback = std::function<PetscErrorCode(const DynamicsStep&, Vec X, Vec V)>;

  Dynamics(assembly::Assembler& assembler, const model::DynamicsDesc& desc);
  ~Dynamics();
  Dynamics(const Dynamics&) = delete;
  Dynamics& operator=(const Dynamics&) = delete;

  // Applies -dyn_ts_*, -dyn_snes_*, -dyn_ksp_*, -dyn_pc_* options.
  PetscErrorCode setFromOptions();
  // Integrates from (X, V) at t = 0 to t_end; X, V then hold the last accepted state. onStep runs
  // after the initial state and every accepted step. On failure (Newton diverged, NaN, or an
  // energy created beyond half the energy the system has held: a blown-up solution) *failure
  // names the scheme, the time, the step and what to try, and X, V hold the last accepted state.
  PetscErrorCode run(Vec X, Vec V, const StepCallback& onStep, std::string* failure);
  // Energies of a state (all ranks). With configuration-dependent loads (the ALE kinds') their
  // power v . Q(X) comes out of the kinetic energy's element pass into *configurationPower, for
  // powers() at the same state; otherwise it is left empty.
  PetscErrorCode energies(Vec X, Vec V, DynamicsStep* s, std::optional<PetscReal>* configurationPower);
  PetscErrorCode dynamicResidual(Vec X, Vec V, Vec A, PetscReal t, Vec F, assembly::SupportRows rows);
  // The force the supports exert on the body, f_s = M a + f_int - f_ext on supported rows (zero
  // elsewhere), at the current state of the integration (inside a step callback, or after run()).
  PetscErrorCode supportForce(Vec F);
  const char* schemeName() const { return _schemeName.c_str(); }
  // Newton matrices assembled since construction (generalized-alpha family: NewtonMatrixReuse
  // keeps one across iterations and steps while it contracts).
  long newtonMatrices() const { return _reuse.rebuilds(); }
  // The generalized-alpha family's Newton start in use ("acceleration", "velocity" or
  // "displacement"; GeneralizedAlphaGetPredictor), "" for the other schemes and before run().
  std::string newtonStart() const;
  // Rebuild the Newton matrix when the corrections shrink by less than this factor per iteration
  // (default 0.1; -dyn_newton_matrix_contraction); 0: full Newton, a new matrix at every iterate.
  void setNewtonMatrixContraction(double c) { _reuse.setContraction(c); }
  // The scheme with its parameters and the TS type that runs it (checkpoints must match it).
  std::string signature() const;

  // Checkpoints. saveState: the state at the current TS time (inside a step callback, or after
  // run()); A and a are borrowed, valid until the next step. resumeFrom: the next run() continues
  // from that state (X, V passed to run() hold its coordinates and velocities) instead of the
  // consistent start. exactRestart: whether that continues the trajectory to solver tolerance
  // (generalized-alpha family, RK4 and ABM4; BDF restarts its multistep start-up).
  PetscErrorCode saveState(ResumeState* s);
  PetscErrorCode resumeFrom(const ResumeState& s);
  bool exactRestart() const;
  // A check run after every step on every rank; when it returns true on any rank, the run stops
  // after that step (no failure; stoppedByRequest() is then true). E.g. a wall-time limit.
  void setStopCheck(std::function<bool()> check) { _stopCheck = std::move(check); }
  bool stoppedByRequest() const { return _stopped; }
  // The first-order state layout (for checkpoints of ABM4's history); null for generalized-alpha.
  StateSpace* stateSpace() { return _space.get(); }

private:
  static PetscErrorCode formFunction(TS, PetscReal t, Vec U, Vec V, Vec A, Vec F, void* ctx);
  static PetscErrorCode formJacobian(TS, PetscReal t, Vec U, Vec V, Vec A, PetscReal shiftV, PetscReal shiftA, Mat J,
                                     Mat P, void* ctx);
  static PetscErrorCode retryNewton(void* ctx, PetscBool* again);
  static PetscErrorCode settleContact(void* ctx, PetscReal t, Vec X, Vec V, PetscBool release, PetscInt* changed);
  static PetscErrorCode monitor(TS, PetscInt step, PetscReal t, Vec X, void* ctx);
  static PetscErrorCode postStep(TS ts);
  static PetscErrorCode prescribe(PetscReal t, Vec X, Vec V, Vec A, void* ctx);
  PetscErrorCode applyScheme();
  PetscErrorCode consistentAcceleration(PetscReal t, Vec X, Vec V, Vec A, bool project);
  PetscErrorCode perturbedStart(Vec X, Vec V, Vec a);  // generalized-alpha with joints: a0, v0
  PetscErrorCode subtractPrescribedRate(Vec X, Vec w, Vec rhs, Vec scratch);
  PetscErrorCode createMassSolver(Vec X, KSP* ksp);
  PetscErrorCode currentAcceleration(Vec* A);
  // configurationPower: v . Q(X) from energies() at this state, or empty (then assembled here)
  PetscErrorCode powers(PetscReal t, Vec X, Vec V, const std::optional<PetscReal>& configurationPower,
                        PetscReal* damping, PetscReal* support, PetscReal* load);
  PetscErrorCode supportForceAt(PetscReal t, Vec X, Vec V, Vec F);  // first-order form
  PetscErrorCode monitorState(PetscInt step, PetscReal t, Vec X, Vec V);
  PetscErrorCode highestFrequency(Vec X, PetscReal* omega);
  std::string failureHint(const DynamicsStep& at) const;

  assembly::Assembler& _asm;
  model::DynamicsDesc _desc;
  TS _ts = nullptr;
  // mass with supported columns kept, for products only (IsotropicMass.hpp); Newton matrix
  Mat _M = nullptr, _J = nullptr;
  Vec _fext = nullptr, _w1 = nullptr, _w2 = nullptr;
  Vec _supported = nullptr;  // 1 on supported rows, 0 elsewhere
  Vec _reaction = nullptr;   // support force of the last residual evaluation (moving supports)
  bool _reactionValid = false;
  Vec _a0 = nullptr;         // initial acceleration (kept for TS types without an acceleration state)
  Vec _multipliers = nullptr, _notMultiplier = nullptr;  // 1 / 0 on multiplier DOFs, and 1 - that
  bool _damped = false, _moving = false, _constrained = false;
  bool _variableMass = false;  // kinds with M(q): their inertia in the residual (Assembler::addInertia)
  bool _configurationLoads = false;  // loads Q(q) (the ALE kinds'): counted by their work, not in _fext
  bool _firstOrder = false, _explicit = false;  // StateSpace form; RK4 / ABM4
  bool _ownAlpha = false;                        // run() integrates with our strand_alpha TS
  std::string _schemeName;
  KSP _massSolver = nullptr;              // first-order form: the masked mass, factored once
  std::unique_ptr<StateSpace> _space;
  std::unique_ptr<ConstrainedStateSpace> _constrainedSpace;  // BDF with joints
  Vec _Y = nullptr, _acc = nullptr;       // first-order state (u, v); scratch acceleration
  Vec _ydot = nullptr;                    // BDF with joints: the step's derivative (u', v')
  AlphaParams _params{0.0, 0.0, 0.5, 0.25};
  const StepCallback* _onStep = nullptr;
  DynamicsStep _last;
  double _lastDampingPower = 0.0, _lastSupportPower = 0.0, _lastLoadPower = 0.0;
  NewtonFloor _floor;
  NewtonMatrixReuse _reuse;
  std::function<bool()> _stopCheck;
  bool _stopped = false;
  double _collapsedStep = 0.0;  // adaptive BDF: the step taken at the controller's minimum (postStep)
  bool _resuming = false;
  ResumeState _resume;  // its A, a are owned copies while _resuming
  double _e0 = 0.0, _energyScale = 0.0, _blowUp = 0.0;  // blow-up guard (monitor, postStep)
  DynamicsStep _blowUpAt;  // first step of the streak
  int _overSteps = 0;      // consecutive steps with energy created beyond the guard's bound
  double _energyFloor = 0.0;  // below it, created energy is noise: 1e-12 (sum over cables of EA L + |f_ext| |q0|)
  static constexpr int kBlowUpSteps = 5;
};

}  // namespace strand::solvers
