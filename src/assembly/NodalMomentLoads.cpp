#include "NodalMomentLoads.hpp"

#include "strand/elements/NodalMoment.hpp"

namespace strand::assembly {
namespace {

// Q and dQ/de of a moment on the block's current vector e = q0 + x (dim 2 or 3).
void momentForce(int dim, const model::Vec3& moment, const double* e, double* Q, double* dQ) {
  if (dim == 2) elements::NodalMoment<2>::force(moment, e, Q, dQ);
  else elements::NodalMoment<3>::force(moment, e, Q, dQ);
}

}  // namespace

NodalMomentLoads::NodalMomentLoads(const model::Model& model, const model::DofMap& dofs,
                                   const std::vector<double>& q0Local)
    : _dim(model.dim()), _ownedBegin(dofs.ownedBegin()), _q0(q0Local) {
  for (const model::NodalMomentLoad& ml : model.nodalMoments()) {
    const PetscInt g = dofs.globalBlock()[ml.block];
    if (g >= dofs.ownedBegin() && g < dofs.ownedEnd()) _owned.push_back({g - dofs.ownedBegin(), ml.moment});
  }
}

void NodalMomentLoads::residual(const double* x, double loadFactor, double* r) const {
  const int D = _dim;
  for (const Owned& ml : _owned) {
    double Q[3], e[3];
    for (int i = 0; i < D; ++i) e[i] = _q0[ml.localBlock * D + i] + x[ml.localBlock * D + i];
    momentForce(D, ml.moment, e, Q, nullptr);
    for (int i = 0; i < D; ++i) r[ml.localBlock * D + i] -= loadFactor * Q[i];
  }
}

PetscErrorCode NodalMomentLoads::jacobian(const double* x, double loadFactor, Mat J, const std::vector<char>& fixed) const {
  PetscFunctionBeginUser;
  const int D = _dim;
  for (const Owned& ml : _owned) {
    double Q[3], dQ[9], e[3];
    for (int i = 0; i < D; ++i) e[i] = _q0[ml.localBlock * D + i] + x[ml.localBlock * D + i];
    momentForce(D, ml.moment, e, Q, dQ);
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) {
        const PetscInt li = ml.localBlock * D + i, lj = ml.localBlock * D + j;
        dQ[i * D + j] = (fixed[li] || fixed[lj]) ? 0.0 : -loadFactor * dQ[i * D + j];
      }
    const PetscInt g = ml.localBlock + _ownedBegin;
    PetscCall(MatSetValuesBlocked(J, 1, &g, 1, &g, dQ, ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

}  // namespace strand::assembly
