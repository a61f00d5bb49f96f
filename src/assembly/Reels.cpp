#include "Reels.hpp"

namespace strand::assembly {

Reels::Reels(const model::Model& model, const model::DofMap& dofs) : _model(model) {
  const int D = model.dim();
  for (int r = 0; r < static_cast<int>(model.reels().size()); ++r) {
    _rhoA.push_back(model.bodies()[model.reelBody(r)].properties.rhoA);
    const PetscInt g = dofs.globalBlock()[model.reelBlock(r)];
    if (g >= dofs.ownedBegin() && g < dofs.ownedEnd()) _owned.push_back({r, (g - dofs.ownedBegin()) * D, g * D});
  }
}

double Reels::inertia(int r, double phi, double* dJ) const {
  const model::ReelDesc& d = _model.reels()[r];
  const double content = d.content - d.radius * phi;  // [m] still wound on it
  const double k = _rhoA[r] * d.radius * d.radius;    // dJ/dc
  if (dJ) *dJ = content > 0.0 ? -k * d.radius : 0.0;   // empty: the core alone
  return d.inertia + (content > 0.0 ? k * content : 0.0);
}

void Reels::residual(const double* v, double* r) const {
  if (!v) return;
  for (const Owned& o : _owned) r[o.local] += _model.reels()[o.reel].damping * v[o.local];
}

PetscErrorCode Reels::dampingMatrices(double shiftV, Mat J, Mat D, const std::vector<char>& fixed) const {
  PetscFunctionBeginUser;
  for (const Owned& o : _owned) {
    const double c = _model.reels()[o.reel].damping;
    if (c == 0.0 || fixed[o.local]) continue;
    if (J) PetscCall(MatSetValue(J, o.global, o.global, shiftV * c, ADD_VALUES));
    if (D) PetscCall(MatSetValue(D, o.global, o.global, c, ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

// phi = x: a reel's angle starts at 0 (q0 = 0 on its block)
void Reels::inertiaResidual(const double* x, const double* a, double* r) const {
  for (const Owned& o : _owned) r[o.local] += inertia(o.reel, x[o.local]) * a[o.local];
}

PetscErrorCode Reels::inertiaJacobian(const double* x, const double* a, double shiftA, Mat J,
                                      const std::vector<char>& fixed) const {
  PetscFunctionBeginUser;
  for (const Owned& o : _owned) {
    if (fixed[o.local]) continue;
    double dJ;
    const double Jr = inertia(o.reel, x[o.local], &dJ);
    PetscCall(MatSetValue(J, o.global, o.global, shiftA * Jr + dJ * a[o.local], ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Reels::massAt(const double* x, Mat M, const std::vector<char>& fixed) const {
  PetscFunctionBeginUser;
  for (const Owned& o : _owned)
    if (!fixed[o.local]) PetscCall(MatSetValue(M, o.global, o.global, inertia(o.reel, x[o.local]), ADD_VALUES));
  PetscFunctionReturn(0);
}

double Reels::kineticEnergy(const double* x, const double* v) const {
  double T = 0.0;
  for (const Owned& o : _owned) T += 0.5 * inertia(o.reel, x[o.local]) * v[o.local] * v[o.local];
  return T;
}

}  // namespace strand::assembly
