#include "Multibody.hpp"

#include <algorithm>
#include <cmath>

namespace strand::assembly {

using elements::Constraint;
using elements::ConstraintEq;
using elements::ConstraintForm;

namespace {
constexpr int kMaxBlocks = 6;  // a clamp: two multiplier blocks and four coordinate blocks
}

Multibody::Multibody(const model::Model& model, const model::DofMap& dofs, const std::vector<double>& q0Local)
    : _model(model), _dofs(dofs), _q0(q0Local) {}

// q = q0 + x of the joint's coordinate blocks (after its multiplier blocks) of local coupling k.
template <int D>
void Multibody::gather(int k, const double* x, double* q) const {
  const model::Joint& j = _model.joints()[_model.couplings()[_dofs.localCouplings()[k]].joint];
  const PetscInt* lb = &_dofs.couplingLocalBlocks()[_dofs.couplingOffset()[k] + j.lambdaBlocks.size()];
  for (size_t b = 0; b < j.blocks.size(); ++b)
    for (int i = 0; i < D; ++i) q[b * D + i] = _q0[lb[b] * D + i] + x[lb[b] * D + i];
}

template <int D>
void Multibody::evaluate(int joint, const double* q, int n, double* g, double* G) const {
  int row = 0;
  for (const ConstraintEq& e : _model.joints()[joint].equations) {
    Constraint<D>::evaluate(e, q, n, g + row, G + row * n);
    row += Constraint<D>::equations(e);
  }
}

namespace {
// Multiplier values mu of local coupling k (the first `count` entries of its multiplier blocks).
void gatherMu(const PetscInt* lb, int count, int D, const double* x, double* mu) {
  for (int r = 0; r < count; ++r) mu[r] = x[lb[r / D] * D + r % D];
}
}  // namespace

void Multibody::residual(const double* x, double scale, double* r) const {
  const int D = _model.dim();
  const auto& local = _dofs.localCouplings();
  for (size_t k = 0; k < local.size(); ++k) {
    const model::Coupling& c = _model.couplings()[local[k]];
    if (c.joint < 0) continue;
    const model::Joint& j = _model.joints()[c.joint];
    const PetscInt* lb = &_dofs.couplingLocalBlocks()[_dofs.couplingOffset()[k]];
    const PetscInt* qb = lb + j.lambdaBlocks.size();
    const int n = static_cast<int>(j.blocks.size()) * D;
    double q[elements::kMaxJointCoordinates], g[6], G[6 * elements::kMaxJointCoordinates], mu[6];
    if (D == 2) {
      gather<2>(static_cast<int>(k), x, q);
      evaluate<2>(c.joint, q, n, g, G);
    } else {
      gather<3>(static_cast<int>(k), x, q);
      evaluate<3>(c.joint, q, n, g, G);
    }
    gatherMu(lb, j.count, D, x, mu);
    for (int e = 0; e < j.count; ++e) {
      r[lb[e / D] * D + e % D] += scale * g[e];
      for (int col = 0; col < n; ++col) r[qb[col / D] * D + col % D] += scale * G[e * n + col] * mu[e];
    }
  }
}

PetscErrorCode Multibody::jacobian(const double* x, double scale, double shiftA, Mat J, const std::vector<char>& fixed,
                                   bool gradientsOnly) const {
  PetscFunctionBeginUser;
  const int D = _model.dim();
  const auto& local = _dofs.localCouplings();
  double Ke[(kMaxBlocks * 3) * (kMaxBlocks * 3)];
  for (size_t k = 0; k < local.size(); ++k) {
    const model::Coupling& c = _model.couplings()[local[k]];
    const PetscInt off = _dofs.couplingOffset()[k];
    const PetscInt* lb = &_dofs.couplingLocalBlocks()[off];
    const int nb = static_cast<int>(c.blocks.size()), N = nb * D;
    std::fill(Ke, Ke + N * N, 0.0);
    if (c.rigidBody >= 0) {
      const model::RigidBody& rb = _model.rigidBodies()[c.rigidBody];
      Ke[0 * N + 0] = Ke[1 * N + 1] = shiftA * rb.mass;  // blocks (x, y), (phi, unused)
      Ke[2 * N + 2] = shiftA * rb.inertia;
    } else {
      const model::Joint& j = _model.joints()[c.joint];
      const int L = static_cast<int>(j.lambdaBlocks.size()) * D, n = N - L;
      double q[elements::kMaxJointCoordinates], g[6], G[6 * elements::kMaxJointCoordinates], mu[6];
      double H[elements::kMaxJointCoordinates * elements::kMaxJointCoordinates] = {};
      if (D == 2) {
        gather<2>(static_cast<int>(k), x, q);
        evaluate<2>(c.joint, q, n, g, G);
      } else {
        gather<3>(static_cast<int>(k), x, q);
        evaluate<3>(c.joint, q, n, g, G);
      }
      gatherMu(lb, j.count, D, x, mu);
      if (!gradientsOnly) {
        int row = 0;
        for (const ConstraintEq& e : j.equations) {
          if (D == 2) Constraint<2>::addHessian(e, q, n, mu + row, scale, H);
          else Constraint<3>::addHessian(e, q, n, mu + row, scale, H);
          row += e.form == ConstraintForm::Equal ? D : 1;
        }
      }
      for (int r = 0; r < n; ++r)
        for (int col = 0; col < n; ++col) Ke[(L + r) * N + L + col] = H[r * n + col];
      for (int e = 0; e < j.count; ++e)
        for (int col = 0; col < n; ++col) Ke[e * N + L + col] = Ke[(L + col) * N + e] = scale * G[e * n + col];
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

PetscErrorCode Multibody::mass(Mat M, const std::vector<char>& fixed) const {
  PetscFunctionBeginUser;
  const auto& local = _dofs.localCouplings();
  for (size_t k = 0; k < local.size(); ++k) {
    const model::Coupling& c = _model.couplings()[local[k]];
    if (c.rigidBody < 0) continue;
    const model::RigidBody& rb = _model.rigidBodies()[c.rigidBody];
    const PetscInt* lb = &_dofs.couplingLocalBlocks()[_dofs.couplingOffset()[k]];
    const PetscInt* gb = &_dofs.couplingGlobalBlocks()[_dofs.couplingOffset()[k]];
    double Ke[16] = {};
    const double diag[4] = {rb.mass, rb.mass, rb.inertia, 0.0};
    for (int i = 0; i < 4; ++i) Ke[i * 4 + i] = fixed[lb[i / 2] * 2 + i % 2] ? 0.0 : diag[i];
    PetscCall(MatSetValuesBlocked(M, 2, gb, 2, gb, Ke, ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

void Multibody::velocityTerm(const double* x, const double* v, double* r) const {
  const int D = _model.dim();
  const auto& local = _dofs.localCouplings();
  for (size_t k = 0; k < local.size(); ++k) {
    const model::Coupling& c = _model.couplings()[local[k]];
    if (c.joint < 0) continue;
    const model::Joint& j = _model.joints()[c.joint];
    const PetscInt* lb = &_dofs.couplingLocalBlocks()[_dofs.couplingOffset()[k]];
    const PetscInt* qb = lb + j.lambdaBlocks.size();
    const int n = static_cast<int>(j.blocks.size()) * D;
    double q[elements::kMaxJointCoordinates], ve[elements::kMaxJointCoordinates];
    if (D == 2) gather<2>(static_cast<int>(k), x, q);
    else gather<3>(static_cast<int>(k), x, q);
    for (int col = 0; col < n; ++col) ve[col] = v[qb[col / D] * D + col % D];
    int row = 0;
    for (const ConstraintEq& e : j.equations) {
      const int m = e.form == ConstraintForm::Equal ? D : 1;
      for (int i = 0; i < m; ++i, ++row) {
        double w[3] = {0.0, 0.0, 0.0}, H[elements::kMaxJointCoordinates * elements::kMaxJointCoordinates] = {};
        w[i] = 1.0;
        if (D == 2) Constraint<2>::addHessian(e, q, n, w, 1.0, H);
        else Constraint<3>::addHessian(e, q, n, w, 1.0, H);
        double vHv = 0.0;
        for (int a = 0; a < n; ++a)
          for (int b = 0; b < n; ++b) vHv += ve[a] * H[a * n + b] * ve[b];
        r[lb[row / D] * D + row % D] += vHv;
      }
    }
  }
}

void Multibody::violation(const double* x, const double* v, double* position, double* velocity) const {
  const int D = _model.dim();
  *position = *velocity = 0.0;
  const auto& local = _dofs.localCouplings();
  for (size_t k = 0; k < local.size(); ++k) {
    const model::Coupling& c = _model.couplings()[local[k]];
    if (c.joint < 0) continue;
    const model::Joint& j = _model.joints()[c.joint];
    const PetscInt* qb = &_dofs.couplingLocalBlocks()[_dofs.couplingOffset()[k] + j.lambdaBlocks.size()];
    const int n = static_cast<int>(j.blocks.size()) * D;
    double q[elements::kMaxJointCoordinates], g[6], G[6 * elements::kMaxJointCoordinates];
    if (D == 2) {
      gather<2>(static_cast<int>(k), x, q);
      evaluate<2>(c.joint, q, n, g, G);
    } else {
      gather<3>(static_cast<int>(k), x, q);
      evaluate<3>(c.joint, q, n, g, G);
    }
    for (int e = 0; e < j.count; ++e) {
      double gv = 0.0;
      for (int col = 0; col < n; ++col) gv += G[e * n + col] * v[qb[col / D] * D + col % D];
      *position = std::max(*position, std::fabs(g[e]));
      *velocity = std::max(*velocity, std::fabs(gv));
    }
  }
}

}  // namespace strand::assembly
