#include "strand/solvers/ModalSolver.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include "strand/solvers/StaticSolver.hpp"

namespace strand::solvers {

namespace {

// Krylov bases keep SLEPc's default storage (BVSVEC, one contiguous block, BLAS-2 orthogonalization).
// With Debian's reference BLAS one Vec per column (BVVECS) was faster; with OpenBLAS (.ci/setup)
// BVSVEC is: 200-point sweep on 2,000 DOF, EPS 1.24 -> 1.16 s, PEP 2.61 -> 2.09 s; 20,000 DOF,
// PEP 114 -> 91 ms per point (docs/performance.md). -modal_bv_type overrides it.
constexpr int kPepMaxDofs = 5000;  // auto: TOAR up to this size, projection above (design section 4)
constexpr double kShift = 1e-8;    // eps target sigma = -kShift |K|/|M| (ModalSolver::solve)
// lambda below kRigid |K|/|M| is a rigid-body mode: a free body's come out at 1e-16..1e-22 of it
// (round-off of K x for an exact null vector), elastic modes of practical meshes far above
constexpr double kRigid = 1e-13;

// Rotate a complex vector x = xr + i xi by a phase so that its real part carries the most energy
// (a real mode shape for output and node finding).
PetscErrorCode alignPhase(Vec xr, Vec xi) {
  PetscFunctionBeginUser;
  PetscScalar rr, ii, ri;
  PetscCall(VecDot(xr, xr, &rr));
  PetscCall(VecDot(xi, xi, &ii));
  PetscCall(VecDot(xr, xi, &ri));
  const double th = 0.5 * std::atan2(2.0 * ri, rr - ii), c = std::cos(th), s = std::sin(th);
  Vec t;
  PetscCall(VecDuplicate(xr, &t));
  PetscCall(VecCopy(xr, t));
  PetscCall(VecAXPBY(xr, s, c, xi));   // xr = c xr + s xi
  PetscCall(VecAXPBY(xi, -s, c, t));   // xi = c xi - s xr
  PetscCall(VecDestroy(&t));
  PetscFunctionReturn(0);
}
// Shift-and-invert about the target with the project's direct solver; with multipliers (a clamp
// holding a skew slope's direction, r'.n = 0) K - sigma M is a saddle point: MUMPS, which pivots
// (M is zero on the multiplier rows: their eigenvalues are infinite and stay away from the target).
PetscErrorCode useShiftInvert(ST st, bool saddlePoint) {
  PetscFunctionBeginUser;
  KSP ksp;
  PetscCall(STSetType(st, STSINVERT));
  PetscCall(STGetKSP(st, &ksp));
  PetscCall(setDirectSolverDefaults(ksp, saddlePoint));
  PetscFunctionReturn(0);
}
}  // namespace

ModalOptions modalOptions(const model::ModesDesc& modes) {
  ModalOptions opt;
  opt.count = modes.count;
  opt.coriolis = modes.coriolis;
  opt.method = modes.method;
  opt.projectionModes = modes.projectionModes;
  opt.warmStart = modes.warmStart;
  return opt;
}

ModalSolver::ModalSolver(assembly::Assembler& assembler, const ModalOptions& options)
    : _asm(assembler), _opt(options), _method(options.method) {
  if (_opt.projectionModes <= 0) _opt.projectionModes = std::max(2 * _opt.count, _opt.count + 10);
  _transport = assembler.hasVariableMass() && materialFlows(assembler);
  if (_method == model::ModalMethod::Auto) {
    if (!_opt.coriolis && !_transport) _method = model::ModalMethod::Eps;
    else _method = assembler.model().numDofs() <= kPepMaxDofs ? model::ModalMethod::Pep : model::ModalMethod::Projected;
  }
}

ModalSolver::~ModalSolver() {
  for (Vec& v : _previous) VecDestroy(&v);
  EPSDestroy(&_eps);
  PEPDestroy(&_pep);
  ISDestroy(&_free);
  for (Mat* m : {&_K, &_M, &_G, &_Kq, &_Kf, &_Mf, &_Gf}) MatDestroy(m);
}

PetscErrorCode ModalSolver::assemble(Vec X) {
  PetscFunctionBeginUser;
  const model::DofMap& dofs = _asm.dofs();
  const bool needG = _method != model::ModalMethod::Eps;
  const MatReuse reuse = _K ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX;
  if (!_K) {
    PetscCall(dofs.createMatrix(&_K, "modal_", MATAIJ));
    PetscCall(dofs.createMatrix(&_M, "modal_", MATAIJ));
    if (needG) PetscCall(dofs.createMatrix(&_G, "modal_", MATAIJ));
    PetscCall(_asm.freeDofs(&_free));
  }
  PetscCall(_asm.staticJacobian(X, 1.0, _K));  // K_T = K - Omega^2 M_P
  PetscCall(_asm.massMatrixAt(X, _M));
  if (_asm.hasVariableMass()) PetscCall(addSteadyFlowInertia(X, needG));
  else if (needG) {
    if (_opt.coriolis) PetscCall(_asm.gyroscopicMatrix(_G));
    else {
      PetscCall(MatZeroEntries(_G));
      PetscCall(MatAssemblyBegin(_G, MAT_FINAL_ASSEMBLY));
      PetscCall(MatAssemblyEnd(_G, MAT_FINAL_ASSEMBLY));
    }
  }
  PetscCall(MatCreateSubMatrix(_K, _free, _free, reuse, &_Kf));
  PetscCall(MatCreateSubMatrix(_M, _free, _free, reuse, &_Mf));
  if (needG) PetscCall(MatCreateSubMatrix(_G, _free, _free, reuse, &_Gf));
  PetscFunctionReturn(0);
}

// Kinds whose mass depends on the coordinates (the ALE kinds) carry material that may flow through
// the nodes at the prescribed rates pdot (material_motion). About that steady flow (positions at
// rest, pdot constant, so every acceleration zero) the inertial force F(q, qdot, qddot) linearizes
// to M(q) x'' + dF/dqdot x' + dF/dq x: the transport adds the gyroscopic matrix G = dF/dqdot
// (2 rho A v w_xt in Wickert & Mote's Eq. 54) and to the stiffness dF/dq (-rho A v^2 w_xx).
// The inertia of a straight span in steady flow is zero, so its static state is the steady one;
// a curved span's steady state would need F(q, qdot0, 0) in the static residual (not built).
PetscErrorCode ModalSolver::addSteadyFlowInertia(Vec X, bool needG) {
  PetscFunctionBeginUser;
  Vec V0, A0;
  Mat Kq;
  PetscCall(_asm.dofs().createVector(&V0));
  PetscCall(VecDuplicate(V0, &A0));
  PetscCall(VecSet(V0, 0.0));
  PetscCall(VecSet(A0, 0.0));
  PetscCall(_asm.prescribedMotion(0.0, nullptr, V0, nullptr));  // the material rates pdot
  if (!_Kq) PetscCall(_asm.dofs().createMatrix(&_Kq, "modal_", MATAIJ));
  Kq = _Kq;
  PetscCall(_asm.inertiaJacobian(X, V0, A0, 0.0, 0.0, Kq));
  {  // does the state carry the flow's inertia F(X, V0, 0)? zero (round-off) on a straight span;
     // on a curved one of order rho A v^2 kappa h against Kq's rho A v^2 / h times the span
    Vec F;
    PetscReal f, k;
    PetscCall(VecDuplicate(V0, &F));
    PetscCall(VecSet(F, 0.0));
    PetscCall(_asm.addInertia(X, V0, A0, F));
    PetscCall(_asm.zeroSupportedRows(F));
    PetscCall(VecNorm(F, NORM_INFINITY, &f));
    PetscCall(MatNorm(Kq, NORM_INFINITY, &k));
    _curvedFlow = f > 1e-8 * k * _asm.model().scales().length;  // a force against Kq times a length
    PetscCall(VecDestroy(&F));
  }
  PetscCall(MatAXPY(_K, 1.0, Kq, SUBSET_NONZERO_PATTERN));
  if (needG) {
    PetscCall(_asm.inertiaJacobian(X, V0, A0, 1.0, 0.0, _G));
    PetscCall(MatAXPY(_G, -1.0, Kq, SAME_NONZERO_PATTERN));
  }
  PetscCall(VecDestroy(&V0));
  PetscCall(VecDestroy(&A0));
  PetscFunctionReturn(0);
}

// The divergence of a steady flow. At A = 0 the inertial force is quadratic in the rates, so with
// every material rate scaled by s the stiffness is K(s) = K_e + s^2 K_q (K_q at the current rates,
// K_e the elastic and load part). It loses definiteness (a static buckling of the moving span:
// the lowest frequency falls to zero) at the smallest s with K_e phi = s^2 (-K_q) phi, i.e. at
// s = 1 / sqrt(nu_max) for the largest nu of (-K_q) phi = nu K_e phi (generalized, K_e
// factored). For a pinned span this is v_d^2 = (T + EI (pi/l)^2) / rho (Wickert & Mote 1990).
// That holds while the steady state does not change with the speed (a straight span). A curved
// span's steady state carries the flow's inertia: its tension rises by rho A v^2 with the speed
// (its effective tension stays the one at rest: Routh), so a hanging moving chain does not diverge
// and the frozen estimate would be wrong: NaN.
PetscErrorCode ModalSolver::divergenceFactor(double* factor) {
  PetscFunctionBeginUser;
  *factor = std::numeric_limits<double>::infinity();
  if (!_transport || !_Kq) PetscFunctionReturn(0);
  if (_curvedFlow) {
    *factor = std::numeric_limits<double>::quiet_NaN();
    PetscFunctionReturn(0);
  }
  MPI_Comm comm = _asm.dofs().comm();
  Mat B, Ke;
  PetscCall(MatCreateSubMatrix(_Kq, _free, _free, MAT_INITIAL_MATRIX, &B));
  PetscCall(MatDuplicate(_Kf, MAT_COPY_VALUES, &Ke));
  PetscCall(MatAXPY(Ke, -1.0, B, SUBSET_NONZERO_PATTERN));
  PetscCall(MatScale(B, -1.0));
  EPS eps;
  ST st;
  KSP ksp;
  PetscCall(EPSCreate(comm, &eps));
  PetscCall(EPSSetOptionsPrefix(eps, "divergence_"));
  PetscCall(EPSSetOperators(eps, B, Ke));
  PetscCall(EPSSetProblemType(eps, EPS_GNHEP));
  PetscCall(EPSSetWhichEigenpairs(eps, EPS_LARGEST_REAL));
  PetscCall(EPSSetDimensions(eps, 1, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscCall(EPSSetTolerances(eps, 1e-12, 500));
  PetscCall(EPSGetST(eps, &st));
  PetscCall(STSetType(st, STSHIFT));  // inv(K_e) (-K_q)
  PetscCall(STGetKSP(st, &ksp));
  PetscCall(setDirectSolverDefaults(ksp));
  PetscCall(EPSSetFromOptions(eps));
  PetscCall(EPSSolve(eps));
  PetscInt nconv;
  PetscCall(EPSGetConverged(eps, &nconv));
  if (nconv > 0) {
    PetscScalar nu;
    PetscCall(EPSGetEigenvalue(eps, 0, &nu, nullptr));
    if (PetscRealPart(nu) > 0.0) *factor = 1.0 / std::sqrt(PetscRealPart(nu));
  }
  PetscCall(EPSDestroy(&eps));
  PetscCall(MatDestroy(&B));
  PetscCall(MatDestroy(&Ke));
  PetscFunctionReturn(0);
}

// Whether any prescribed rate is nonzero at t = 0 in a model with ALE kinds (the material flows).
bool ModalSolver::materialFlows(assembly::Assembler& assembler) {
  Vec V0;
  PetscReal n = 0.0;
  if (assembler.dofs().createVector(&V0)) return true;
  if (!VecSet(V0, 0.0) && !assembler.prescribedMotion(0.0, nullptr, V0, nullptr)) VecNorm(V0, NORM_INFINITY, &n);
  VecDestroy(&V0);
  return n > 0.0;
}

PetscErrorCode ModalSolver::toFull(Vec freeVec, Vec* full) {
  PetscFunctionBeginUser;
  const PetscInt* idx;
  PetscInt n;
  PetscCall(ISGetLocalSize(_free, &n));
  PetscCall(ISGetIndices(_free, &idx));
  PetscCall(_asm.dofs().createVector(full));
  PetscCall(VecSet(*full, 0.0));
  const PetscScalar* a;
  PetscCall(VecGetArrayRead(freeVec, &a));
  PetscCall(VecSetValues(*full, n, idx, a, INSERT_VALUES));
  PetscCall(VecRestoreArrayRead(freeVec, &a));
  PetscCall(ISRestoreIndices(_free, &idx));
  PetscCall(VecAssemblyBegin(*full));
  PetscCall(VecAssemblyEnd(*full));
  PetscFunctionReturn(0);
}

PetscErrorCode ModalSolver::solve(Vec X, ModalResult* result) {
  PetscFunctionBeginUser;
  PetscCall(assemble(X));
  PetscInt nfree;
  PetscCall(ISGetSize(_free, &nfree));
  // A small negative target: shift-and-invert factors K - sigma M, which is definite also when K is
  // singular (a free body's rigid-body modes, a mechanism), and the modes still come in ascending
  // order (all lambda >= 0 are nearer sigma the smaller they are). sigma = -1e-8 |K|/|M|, far above
  // LU's zero-pivot test (1e-14 relative). Measured (relative residuals): free-free beam, rigid modes
  // 7e-9 and elastic 1e-11..1e-10 (with 1e-10: 4e-7 and 2e-8); the hanging cable 4e-11..3e-9
  // (target 0: 2e-10..2e-8); the cantilever unchanged (1e-12..3e-10).
  PetscReal nk, nm;
  PetscCall(MatNorm(_Kf, NORM_INFINITY, &nk));
  PetscCall(MatNorm(_Mf, NORM_INFINITY, &nm));
  _lambdaScale = nm > 0.0 ? nk / nm : nk;
  _shift = -kShift * _lambdaScale;
  // The projection on m undamped modes is no reduction once m reaches the free coordinates, and its
  // highest basis modes (the least accurate of a shift-and-invert solve about 0) spoil the reduced
  // problem: residual 1e-7 against 1e-13 for pep (issue 32 item 11). Then solve the quadratic
  // problem itself.
  model::ModalMethod method = _method;
  if (method == model::ModalMethod::Projected && _opt.projectionModes >= nfree) {
    result->note = "modes.projection_modes " + std::to_string(_opt.projectionModes) + " >= the " +
                   std::to_string(nfree) + " free coordinates: no reduction; solved with method pep (exact) instead";
    method = model::ModalMethod::Pep;
  }
  const int count = static_cast<int>(std::min<PetscInt>(_opt.count, nfree));
  if (count < _opt.count)
    result->note = "modes.count " + std::to_string(_opt.count) + " > the " + std::to_string(nfree) +
                   " free coordinates: " + std::to_string(count) + " modes";
  switch (method) {
    case model::ModalMethod::Pep: PetscCall(solvePep(result, count)); break;
    case model::ModalMethod::Projected: PetscCall(solveProjected(result)); break;
    default: PetscCall(solveEps(count, result)); break;
  }
  PetscFunctionReturn(0);
}

// Generalized Hermitian problem; eigenvectors are M-normalized (SLEPc, GHEP). Also keeps the
// free-DOF eigenvectors in _previous (warm start, projection basis).
PetscErrorCode ModalSolver::solveEps(int nev, ModalResult* result) {
  PetscFunctionBeginUser;
  MPI_Comm comm = _asm.dofs().comm();
  if (!_eps) {
    ST st;
    PetscCall(EPSCreate(comm, &_eps));
    PetscCall(EPSSetOptionsPrefix(_eps, "modal_"));
    PetscCall(EPSSetProblemType(_eps, EPS_GHEP));
    PetscCall(EPSSetDimensions(_eps, nev, PETSC_DEFAULT, PETSC_DEFAULT));
    PetscCall(EPSSetTarget(_eps, _shift));
    PetscCall(EPSSetWhichEigenpairs(_eps, EPS_TARGET_MAGNITUDE));
    PetscCall(EPSSetTolerances(_eps, 1e-12, 200));
    PetscCall(EPSGetST(_eps, &st));
    PetscCall(useShiftInvert(st, _asm.hasConstraints()));
    PetscCall(EPSSetOperators(_eps, _Kf, _Mf));
    PetscCall(EPSSetFromOptions(_eps));
  } else {
    PetscCall(EPSSetOperators(_eps, _Kf, _Mf));
    PetscCall(EPSSetDimensions(_eps, nev, PETSC_DEFAULT, PETSC_DEFAULT));
    PetscCall(EPSSetTarget(_eps, _shift));
  }
  if (_opt.warmStart && !_previous.empty())
    PetscCall(EPSSetInitialSpace(_eps, static_cast<PetscInt>(_previous.size()), _previous.data()));
  PetscCall(EPSSolve(_eps));

  PetscInt nconv;
  PetscCall(EPSGetConverged(_eps, &nconv));
  nconv = std::min<PetscInt>(nconv, nev);
  for (Vec& v : _previous) PetscCall(VecDestroy(&v));
  _previous.clear();
  Vec kx, mx;
  PetscCall(MatCreateVecs(_Kf, nullptr, &kx));
  PetscCall(VecDuplicate(kx, &mx));
  struct Pair { double lambda; Vec x; double res; };
  std::vector<Pair> pairs;
  for (PetscInt k = 0; k < nconv; ++k) {
    Vec xr;
    PetscCall(MatCreateVecs(_Kf, &xr, nullptr));
    PetscScalar lambda;
    PetscCall(EPSGetEigenpair(_eps, k, &lambda, nullptr, xr, nullptr));
    PetscReal nk, nm, nr;  // residual check, independent of SLEPc's own estimate
    PetscCall(MatMult(_Kf, xr, kx));
    PetscCall(MatMult(_Mf, xr, mx));
    PetscCall(VecNorm(kx, NORM_2, &nk));
    PetscCall(VecNorm(mx, NORM_2, &nm));
    PetscCall(VecAXPY(kx, -lambda, mx));
    PetscCall(VecNorm(kx, NORM_2, &nr));
    // relative to |K x|, or for a rigid-body mode (K x ~ 0) to the shift's scale |sigma M x|
    pairs.push_back({PetscRealPart(lambda), xr, nr / std::max(nk, std::fabs(_shift) * nm)});
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.lambda < b.lambda; });
  result->method = "eps";
  for (const Pair& p : pairs) {
    Vec full;
    PetscCall(toFull(p.x, &full));
    result->rigid.push_back(std::fabs(p.lambda) <= kRigid * _lambdaScale);
    result->omega.push_back(result->rigid.back() ? 0.0 : std::sqrt(std::max(0.0, p.lambda)));
    result->shapes.push_back(full);
    result->relativeResidual.push_back(p.res);
    _previous.push_back(p.x);
  }
  PetscCall(VecDestroy(&kx));
  PetscCall(VecDestroy(&mx));
  PetscFunctionReturn(0);
}

// Quadratic problem (lambda^2 M + lambda G + K_T) x = 0 by TOAR with shift-and-invert about 0.
PetscErrorCode ModalSolver::solvePep(ModalResult* result, int count) {
  PetscFunctionBeginUser;
  MPI_Comm comm = _asm.dofs().comm();
  Mat A[3] = {_Kf, _Gf, _Mf};
  if (!_pep) {
    ST st;
    PetscCall(PEPCreate(comm, &_pep));
    PetscCall(PEPSetOptionsPrefix(_pep, "modal_"));
    PetscCall(PEPSetType(_pep, PEPTOAR));
    // G = 0 (Coriolis off, for comparison with eps): TOAR with the gyroscopic type stalls (200
    // iterations, one pair, measured); the general type converges
    // (the transport of ALE kinds: G is skew only up to the momentum flux through free ends)
    PetscCall(PEPSetProblemType(_pep, _opt.coriolis && !_transport ? PEP_GYROSCOPIC : PEP_GENERAL));
    // ncv: SLEPc's default (2 nev) needed 67 restarts with Coriolis and did not converge without it
    // (pairs of equal magnitude) at 5 modes; 40 converges in one. For 10 modes 40 was 7 % faster
    // than 60 over a 200-point sweep, frequencies within 1.3e-8, backward errors < 1e-9 (measured,
    // docs/performance.md).
    PetscCall(PEPSetDimensions(_pep, 2 * count, std::max(40, 3 * count + 10), PETSC_DEFAULT));
    // Scalar scaling of lambda (Fan, Lin, Van Dooren 2004): ||K|| >> omega^2 ||M|| for ANCF. Without it
    // the eigenvalues were accurate to only 1.6e-9 (mode 5 of verify_rotating_modes against eps,
    // Re(lambda)/|lambda| 5e-11); with it they agree to 1e-12 (1.6e-12) at about 10 % more time.
    PetscCall(PEPSetScale(_pep, PEP_SCALE_SCALAR, PETSC_DEFAULT, nullptr, nullptr, PETSC_DEFAULT, PETSC_DEFAULT));
    PetscCall(PEPSetTarget(_pep, 0.0));
    PetscCall(PEPSetWhichEigenpairs(_pep, PEP_TARGET_MAGNITUDE));
    PetscCall(PEPSetTolerances(_pep, 1e-12, 200));
    PetscCall(PEPGetST(_pep, &st));
    PetscCall(useShiftInvert(st, _asm.hasConstraints()));
    PetscCall(PEPSetOperators(_pep, 3, A));
    PetscCall(PEPSetFromOptions(_pep));
  } else {
    PetscCall(PEPSetOperators(_pep, 3, A));
  }
  PetscCall(PEPSolve(_pep));
  PetscInt nconv;
  PetscCall(PEPGetConverged(_pep, &nconv));
  struct Pair { double omega; Vec xr, xi; double res; };
  std::vector<Pair> pairs;
  double maxRe = 0.0;
  for (PetscInt k = 0; k < nconv; ++k) {
    Vec xr, xi;
    PetscCall(MatCreateVecs(_Kf, &xr, nullptr));
    PetscCall(VecDuplicate(xr, &xi));
    PetscScalar kr, ki;
    PetscCall(PEPGetEigenpair(_pep, k, &kr, &ki, xr, xi));
    const double mag = std::hypot(kr, ki);
    if (mag > 0.0) maxRe = std::max(maxRe, std::fabs(kr) / mag);
    if (ki <= 0.0) {  // keep one of each conjugate pair, lambda = i omega
      PetscCall(VecDestroy(&xr));
      PetscCall(VecDestroy(&xi));
      continue;
    }
    PetscReal err;
    PetscCall(PEPComputeError(_pep, k, PEP_ERROR_BACKWARD, &err));
    PetscCall(alignPhase(xr, xi));
    pairs.push_back({ki, xr, xi, err});
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.omega < b.omega; });
  if (static_cast<int>(pairs.size()) > count) {
    for (size_t k = count; k < pairs.size(); ++k) {
      PetscCall(VecDestroy(&pairs[k].xr));
      PetscCall(VecDestroy(&pairs[k].xi));
    }
    pairs.resize(count);
  }
  result->method = "pep";
  result->maxRealPart = maxRe;
  for (Pair& p : pairs) {
    Vec fr, fi;
    PetscCall(toFull(p.xr, &fr));
    PetscCall(toFull(p.xi, &fi));
    result->omega.push_back(p.omega);
    result->rigid.push_back(false);
    result->shapes.push_back(fr);
    result->shapesImag.push_back(fi);
    result->relativeResidual.push_back(p.res);
    PetscCall(VecDestroy(&p.xr));
    PetscCall(VecDestroy(&p.xi));
  }
  PetscFunctionReturn(0);
}

// Projection on the first m undamped modes Phi: a dense 2m x 2m companion problem, solved
// redundantly on every rank (the reduced matrices are global dot products).
PetscErrorCode ModalSolver::solveProjected(ModalResult* result) {
  PetscFunctionBeginUser;
  ModalResult basis;
  PetscCall(solveEps(_opt.projectionModes, &basis));
  destroyModes(&basis);
  const int m = static_cast<int>(_previous.size());
  PetscCheck(m >= _opt.count, _asm.dofs().comm(), PETSC_ERR_NOT_CONVERGED,
             "projected modal solve: only %d of %d basis modes converged", m, _opt.projectionModes);
  Eigen::MatrixXd Kr(m, m), Mr(m, m), Gr(m, m);
  Vec t;
  PetscCall(VecDuplicate(_previous[0], &t));
  std::vector<PetscScalar> dots(m);
  for (auto [mat, red] : {std::pair<Mat, Eigen::MatrixXd*>{_Kf, &Kr}, {_Mf, &Mr}, {_Gf, &Gr}})
    for (int j = 0; j < m; ++j) {
      PetscCall(MatMult(mat, _previous[j], t));
      PetscCall(VecMDot(t, m, _previous.data(), dots.data()));
      for (int i = 0; i < m; ++i) (*red)(i, j) = PetscRealPart(dots[i]);
    }
  // companion form of lambda^2 Mr + lambda Gr + Kr: z = [y; lambda y]
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(2 * m, 2 * m);
  const Eigen::MatrixXd Minv = Mr.inverse();
  C.topRightCorner(m, m).setIdentity();
  C.bottomLeftCorner(m, m) = -Minv * Kr;
  C.bottomRightCorner(m, m) = -Minv * Gr;
  Eigen::EigenSolver<Eigen::MatrixXd> es(C);
  struct Pair { double omega; std::complex<double> lambda; Eigen::VectorXcd y; };
  std::vector<Pair> pairs;
  double maxRe = 0.0;
  for (int k = 0; k < 2 * m; ++k) {
    const std::complex<double> lam = es.eigenvalues()(k);
    if (std::abs(lam) > 0.0) maxRe = std::max(maxRe, std::fabs(lam.real()) / std::abs(lam));
    if (lam.imag() > 0.0) pairs.push_back({lam.imag(), lam, es.eigenvectors().col(k).head(m)});
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.omega < b.omega; });
  pairs.resize(std::min<size_t>(pairs.size(), _opt.count));
  result->method = "projected";
  result->maxRealPart = maxRe;
  Vec kx, mx, gx;
  PetscCall(VecDuplicate(t, &kx));
  PetscCall(VecDuplicate(t, &mx));
  PetscCall(VecDuplicate(t, &gx));
  for (const Pair& p : pairs) {
    Vec xr, xi;
    PetscCall(VecDuplicate(t, &xr));
    PetscCall(VecDuplicate(t, &xi));
    PetscCall(VecSet(xr, 0.0));
    PetscCall(VecSet(xi, 0.0));
    std::vector<PetscScalar> re(m), im(m);
    for (int i = 0; i < m; ++i) { re[i] = p.y(i).real(); im[i] = p.y(i).imag(); }
    PetscCall(VecMAXPY(xr, m, re.data(), _previous.data()));
    PetscCall(VecMAXPY(xi, m, im.data(), _previous.data()));
    PetscCall(alignPhase(xr, xi));
    // residual of the full quadratic problem for lambda = a + i b, x = xr + i xi (relative to ||K x||)
    const double a = p.lambda.real(), b = p.lambda.imag(), l2r = a * a - b * b, l2i = 2 * a * b;
    PetscReal nr2 = 0.0, nk2 = 0.0;
    for (int part = 0; part < 2; ++part) {
      Vec u = part == 0 ? xr : xi, w = part == 0 ? xi : xr;
      const double sgn = part == 0 ? -1.0 : 1.0;  // real part: ... - l2i M xi - b G xi; imag: + l2i M xr + b G xr
      PetscReal nk;
      PetscCall(MatMult(_Kf, u, kx));
      PetscCall(VecNorm(kx, NORM_2, &nk));
      nk2 += nk * nk;
      PetscCall(MatMult(_Mf, u, mx));
      PetscCall(VecAXPY(kx, l2r, mx));
      PetscCall(MatMult(_Gf, u, gx));
      PetscCall(VecAXPY(kx, a, gx));
      PetscCall(MatMult(_Mf, w, mx));
      PetscCall(VecAXPY(kx, sgn * l2i, mx));
      PetscCall(MatMult(_Gf, w, gx));
      PetscCall(VecAXPY(kx, sgn * b, gx));
      PetscReal nr;
      PetscCall(VecNorm(kx, NORM_2, &nr));
      nr2 += nr * nr;
    }
    Vec fr, fi;
    PetscCall(toFull(xr, &fr));
    PetscCall(toFull(xi, &fi));
    result->omega.push_back(p.omega);
    result->rigid.push_back(false);
    result->shapes.push_back(fr);
    result->shapesImag.push_back(fi);
    result->relativeResidual.push_back(std::sqrt(nr2 / nk2));
    PetscCall(VecDestroy(&xr));
    PetscCall(VecDestroy(&xi));
  }
  PetscCall(VecDestroy(&kx));
  PetscCall(VecDestroy(&mx));
  PetscCall(VecDestroy(&gx));
  PetscCall(VecDestroy(&t));
  PetscFunctionReturn(0);
}

PetscErrorCode solveModes(assembly::Assembler& assembler, Vec X, int nev, ModalResult* result) {
  PetscFunctionBeginUser;
  ModalOptions opt;
  opt.count = nev;
  ModalSolver solver(assembler, opt);
  PetscCall(solver.solve(X, result));
  PetscFunctionReturn(0);
}

void destroyModes(ModalResult* result) {
  for (Vec& v : result->shapes) VecDestroy(&v);
  for (Vec& v : result->shapesImag) VecDestroy(&v);
  result->shapes.clear();
  result->shapesImag.clear();
  result->omega.clear();
  result->rigid.clear();
  result->relativeResidual.clear();
}

}  // namespace strand::solvers
