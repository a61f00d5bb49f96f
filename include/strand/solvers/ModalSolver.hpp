// Natural frequencies about a static (or steady rotating) state with SLEPc (options prefix "modal_").
//
// Linearized equations of motion in the (rotating) frame (design section 4; seed 003 Eq. 74):
//   M x'' + G x' + K_T x = 0,   K_T = K(u*) - Omega^2 M_P  (the Jacobian of the static residual),
// on the free DOFs (supports removed with MatCreateSubMatrix). Methods:
//   eps        generalized Hermitian K_T phi = omega^2 M phi, shift-and-invert about a small negative
//              target (G ignored): a free body's rigid-body modes come first, at 0 Hz, then the
//              elastic ones (issue 32 item 7);
//   pep        quadratic (lambda^2 M + lambda G + K_T) x = 0 with TOAR, shift-and-invert about 0;
//              lambda = +- i omega for a stable gyroscopic system;
//   projected  the same quadratic problem on the span of the first m eps modes Phi:
//              (lambda^2 Phi^T M Phi + lambda Phi^T G Phi + Phi^T K_T Phi) y = 0, solved dense
//              (design section 4: TOAR loses accuracy on fine meshes).
// Kinds whose mass depends on the coordinates (the ALE kinds) are linearized about their steady
// material flow at the prescribed rates of t = 0: M = M(q), G = dF/dqdot (the transport's
// gyroscopic terms), K_T += dF/dq (its stiffness change); with the material flowing the method is
// pep (or projected), of the general type (ModalSolver.cpp, addSteadyFlowInertia).
// One ModalSolver keeps its matrices and solver objects between calls, so a sweep reuses the
// symbolic factorization and warm-starts the eigensolver with the previous eigenvectors.
#pragma once
#include <slepceps.h>
#include <slepcpep.h>

#include <string>
#include <vector>

#include "strand/assembly/Assembler.hpp"
#include "strand/model/SceneDescription.hpp"

namespace strand::solvers {

struct ModalResult {
  std::vector<double> omega;  // angular frequencies [rad/s], ascending; 0 for rigid-body modes
  std::vector<bool> rigid;    // a rigid-body mode (lambda at round-off of |K|/|M|): free bodies, mechanisms
  std::vector<Vec> shapes;    // full-length mode shapes (zero at supports), caller destroys
  std::vector<Vec> shapesImag;  // imaginary parts (quadratic problem with Coriolis), else empty
  std::vector<double> relativeResidual;  // eps: ||K phi - omega^2 M phi|| / ||K phi||; pep: backward error
  double maxRealPart = 0.0;   // quadratic problems: max |Re lambda| / |lambda| (0 for a gyroscopic system)
  std::string method;         // "eps", "pep" or "projected"
  std::string note;           // what the solver changed from the options (method, count), or ""
};

struct ModalOptions {
  int count = 6;
  bool coriolis = false;
  model::ModalMethod method = model::ModalMethod::Auto;
  int projectionModes = 0;  // 0: max(2 count, count + 10)
  // previous eigenvectors as the initial space: off, it made EPS skip an eigenvalue (docs/architecture.md)
  bool warmStart = false;
};

// The options a scene's `modes` section asks for.
ModalOptions modalOptions(const model::ModesDesc& modes);

class ModalSolver {
public:
  ModalSolver(assembly::Assembler& assembler, const ModalOptions& options);
  ~ModalSolver();
  ModalSolver(const ModalSolver&) = delete;
  ModalSolver& operator=(const ModalSolver&) = delete;

  // Modes about state X (the Jacobian at load factor 1 and the model's current angular speed).
  PetscErrorCode solve(Vec X, ModalResult* result);
  model::ModalMethod method() const { return _method; }
  // After solve(): whether the material of ALE kinds flows (the quadratic problem of transport),
  // and the factor s on every material rate at which the steady flow diverges (the stiffness
  // K_e + s^2 K_q loses definiteness; +inf when it never does). The critical transport speed is
  // s times the current one.
  bool transport() const { return _transport; }
  // The full mass matrix of the last solve, M(X) (supported rows and columns zero).
  Mat massMatrix() const { return _M; }
  // NaN when the state carries the flow's inertia (a curved span: its tension rises by rho A v^2
  // with the speed, so the frozen-state estimate does not apply).
  PetscErrorCode divergenceFactor(double* factor);
  // Whether any prescribed rate is nonzero at t = 0 in a model with ALE kinds (the material flows;
  // the static state is then the steady flow's, StaticSolver).
  static bool materialFlows(assembly::Assembler& assembler);

private:
  PetscErrorCode assemble(Vec X);
  PetscErrorCode solveEps(int nev, ModalResult* result);
  PetscErrorCode solvePep(ModalResult* result, int count);
  PetscErrorCode solveProjected(ModalResult* result);
  PetscErrorCode toFull(Vec freeVec, Vec* full);
  PetscErrorCode addSteadyFlowInertia(Vec X, bool needG);

  assembly::Assembler& _asm;
  ModalOptions _opt;
  model::ModalMethod _method;
  bool _transport = false;  // ALE kinds with material flowing: G from the transport (quadratic problem)
  Mat _Kq = nullptr;  // the transport's stiffness dF/dq at the current material rates (ALE kinds)
  bool _curvedFlow = false;  // the steady state carries the flow's inertia (a curved span): it changes with the speed
  Mat _K = nullptr, _M = nullptr, _G = nullptr, _Kf = nullptr, _Mf = nullptr, _Gf = nullptr;
  IS _free = nullptr;
  double _shift = 0.0, _lambdaScale = 0.0;  // eps target (negative, small) and |K|/|M| of the last solve
  EPS _eps = nullptr;
  PEP _pep = nullptr;
  std::vector<Vec> _previous;  // eigenvectors of the last solve (free DOFs), for warm starts
};

// One-shot helper: eps modes about X.
PetscErrorCode solveModes(assembly::Assembler& assembler, Vec X, int nev, ModalResult* result);
void destroyModes(ModalResult* result);

}  // namespace strand::solvers
