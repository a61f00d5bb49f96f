// Time integration of the floating-frame hub-beam (HubBeam.hpp) on PETSc TS, options prefix "ffr_".
//
// The same schemes as the ANCF dynamics (solvers/Dynamics.hpp; scene key dynamics.integrator):
//  - generalized-alpha, Newmark, HHT on our TS "strand_alpha" with the I2Function F(t, q, q', q'')
//    and the exact Newton matrix dF/dq + shiftV dF/dq' + shiftA dF/dq'' (HubBeam::jacobian);
//  - BDF 1-5 (TSBDF, fixed or adaptive) on y = (q, v) with the IFunction (q' - v, F(t, q, v, v')) and
//    its exact Jacobian [sI, -I; dF/dq, dF/dv + s dF/da];
//  - RK4 (TSRK 4) and Adams-Bashforth-Moulton 4 (solvers/AdamsBashforthMoulton.hpp) on
//    y' = (v, M(q)^{-1} Q(t, q, v)), the explicit pair seed 001 section 3 compares with Newmark.
// The system is small and dense (n <= a few hundred): one copy per rank on PETSC_COMM_SELF, dense
// PETSc matrices with LU; every rank computes the same trajectory (rank 0 writes).
// Small-system path (HubBeamDense.cpp; the default for every fixed-step scheme): the same steps as
// plain loops on Eigen matrices, because PETSc's layers cost several times more per step at a few
// unknowns (docs/performance.md). The TS runs for adaptive BDF, with -ffr_dense false, or when
// PETSc options for it are given (-ffr_ts_*, -ffr_snes_*, -ffr_ksp_*, -ffr_pc_*).
//
// Monitors: the tip deformation in the floating frame, the hub's angle, rate and torque, and the
// energy balance E = T + U - W_hub, W_hub = int tau theta' dt (trapezoidal), which the exact motion
// keeps constant. A run stops cleanly (failure message with time, step and a hint) when Newton
// fails, a value is not finite, or the tip moves more than kDeformationLimit L in the floating
// frame: far outside any beam model, e.g. the zero-order model above its first bending frequency.
#pragma once
#include <petscts.h>

#include <functional>
#include <string>

#include "strand/ffr/HubBeam.hpp"
#include "strand/solvers/GeneralizedAlpha.hpp"

namespace strand::ffr {

struct HubBeamStep {
  int step = 0;
  double time = 0.0;
  int newtonIterations = 0;  // of the step that ended here
  int rejectedSteps = 0;     // since the start (adaptive BDF)
  HubBeam::Observation obs;
  double hubWork = 0.0;      // W_hub
  double energy() const { return obs.kinetic + obs.strain - hubWork; }
};

class HubBeamDynamics {
public:
  static constexpr double kDeformationLimit = 10.0;
  using StepCallback = std::function<void(const HubBeamStep&, const Eigen::VectorXd& q, const Eigen::VectorXd& v)>;

  HubBeamDynamics(const HubBeam& model, const model::DynamicsDesc& desc);
  ~HubBeamDynamics();
  HubBeamDynamics(const HubBeamDynamics&) = delete;
  HubBeamDynamics& operator=(const HubBeamDynamics&) = delete;

  PetscErrorCode setFromOptions();
  // Integrates from rest in the frame (d = 0, d' = 0; a free hub at theta = 0 with its initial
  // rate) to t_end. onStep runs after the initial state and every accepted step. On failure,
  // *failure says why, when and what to try; the run returns 0 (no PETSc error).
  PetscErrorCode run(const StepCallback& onStep, std::string* failure);
  // A check run after every step; true on any rank ends the run after that step (no failure;
  // stoppedByRequest() is then true): a stop signal of a batch job.
  void setStopCheck(std::function<bool()> check) { _stopCheck = std::move(check); }
  bool stoppedByRequest() const { return _stopped; }
  const std::string& schemeName() const { return _schemeName; }
  // The post-step check (public for the TS callback): stops the run on a non-finite state or a tip
  // beyond kDeformationLimit L.
  PetscErrorCode checkState(TS ts);

private:
  static PetscErrorCode i2Function(TS, PetscReal t, Vec U, Vec V, Vec A, Vec F, void* ctx);
  static PetscErrorCode i2Jacobian(TS, PetscReal t, Vec U, Vec V, Vec A, PetscReal sV, PetscReal sA, Mat J, Mat P,
                                   void* ctx);
  static PetscErrorCode iFunction(TS, PetscReal t, Vec Y, Vec Ydot, Vec F, void* ctx);
  static PetscErrorCode iJacobian(TS, PetscReal t, Vec Y, Vec Ydot, PetscReal s, Mat J, Mat P, void* ctx);
  static PetscErrorCode rhsFunction(TS, PetscReal t, Vec Y, Vec F, void* ctx);
  static PetscErrorCode monitor(TS, PetscInt step, PetscReal t, Vec X, void* ctx);
  PetscErrorCode stateOf(Vec X, Eigen::VectorXd& q, Eigen::VectorXd& v);
  PetscErrorCode runDense();
  PetscErrorCode runDenseAlpha();
  PetscErrorCode runDenseBdf();
  PetscErrorCode runDenseExplicit();
  double newtonTolerance() const;  // |F| of a displacement error of 1e-13 L
  Eigen::VectorXd initialRate() const;  // v(0): zero, or the free hub's initial rate
  std::string newtonFailure(double t, int step, int its, double norm) const;
  // the step's outputs and the callback; the acceleration is computed unless `known`
  void record(int step, double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, int newton, int rejected,
              const Eigen::VectorXd* known = nullptr);
  // why the run stops at this state (finite: q and v are; o: its observation), or empty
  std::string divergence(double t, int step, bool finite, const HubBeam::Observation& o) const;
  void acceleration(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, Eigen::VectorXd& a) const;

  const HubBeam& _model;
  model::DynamicsDesc _desc;
  std::string _schemeName;
  bool _firstOrder = false, _explicit = false, _dense = false;
  solvers::AlphaParams _params{0.0, 0.0, 0.5, 0.25};
  int _n = 0;  // unknowns q
  TS _ts = nullptr;
  Mat _J = nullptr;
  Vec _X = nullptr, _V = nullptr, _Y = nullptr;
  Eigen::LLT<Eigen::MatrixXd> _massFactor;  // driven hub: the constant mass
  const StepCallback* _onStep = nullptr;
  HubBeamStep _last;
  double _lastPower = 0.0;
  bool _haveLast = false;
  int _lastIterations = 0;
  std::string _stop;  // why the monitor stopped the run
  std::function<bool()> _stopCheck;
  bool _stopped = false;
  bool stopRequested();  // _stopCheck agreed over the ranks (every rank integrates the same system)
};

}  // namespace strand::ffr
