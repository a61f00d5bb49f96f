// Time integration of M a + f_int(u, v) - f_ext = 0 on PETSc TS (options prefix "dyn_").
//
// The scheme is generalized-alpha for second-order systems (Chung & Hulbert, J. Appl. Mech. 60
// (1993) 371; PETSc TSALPHA2), fixed step. The residual PETSc asks for at the alpha point
// (t_n + alpha_f h, u_a, v_a, a_a) is F = M a_a + f_int(u_a, v_a) - f_ext (design section 3);
// the Newton matrix is K + shiftV D + shiftA M, assembled in one pass (Assembler::dynamicJacobian).
// Parameter choices of the same scheme (docs/user-guide.md, "Dynamics"):
//   generalized_alpha  rho_inf in [0, 1]: alpha_m = (2 - rho)/(1 + rho), alpha_f = 1/(1 + rho),
//                      gamma = 1/2 + alpha_m - alpha_f, beta = (1 + alpha_m - alpha_f)^2 / 4;
//                      rho_inf = 1 is the non-dissipative midpoint-like member;
//   newmark            average acceleration: alpha_m = alpha_f = 1, gamma = 1/2, beta = 1/4;
//   hht                Hilber-Hughes-Taylor: alpha_m = 1, alpha_f = 1 - alpha, gamma = 1/2 + alpha,
//                      beta = (1 + alpha)^2 / 4.
// Supports are eliminated (unit rows, Assembler).
// Known limitation (measured in tests/verification/test_dynamics.cpp): PETSc 3.18's TSALPHA2 takes
// the initial acceleration from two backward-Euler half steps (alpha2.c, TSAlpha_Restart), an
// O(h) error. The non-dissipative member rho_inf = 1 keeps order 2 and Newmark's exact period
// error; Newmark (alpha_f = 1), HHT and rho_inf < 1 fall to order 1 in the first-mode test (the
// first step adds 1.8 % energy at omega h = 0.16). The fix is our own generalized-alpha TS with
// the consistent start M a_0 = -R(u_0, v_0); until then prefer rho_inf = 1.
//
// Energy monitor (every step): kinetic T = v.M v / 2, strain U, potential of the constant loads
// P = -f_ext.u, work dissipated by Kelvin-Voigt damping W_d = int v.f_d dt (trapezoidal rule,
// f_d = f_int(u, v) - f_int(u, 0)); the balance E = T + U + P + W_d is constant for the exact motion.
#pragma once
#include <petscts.h>

#include <functional>
#include <string>

#include "strand/assembly/Assembler.hpp"
#include "strand/model/SceneDescription.hpp"

namespace strand::solvers {

struct DynamicsStep {
  int step = 0;      // 0: initial state
  double time = 0.0;
  int newtonIterations = 0;
  double kinetic = 0.0, strain = 0.0, potential = 0.0, dissipated = 0.0;
  double energy() const { return kinetic + strain + potential + dissipated; }
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
  // after the initial state and every accepted step. On failure (Newton diverged, NaN) *failure
  // names the scheme, the time, the step and what to try, and X, V hold the last accepted state.
  PetscErrorCode run(Vec X, Vec V, const StepCallback& onStep, std::string* failure);
  // Energies of a state (all ranks).
  PetscErrorCode energies(Vec X, Vec V, DynamicsStep* s);
  const char* schemeName() const;

private:
  static PetscErrorCode formFunction(TS, PetscReal t, Vec U, Vec V, Vec A, Vec F, void* ctx);
  static PetscErrorCode formJacobian(TS, PetscReal t, Vec U, Vec V, Vec A, PetscReal shiftV, PetscReal shiftA, Mat J,
                                     Mat P, void* ctx);
  static PetscErrorCode monitor(TS, PetscInt step, PetscReal t, Vec X, void* ctx);
  PetscErrorCode dampingPower(Vec X, Vec V, PetscReal* power);

  assembly::Assembler& _asm;
  model::DynamicsDesc _desc;
  TS _ts = nullptr;
  Mat _M = nullptr, _J = nullptr;
  Vec _fext = nullptr, _w1 = nullptr, _w2 = nullptr;
  bool _damped = false;
  const StepCallback* _onStep = nullptr;
  DynamicsStep _last;
  double _lastPower = 0.0;
  PetscReal _fnorm0 = 0.0;  // |F| at the first Newton iterate (roundoffFloorConvergence)
};

}  // namespace strand::solvers
