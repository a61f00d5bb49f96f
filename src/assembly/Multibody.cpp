#include "Multibody.hpp"

#include <algorithm>
#include <cmath>

namespace strand::assembly {

using elements::Constraint;
using elements::ConstraintEq;
using elements::kMaxJointCoordinates;

namespace {
constexpr int kMaxBlocks = 10;  // a 3D clamp to a rigid body: two multiplier, four body and two cable blocks

int equations(const ConstraintEq& e, int D) {
  return D == 2 ? Constraint<2>::equations(e) : Constraint<3>::equations(e);
}

void addHessian(const ConstraintEq& e, const double* q, int n, const double* w, double s, double* H, int D) {
  if (D == 2) Constraint<2>::addHessian(e, q, n, w, s, H);
  else Constraint<3>::addHessian(e, q, n, w, s, H);
}
}  // namespace

Multibody::Multibody(const model::Model& model, const model::DofMap& dofs, const std::vector<double>& q0Local)
    : _model(model), _dofs(dofs), _q0(q0Local) {}

Multibody::JointState Multibody::state(int k, const double* x) const {
  const int D = _model.dim();
  JointState s;
  s.joint = &_model.joints()[_model.couplings()[_dofs.localCouplings()[k]].joint];
  s.lb = &_dofs.couplingLocalBlocks()[_dofs.couplingOffset()[k]];
  s.qb = s.lb + s.joint->lambdaBlocks.size();
  s.n = static_cast<int>(s.joint->blocks.size()) * D;
  for (int c = 0; c < s.n; ++c) s.q[c] = _q0[s.qb[c / D] * D + c % D] + x[s.qb[c / D] * D + c % D];
  int row = 0;
  for (const ConstraintEq& e : s.joint->equations) {
    if (D == 2) Constraint<2>::evaluate(e, s.q, s.n, s.g + row, s.G + row * s.n);
    else Constraint<3>::evaluate(e, s.q, s.n, s.g + row, s.G + row * s.n);
    row += equations(e, D);
  }
  for (int r = 0; r < s.joint->count; ++r) s.mu[r] = x[s.lb[r / D] * D + r % D];
  return s;
}

bool Multibody::isJoint(int k) const { return _model.couplings()[_dofs.localCouplings()[k]].joint >= 0; }
bool Multibody::isRigidBody(int k) const { return _model.couplings()[_dofs.localCouplings()[k]].rigidBody >= 0; }

void Multibody::residual(const double* x, double scale, double loadFactor, double* r) const {
  const int D = _model.dim();
  for (int k = 0; k < static_cast<int>(_dofs.localCouplings().size()); ++k) {
    if (!isJoint(k)) {  // a rigid body: only a 3D torque adds to the residual here (contact: PulleyContacts)
      if (D == 2 || loadFactor == 0.0 || !isRigidBody(k)) continue;
      const double* t = _model.rigidBodies()[_model.couplings()[_dofs.localCouplings()[k]].rigidBody].torque.data();
      const PetscInt* lb = &_dofs.couplingLocalBlocks()[_dofs.couplingOffset()[k]];
      for (int a = 1; a < 4; ++a) {  // r -= loadFactor 1/2 tau x a_k
        double e[3];
        for (int i = 0; i < 3; ++i) e[i] = _q0[lb[a] * 3 + i] + x[lb[a] * 3 + i];
        double* ra = &r[lb[a] * 3];
        ra[0] -= 0.5 * loadFactor * (t[1] * e[2] - t[2] * e[1]);
        ra[1] -= 0.5 * loadFactor * (t[2] * e[0] - t[0] * e[2]);
        ra[2] -= 0.5 * loadFactor * (t[0] * e[1] - t[1] * e[0]);
      }
      continue;
    }
    const JointState s = state(k, x);
    for (int e = 0; e < s.joint->count; ++e) {
      r[s.lb[e / D] * D + e % D] += scale * s.g[e];
      for (int c = 0; c < s.n; ++c) r[s.qb[c / D] * D + c % D] += scale * s.G[e * s.n + c] * s.mu[e];
    }
  }
}

PetscErrorCode Multibody::jacobian(const double* x, double scale, double shiftA, double loadFactor, Mat J,
                                   const std::vector<char>& fixed, bool gradientsOnly) const {
  PetscFunctionBeginUser;
  const int D = _model.dim();
  const auto& local = _dofs.localCouplings();
  double Ke[(kMaxBlocks * 3) * (kMaxBlocks * 3)];
  for (int k = 0; k < static_cast<int>(local.size()); ++k) {
    const model::Coupling& c = _model.couplings()[local[k]];
    if (c.rigidBody < 0 && c.joint < 0) continue;  // a belt element's contact with a pulley: PulleyContacts
    const PetscInt off = _dofs.couplingOffset()[k];
    const PetscInt* lb = &_dofs.couplingLocalBlocks()[off];
    const int nb = static_cast<int>(c.blocks.size()), N = nb * D;
    std::fill(Ke, Ke + N * N, 0.0);
    if (c.rigidBody >= 0) {
      rigidMass(c.rigidBody, shiftA, Ke);
      if (!gradientsOnly) torqueStiffness(c.rigidBody, loadFactor, Ke);
    } else {
      const JointState s = state(k, x);
      const int L = N - s.n;  // multiplier coordinates come first
      double H[kMaxJointCoordinates * kMaxJointCoordinates] = {};
      if (!gradientsOnly) {
        int row = 0;
        for (const ConstraintEq& e : s.joint->equations) {
          addHessian(e, s.q, s.n, s.mu + row, scale, H, D);
          row += equations(e, D);
        }
      }
      for (int r = 0; r < s.n; ++r)
        for (int col = 0; col < s.n; ++col) Ke[(L + r) * N + L + col] = H[r * s.n + col];
      for (int e = 0; e < s.joint->count; ++e)
        for (int col = 0; col < s.n; ++col) Ke[e * N + L + col] = Ke[(L + col) * N + e] = scale * s.G[e * s.n + col];
    }
    for (int a = 0; a < nb; ++a)  // supports and unused slots: their unit diagonal is added elsewhere
      for (int i = 0; i < D; ++i)
        if (fixed[lb[a] * D + i])
          for (int m = 0; m < N; ++m) Ke[(a * D + i) * N + m] = Ke[m * N + a * D + i] = 0.0;
    const PetscInt* gb = &_dofs.couplingGlobalBlocks()[off];
    PetscCall(MatSetValuesBlocked(J, nb, gb, nb, gb, Ke, ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

// 2D: s diag(m, m, J, 0) over the blocks (x, y), (phi, unused), 4 x 4. 3D: s diag(m I, Jbar (x) I)
// over r, a_1, a_2, a_3, 12 x 12. Row-major.
void Multibody::rigidMass(int body, double s, double* Ke) const {
  const model::RigidBody& rb = _model.rigidBodies()[body];
  if (_model.dim() == 2) {
    Ke[0 * 4 + 0] += s * rb.mass;
    Ke[1 * 4 + 1] += s * rb.mass;
    Ke[2 * 4 + 2] += s * rb.inertia;
    return;
  }
  for (int i = 0; i < 3; ++i) Ke[i * 12 + i] += s * rb.mass;
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l)
      for (int i = 0; i < 3; ++i) Ke[(3 + 3 * k + i) * 12 + 3 + 3 * l + i] += s * rb.frameInertia[3 * k + l];
}

// d(-1/2 tau x a_k)/da_k = -1/2 [tau]x on each axis block.
void Multibody::torqueStiffness(int body, double loadFactor, double* Ke) const {
  const model::RigidBody& rb = _model.rigidBodies()[body];
  if (_model.dim() == 2 || loadFactor == 0.0) return;
  const double* t = rb.torque.data();
  const double W[9] = {0, -t[2], t[1], t[2], 0, -t[0], -t[1], t[0], 0};
  for (int k = 1; k < 4; ++k)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) Ke[(3 * k + i) * 12 + 3 * k + j] -= 0.5 * loadFactor * W[i * 3 + j];
}

PetscErrorCode Multibody::mass(Mat M, const std::vector<char>& fixed) const {
  PetscFunctionBeginUser;
  const auto& local = _dofs.localCouplings();
  for (int k = 0; k < static_cast<int>(local.size()); ++k) {
    const model::Coupling& c = _model.couplings()[local[k]];
    if (c.rigidBody < 0) continue;
    const PetscInt* lb = &_dofs.couplingLocalBlocks()[_dofs.couplingOffset()[k]];
    const PetscInt* gb = &_dofs.couplingGlobalBlocks()[_dofs.couplingOffset()[k]];
    const int D = _model.dim(), nb = static_cast<int>(c.blocks.size()), N = nb * D;
    double Ke[12 * 12] = {};
    rigidMass(c.rigidBody, 1.0, Ke);
    for (int i = 0; i < N; ++i)
      if (fixed[lb[i / D] * D + i % D])
        for (int m = 0; m < N; ++m) Ke[i * N + m] = Ke[m * N + i] = 0.0;
    PetscCall(MatSetValuesBlocked(M, nb, gb, nb, gb, Ke, ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

void Multibody::velocityTerm(const double* x, const double* v, double* r) const {
  const int D = _model.dim();
  for (int k = 0; k < static_cast<int>(_dofs.localCouplings().size()); ++k) {
    if (!isJoint(k)) continue;
    const JointState s = state(k, x);
    double ve[kMaxJointCoordinates];
    for (int c = 0; c < s.n; ++c) ve[c] = v[s.qb[c / D] * D + c % D];
    int row = 0;
    for (const ConstraintEq& e : s.joint->equations) {
      for (int i = 0; i < equations(e, D); ++i, ++row) {  // v^T (d^2 g_row / dq^2) v, one row at a time
        double w[3] = {0.0, 0.0, 0.0}, H[kMaxJointCoordinates * kMaxJointCoordinates] = {};
        w[i] = 1.0;
        addHessian(e, s.q, s.n, w, 1.0, H, D);
        double vHv = 0.0;
        for (int a = 0; a < s.n; ++a)
          for (int b = 0; b < s.n; ++b) vHv += ve[a] * H[a * s.n + b] * ve[b];
        r[s.lb[row / D] * D + row % D] += vHv;
      }
    }
  }
}

void Multibody::gradientProduct(const double* x, const double* w, double scale, double* r) const {
  const int D = _model.dim();
  for (int k = 0; k < static_cast<int>(_dofs.localCouplings().size()); ++k) {
    if (!isJoint(k)) continue;
    const JointState s = state(k, x);
    for (int e = 0; e < s.joint->count; ++e) {
      const double we = w[s.lb[e / D] * D + e % D];  // the GGL multiplier of equation e
      double gw = 0.0;
      for (int c = 0; c < s.n; ++c) {
        const PetscInt i = s.qb[c / D] * D + c % D;
        gw += s.G[e * s.n + c] * w[i];
        r[i] += scale * s.G[e * s.n + c] * we;
      }
      r[s.lb[e / D] * D + e % D] += scale * gw;
    }
  }
}

PetscErrorCode Multibody::addJointMatrix(int k, double* Ke, Mat J, const std::vector<char>& fixed) const {
  PetscFunctionBeginUser;
  const int D = _model.dim();
  const model::Coupling& c = _model.couplings()[_dofs.localCouplings()[k]];
  const PetscInt off = _dofs.couplingOffset()[k];
  const PetscInt* lb = &_dofs.couplingLocalBlocks()[off];
  const int nb = static_cast<int>(c.blocks.size()), N = nb * D;
  for (int a = 0; a < nb; ++a)
    for (int i = 0; i < D; ++i)
      if (fixed[lb[a] * D + i])
        for (int m = 0; m < N; ++m) Ke[(a * D + i) * N + m] = Ke[m * N + a * D + i] = 0.0;
  PetscCall(MatSetValuesBlocked(J, nb, &_dofs.couplingGlobalBlocks()[off], nb, &_dofs.couplingGlobalBlocks()[off], Ke,
                                ADD_VALUES));
  PetscFunctionReturn(0);
}

PetscErrorCode Multibody::gradientProductJacobian(const double* x, const double* w, double scale, Mat C, Mat dC,
                                                  const std::vector<char>& fixed) const {
  PetscFunctionBeginUser;
  const int D = _model.dim();
  double Ke[(kMaxBlocks * 3) * (kMaxBlocks * 3)];
  for (int k = 0; k < static_cast<int>(_dofs.localCouplings().size()); ++k) {
    if (!isJoint(k)) continue;
    const JointState s = state(k, x);
    const int N = static_cast<int>(_model.couplings()[_dofs.localCouplings()[k]].blocks.size()) * D;
    const int L = N - s.n;  // multiplier coordinates come first
    if (C) {
      std::fill(Ke, Ke + N * N, 0.0);
      for (int e = 0; e < s.joint->count; ++e)
        for (int col = 0; col < s.n; ++col) Ke[e * N + L + col] = Ke[(L + col) * N + e] = scale * s.G[e * s.n + col];
      PetscCall(addJointMatrix(k, Ke, C, fixed));
    }
    if (!dC) continue;
    std::fill(Ke, Ke + N * N, 0.0);
    double we[JointState::kMaxEquations], wq[kMaxJointCoordinates];
    for (int e = 0; e < s.joint->count; ++e) we[e] = w[s.lb[e / D] * D + e % D];
    for (int c = 0; c < s.n; ++c) wq[c] = w[s.qb[c / D] * D + c % D];
    int row = 0;
    for (const ConstraintEq& eq : s.joint->equations) {
      for (int i = 0; i < equations(eq, D); ++i, ++row) {
        double unit[3] = {0.0, 0.0, 0.0}, H[kMaxJointCoordinates * kMaxJointCoordinates] = {};
        unit[i] = 1.0;
        addHessian(eq, s.q, s.n, unit, 1.0, H, D);  // d^2 g_row / dq^2
        for (int a = 0; a < s.n; ++a) {
          double Hw = 0.0;
          for (int b = 0; b < s.n; ++b) {
            Hw += H[a * s.n + b] * wq[b];
            Ke[(L + a) * N + L + b] += scale * we[row] * H[a * s.n + b];  // s H(w): coordinate rows
          }
          Ke[row * N + L + a] += scale * Hw;  // d(s G w)/dq: multiplier rows
        }
      }
    }
    PetscCall(addJointMatrix(k, Ke, dC, fixed));
  }
  PetscFunctionReturn(0);
}

void Multibody::violation(const double* x, const double* v, double* position, double* velocity) const {
  const int D = _model.dim();
  *position = *velocity = 0.0;
  for (int k = 0; k < static_cast<int>(_dofs.localCouplings().size()); ++k) {
    if (!isJoint(k)) continue;
    const JointState s = state(k, x);
    for (int e = 0; e < s.joint->count; ++e) {
      double gv = 0.0;
      for (int c = 0; c < s.n; ++c) gv += s.G[e * s.n + c] * v[s.qb[c / D] * D + c % D];
      *position = std::max(*position, std::fabs(s.g[e]));
      *velocity = std::max(*velocity, std::fabs(gv));
    }
  }
}

}  // namespace strand::assembly
