#include "strand/assembly/Assembler.hpp"

#include <algorithm>
#include <cmath>

#include "strand/elements/AncfCable.hpp"
#include "strand/elements/NodalMoment.hpp"
#include "ElementInserter.hpp"
#include "Multibody.hpp"

namespace strand::assembly {

namespace {
PetscLogEvent evResidual = 0, evJacobian = 0, evMass = 0, evDynJacobian = 0;
void registerEvents() {
  static bool done = false;
  if (done) return;
  PetscClassId cid;
  PetscClassIdRegister("Strand", &cid);
  PetscLogEventRegister("Strand:Asm:Resid", cid, &evResidual);
  PetscLogEventRegister("Strand:Asm:Jacob", cid, &evJacobian);
  PetscLogEventRegister("Strand:Asm:Mass", cid, &evMass);
  PetscLogEventRegister("Strand:Asm:DynJac", cid, &evDynJacobian);
  done = true;
}
}  // namespace

// Per-dimension data and loops. One object per run; element data are computed once.
struct Assembler::Impl {
  virtual ~Impl() = default;
  virtual void residual(const double* x, const double* v, double loadFactor, double* r) const = 0;
  virtual PetscErrorCode jacobian(const double* x, double loadFactor, Mat J, const std::vector<char>& fixed) const = 0;
  virtual PetscErrorCode dynamicJacobian(const double* x, const double* v, double loadFactor, double shiftV,
                                         double shiftA, Mat J, Mat Dmat, const std::vector<char>& fixed) const = 0;
  virtual PetscErrorCode mass(Mat M, const std::vector<char>& fixed) const = 0;
  virtual PetscErrorCode gyroscopic(Mat G, const std::vector<char>& fixed) const = 0;
  virtual double strainEnergy(const double* x) const = 0;
};

namespace {

template <int D>
class CableImpl final : public Assembler::Impl {
  using E = elements::AncfCable<D>;
  static constexpr int N = E::kDof;

public:
  CableImpl(const model::Model& m, const model::DofMap& dofs, const std::vector<double>& q0Local)
      : _model(m), _dofs(dofs), _q0(&q0Local), _tab(m.gaussPoints()), _massTab(4) {
    // shape slots at the Gauss points, per body (uniform elements and slope scales)
    for (const model::Body& b : m.bodies()) {
      typename E::Geometry geo;
      geo.length = b.elementLength;
      geo.slopeScale[0] = b.slopeScale[0];
      geo.slopeScale[1] = b.slopeScale[1];
      _points.push_back(E::pointTable(geo, _tab));
    }
    // slot mass of one element, per body, and the rotation axis operators
    for (const model::Body& b : m.bodies()) {
      double Me[N * N];
      E::mass(b.section, geometry(b, 0), _massTab, Me);
      std::array<double, 16> sm{};
      for (int a = 0; a < 4; ++a)
        for (int c = 0; c < 4; ++c) sm[a * 4 + c] = Me[(a * D) * N + c * D];
      _slotMass.push_back(sm);
    }
    for (int i = 0; i < D * D; ++i) _identity[i] = (i % (D + 1) == 0) ? 1.0 : 0.0;
    const model::Vec3& e = m.rotation().axis;
    if constexpr (D == 2) {
      const double P[4] = {1, 0, 0, 1}, S[4] = {0, -1, 1, 0};  // rotation about z: in-plane
      std::copy(P, P + 4, _projector);
      std::copy(S, S + 4, _skew);
    } else {
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) _projector[i * 3 + j] = (i == j ? 1.0 : 0.0) - e[i] * e[j];
      const double S[9] = {0, -e[2], e[1], e[2], 0, -e[0], -e[1], e[0], 0};
      std::copy(S, S + 9, _skew);
    }
    // consistent distributed load of one element, per body (uniform elements)
    for (const model::Body& b : m.bodies()) {
      std::array<double, N> f{};
      double p[D];
      for (int i = 0; i < D; ++i) p[i] = b.loadPerLength[i];
      E::distributedLoad(geometry(b, 0), _tab, p, f.data());
      _bodyLoad.push_back(f);
    }
    // weight of point masses, m N(eta)^T g, on the local elements that carry them
    const auto& local = dofs.localElements();
    for (size_t k = 0; k < local.size(); ++k) {
      const model::ElementRef& er = m.elements()[local[k]];
      const model::Body& b = m.bodies()[er.body];
      for (const model::PointMass& pm : b.pointMasses) {
        if (pm.element != er.index) continue;
        const auto sl = E::slots(geometry(b, er.index), math::hermite(pm.eta));
        std::array<double, N> f{};
        for (int a = 0; a < 4; ++a)
          for (int i = 0; i < D; ++i) f[a * D + i] = pm.mass * sl.N[a] * m.gravity()[i];
        _pointMassLoad.push_back({static_cast<int>(k), f});
      }
    }
    // nodal moments on slope blocks this rank owns
    for (const model::NodalMomentLoad& ml : m.nodalMoments()) {
      const PetscInt g = dofs.globalBlock()[ml.slopeBlock];
      if (g >= dofs.ownedBegin() && g < dofs.ownedEnd()) _moments.push_back({g - dofs.ownedBegin(), ml.moment});
    }
  }

  typename E::Geometry geometry(const model::Body& b, int e) const {
    typename E::Geometry geo;
    geo.length = b.elementLength;
    geo.slopeScale[0] = b.slopeScale[e];
    geo.slopeScale[1] = b.slopeScale[e + 1];
    if (!b.kappa0.empty()) geo.kappa0 = &b.kappa0[e * _tab.size()];
    geo.points = &_points[&b - _model.bodies().data()];
    geo.pointsOf = &_tab;
    return geo;
  }

  // Element reference coordinates q0 and displacements u from ghosted-local arrays.
  void gatherElement(int k, const double* x, double* u, double* q0) const {
    const PetscInt* lb = &_dofs.elementLocalBlocks()[4 * k];
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < D; ++i) {
        u[a * D + i] = x[lb[a] * D + i];
        q0[a * D + i] = (*_q0)[lb[a] * D + i];
      }
  }

  // Element velocities from a ghosted-local array.
  void gatherVelocity(int k, const double* v, double* ve) const {
    const PetscInt* lb = &_dofs.elementLocalBlocks()[4 * k];
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < D; ++i) ve[a * D + i] = v[lb[a] * D + i];
  }

  void residual(const double* x, const double* v, double loadFactor, double* r) const override {
    const double omega2 = _model.rotation().omega * _model.rotation().omega;
    const auto& els = _model.elements();
    const auto& local = _dofs.localElements();
    double u[N], q0[N], f[N], ve[N];
    for (size_t k = 0; k < local.size(); ++k) {
      const model::ElementRef& er = els[local[k]];
      const model::Body& b = _model.bodies()[er.body];
      gatherElement(static_cast<int>(k), x, u, q0);
      if (v) gatherVelocity(static_cast<int>(k), v, ve);
      E::force(b.section, geometry(b, er.index), _tab, q0, u, v ? ve : static_cast<const double*>(nullptr), f);
      if (omega2 != 0.0) addCentrifugalForce(er, b, q0, u, loadFactor * omega2, f);
      const auto& fe = _bodyLoad[er.body];
      const PetscInt* lb = &_dofs.elementLocalBlocks()[4 * k];
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < D; ++i) r[lb[a] * D + i] += f[a * D + i] - loadFactor * fe[a * D + i];
    }
    for (const auto& pl : _pointMassLoad) {
      const PetscInt* lb = &_dofs.elementLocalBlocks()[4 * pl.localElement];
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < D; ++i) r[lb[a] * D + i] -= loadFactor * pl.force[a * D + i];
    }
    for (const auto& ml : _moments) {
      double Q[D], e[D];
      slopeOf(ml.localBlock, x, e);
      elements::NodalMoment<D>::force(ml.moment, e, Q, nullptr);
      for (int i = 0; i < D; ++i) r[ml.localBlock * D + i] -= loadFactor * Q[i];
    }
  }

  PetscErrorCode jacobian(const double* x, double loadFactor, Mat J, const std::vector<char>& fixed) const override {
    PetscFunctionBeginUser;
    const double omega2 = _model.rotation().omega * _model.rotation().omega;
    const auto& els = _model.elements();
    const auto& local = _dofs.localElements();
    double u[N], q0[N], K[N * N];
    ElementInserter toJ;
    PetscCall(ElementInserter::create(J, _dofs, &toJ));
    for (size_t k = 0; k < local.size(); ++k) {
      const model::ElementRef& er = els[local[k]];
      const model::Body& b = _model.bodies()[er.body];
      gatherElement(static_cast<int>(k), x, u, q0);
      E::tangent(b.section, geometry(b, er.index), _tab, q0, u, nullptr, nullptr, K, nullptr);
      if (omega2 != 0.0) addMassBlocks(er, b, -loadFactor * omega2, _projector, K);  // softening -Omega^2 M_P
      maskFixed(static_cast<int>(k), fixed, K);
      PetscCall(toJ.add(static_cast<int>(k), K));
    }
    PetscCall(momentTangents(x, loadFactor, J, fixed));
    PetscFunctionReturn(0);
  }

  // J += -loadFactor dQ/de of the nodal moments (they follow the slope).
  PetscErrorCode momentTangents(const double* x, double loadFactor, Mat J, const std::vector<char>& fixed) const {
    PetscFunctionBeginUser;
    for (const auto& ml : _moments) {
      double Q[D], dQ[D * D], e[D];
      slopeOf(ml.localBlock, x, e);
      elements::NodalMoment<D>::force(ml.moment, e, Q, dQ);
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) {
          const PetscInt li = ml.localBlock * D + i, lj = ml.localBlock * D + j;
          dQ[i * D + j] = (fixed[li] || fixed[lj]) ? 0.0 : -loadFactor * dQ[i * D + j];
        }
      const PetscInt g = ml.localBlock + _dofs.ownedBegin();
      PetscCall(MatSetValuesBlocked(J, 1, &g, 1, &g, dQ, ADD_VALUES));
    }
    PetscFunctionReturn(0);
  }

  // Dynamic tangent K + shiftV D + shiftA M (K = df_int/du, D = df_int/dv, consistent mass M):
  // one pass over the elements for the Newton matrix of an implicit integrator.
  PetscErrorCode dynamicJacobian(const double* x, const double* v, double loadFactor, double shiftV, double shiftA,
                                 Mat J, Mat Dmat, const std::vector<char>& fixed) const override {
    PetscFunctionBeginUser;
    const auto& els = _model.elements();
    const auto& local = _dofs.localElements();
    double u[N], q0[N], ve[N], K[N * N], Dm[N * N];
    ElementInserter toJ, toD;
    PetscCall(ElementInserter::create(J, _dofs, &toJ));
    if (Dmat) PetscCall(ElementInserter::create(Dmat, _dofs, &toD));
    for (size_t k = 0; k < local.size(); ++k) {
      const model::ElementRef& er = els[local[k]];
      const model::Body& b = _model.bodies()[er.body];
      gatherElement(static_cast<int>(k), x, u, q0);
      if (v) gatherVelocity(static_cast<int>(k), v, ve);
      const bool damped = v && (b.section.dampAxial != 0.0 || b.section.dampBending != 0.0);
      E::tangent(b.section, geometry(b, er.index), _tab, q0, u, v ? ve : nullptr, nullptr, K, damped ? Dm : nullptr);
      if (damped) {
        for (int i = 0; i < N * N; ++i) K[i] += shiftV * Dm[i];
        if (Dmat) {
          maskFixed(static_cast<int>(k), fixed, Dm);
          PetscCall(toD.add(static_cast<int>(k), Dm));
        }
      }
      addMassBlocks(er, b, shiftA, _identity, K);
      maskFixed(static_cast<int>(k), fixed, K);
      PetscCall(toJ.add(static_cast<int>(k), K));
    }
    PetscCall(momentTangents(x, loadFactor, J, fixed));
    PetscFunctionReturn(0);
  }

  // Consistent mass with point masses: blocks m_ab I_D.
  PetscErrorCode mass(Mat M, const std::vector<char>& fixed) const override {
    return assembleMassBlocks(M, 1.0, _identity, fixed);
  }

  // Coriolis (gyroscopic) matrix of the rotating frame, G = 2 Omega int rho A N^T [e]x N dx (plus
  // point masses): the Coriolis force 2 m Omega e x v on the left-hand side; G is skew-symmetric.
  PetscErrorCode gyroscopic(Mat G, const std::vector<char>& fixed) const override {
    return assembleMassBlocks(G, 2.0 * _model.rotation().omega, _skew, fixed);
  }

  double strainEnergy(const double* x) const override {
    const auto& els = _model.elements();
    const auto& local = _dofs.localElements();
    double u[N], q0[N], U = 0.0;
    for (size_t k = 0; k < local.size(); ++k) {
      const model::ElementRef& er = els[local[k]];
      const model::Body& b = _model.bodies()[er.body];
      gatherElement(static_cast<int>(k), x, u, q0);
      U += E::strainEnergy(b.section, geometry(b, er.index), _tab, q0, u);
    }
    return U;
  }

private:
  // Nodal-slot mass m_ab = rho A int N_a N_b dx + sum m N_a N_b over the element's point masses:
  // the element mass matrix is m (x) I_D (AncfCable::mass).
  void slotMass(const model::ElementRef& er, const model::Body& b, double m[4][4]) const {
    const auto& base = _slotMass[er.body];
    for (int a = 0; a < 4; ++a)
      for (int c = 0; c < 4; ++c) m[a][c] = base[a * 4 + c];
    for (const model::PointMass& pm : b.pointMasses) {
      if (pm.element != er.index) continue;
      const auto sl = E::slots(geometry(b, er.index), math::hermite(pm.eta));
      for (int a = 0; a < 4; ++a)
        for (int c = 0; c < 4; ++c) m[a][c] += pm.mass * sl.N[a] * sl.N[c];
    }
  }

  // Assemble s m (x) X over the local elements (supported rows and columns zero).
  PetscErrorCode assembleMassBlocks(Mat A, double s, const double* X, const std::vector<char>& fixed) const {
    PetscFunctionBeginUser;
    const auto& els = _model.elements();
    const auto& local = _dofs.localElements();
    double Ae[N * N];
    ElementInserter toA;
    PetscCall(ElementInserter::create(A, _dofs, &toA));
    for (size_t k = 0; k < local.size(); ++k) {
      const model::ElementRef& er = els[local[k]];
      for (double& a : Ae) a = 0.0;
      addMassBlocks(er, _model.bodies()[er.body], s, X, Ae);
      maskFixed(static_cast<int>(k), fixed, Ae);
      PetscCall(toA.add(static_cast<int>(k), Ae));
    }
    PetscFunctionReturn(0);
  }

  // A += s m (x) X for a D x D matrix X (row-major): blocks s m_ab X.
  void addMassBlocks(const model::ElementRef& er, const model::Body& b, double s, const double* X, double* A) const {
    double m[4][4];
    slotMass(er, b, m);
    for (int a = 0; a < 4; ++a)
      for (int c = 0; c < 4; ++c)
        for (int i = 0; i < D; ++i)
          for (int j = 0; j < D; ++j) A[(a * D + i) * N + c * D + j] += s * m[a][c] * X[i * D + j];
  }

  // Centrifugal force on the left-hand side, f -= Omega^2 (m (x) P) (q - c~): the centrifugal
  // load Omega^2 int rho A N^T P (r - c) dx, with the axis point c interpolated exactly by the
  // position slots (c~: c at positions, 0 at slopes). Seed 003 Eq. 49: lambda^2 (M q + delta S_x).
  void addCentrifugalForce(const model::ElementRef& er, const model::Body& b, const double* q0, const double* u,
                           double omega2, double* f) const {
    double m[4][4];
    slotMass(er, b, m);
    double w[N];
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < D; ++i) w[a * D + i] = q0[a * D + i] + u[a * D + i] - (a % 2 == 0 ? _model.rotation().center[i] : 0.0);
    for (int a = 0; a < 4; ++a)
      for (int c = 0; c < 4; ++c)
        for (int i = 0; i < D; ++i) {
          double pw = 0.0;
          for (int j = 0; j < D; ++j) pw += _projector[i * D + j] * w[c * D + j];
          f[a * D + i] -= omega2 * m[a][c] * pw;
        }
  }

  void slopeOf(PetscInt localBlock, const double* x, double* e) const {
    for (int i = 0; i < D; ++i) e[i] = (*_q0)[localBlock * D + i] + x[localBlock * D + i];
  }

  // Zero the rows and columns of supported DOFs (their unit diagonal is added once, elsewhere).
  void maskFixed(int k, const std::vector<char>& fixed, double* A) const {
    const PetscInt* lb = &_dofs.elementLocalBlocks()[4 * k];
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < D; ++i)
        if (fixed[lb[a] * D + i]) {
          const int r = a * D + i;
          for (int c = 0; c < N; ++c) A[r * N + c] = A[c * N + r] = 0.0;
        }
  }

  struct OwnedMoment {
    PetscInt localBlock;
    model::Vec3 moment;
  };
  const model::Model& _model;
  const model::DofMap& _dofs;
  const std::vector<double>* _q0;  // reference coordinates, ghosted-local numbering
  elements::CableShapeTable _tab, _massTab;
  std::vector<std::array<double, N>> _bodyLoad;
  std::vector<elements::CablePointTable> _points;  // per body, at the Gauss points of _tab
  std::vector<std::array<double, 16>> _slotMass;       // per body: m_ab of one element (no point masses)
  double _identity[D * D];
  double _projector[D * D], _skew[D * D];              // P = I - e e^T and [e]x of the rotation axis e
  std::vector<OwnedMoment> _moments;
  struct PointMassLoad {
    int localElement;
    std::array<double, N> force;
  };
  std::vector<PointMassLoad> _pointMassLoad;
};

}  // namespace

Assembler::Assembler(const model::Model& model, const model::DofMap& dofs) : _model(model), _dofs(dofs) {
  registerEvents();
  PetscCallAbort(dofs.comm(), dofs.createVector(&_xWork));
  PetscCallAbort(dofs.comm(), VecDuplicate(_xWork, &_rWork));
  PetscCallAbort(dofs.comm(), VecDuplicate(_xWork, &_vWork));
  // supports and initial coordinates in the ghosted local numbering
  const PetscInt bs = dofs.blockSize();
  PetscInt nLocal = 0;
  {
    Vec xl;
    PetscCallAbort(dofs.comm(), VecGhostGetLocalForm(_xWork, &xl));
    PetscCallAbort(dofs.comm(), VecGetLocalSize(xl, &nLocal));
    PetscCallAbort(dofs.comm(), VecGhostRestoreLocalForm(_xWork, &xl));
  }
  {
    PetscInt owned;
    PetscCallAbort(dofs.comm(), VecGetLocalSize(_xWork, &owned));
    int ghosts = nLocal > owned ? 1 : 0, any = 0;
    MPI_Allreduce(&ghosts, &any, 1, MPI_INT, MPI_MAX, dofs.comm());
    _haveGhosts = any != 0;
  }
  _fixedLocal.assign(nLocal, 0);
  _q0Local.assign(nLocal, 0.0);
  _multiplierOwned.assign(dofs.ownedBlocks() * bs, 0);
  _v0Owned.assign(dofs.ownedBlocks() * bs, 0.0);
  for (int b = 0; b < model.numBlocks(); ++b) {
    const PetscInt lb = dofs.localBlock(dofs.globalBlock()[b]);
    if (lb < 0) continue;
    for (PetscInt i = 0; i < bs; ++i) {
      _fixedLocal[lb * bs + i] = model.fixedDofs()[b * bs + i];
      _q0Local[lb * bs + i] = model.initialCoordinates()[b * bs + i];
      if (lb < dofs.ownedBlocks()) {
        const double force = model.nodalForces()[b * bs + i];
        if (force != 0.0) _nodalForceOwned.push_back({lb * bs + i, force});
        _multiplierOwned[lb * bs + i] = model.multiplierDofs()[b * bs + i];
        _v0Owned[lb * bs + i] = model.initialVelocities()[b * bs + i];
      }
    }
  }
  for (PetscInt i = 0; i < dofs.ownedBlocks() * bs; ++i)
    if (_fixedLocal[i]) _fixedOwned.push_back(i);
  _noneFixed.assign(nLocal, 0);
  for (int h = 0; h < static_cast<int>(model.hubMotions().size()); ++h) {
    const model::HubMotion& hub = model.hubMotions()[h];
    for (int k = 0; k < static_cast<int>(hub.blocks.size()); ++k) {
      const PetscInt lb = dofs.localBlock(dofs.globalBlock()[hub.blocks[k]]);
      if (lb < 0 || lb >= dofs.ownedBlocks()) continue;
      _moved.push_back({lb * bs, h, k});
    }
  }
  for (int k = 0; k < static_cast<int>(model.prescribedCoordinates().size()); ++k) {
    const int dof = model.prescribedCoordinates()[k].dof;
    const PetscInt lb = dofs.localBlock(dofs.globalBlock()[dof / bs]);
    if (lb >= 0 && lb < dofs.ownedBlocks()) _movedCoordinates.push_back({lb * bs + dof % bs, k});
  }
  if (model.dim() == 2)
    _impl = std::make_unique<CableImpl<2>>(model, dofs, _q0Local);
  else
    _impl = std::make_unique<CableImpl<3>>(model, dofs, _q0Local);
  _multibody = std::make_unique<Multibody>(model, dofs, _q0Local);
}

Assembler::~Assembler() {
  VecDestroy(&_xWork);
  VecDestroy(&_rWork);
  VecDestroy(&_vWork);
  VecScatterDestroy(&_toRoot);
  VecDestroy(&_rootVec);
}

PetscErrorCode Assembler::initialState(Vec X) const {
  PetscFunctionBeginUser;
  PetscCall(VecSet(X, 0.0));  // unknowns are displacements from the reference shape
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::initialVelocity(Vec V) const {
  PetscFunctionBeginUser;
  PetscScalar* v;
  PetscCall(VecGetArray(V, &v));
  for (size_t i = 0; i < _v0Owned.size(); ++i) v[i] = _v0Owned[i];
  PetscCall(VecRestoreArray(V, &v));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::multiplierMask(Vec mask) const {
  PetscFunctionBeginUser;
  PetscScalar* m;
  PetscCall(VecGetArray(mask, &m));
  for (size_t i = 0; i < _multiplierOwned.size(); ++i) m[i] = _multiplierOwned[i];
  PetscCall(VecRestoreArray(mask, &m));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::supportMask(Vec mask) const {
  PetscFunctionBeginUser;
  PetscScalar* m;
  PetscInt n;
  PetscCall(VecGetLocalSize(mask, &n));
  PetscCall(VecGetArray(mask, &m));
  for (PetscInt i = 0; i < n; ++i) m[i] = _fixedLocal[i] ? 1.0 : 0.0;
  PetscCall(VecRestoreArray(mask, &m));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::saddleMatrix(Vec X, Mat S) {
  PetscFunctionBeginUser;
  LocalRead x;
  PetscCall(beginLocal(X, _xWork, &x));
  PetscCall(MatZeroEntries(S));
  PetscCall(_impl->mass(S, _fixedLocal));
  PetscCall(_multibody->mass(S, _fixedLocal));
  PetscCall(_multibody->jacobian(x.a, 1.0, 0.0, 0.0, S, _fixedLocal, true));
  PetscCall(endLocal(&x));
  PetscCall(assembleWithSupportDiagonal(S));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::jointVector(Vec X, Vec W, const std::function<void(const double*, const double*, double*)>& add,
                                      Vec R) {
  PetscFunctionBeginUser;
  LocalRead x, w;
  LocalSum r;
  PetscCall(beginLocal(X, _xWork, &x));
  PetscCall(beginLocal(W, _vWork, &w));
  PetscCall(beginLocalSum(R, {X, W}, &r));
  add(x.a, w.a, r.a);
  PetscCall(endLocalSum(&r));
  PetscCall(endLocal(&x));
  PetscCall(endLocal(&w));
  PetscCall(deliver(r, R));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::constraintVelocityTerm(Vec X, Vec V, Vec R) {
  return jointVector(X, V, [&](const double* x, const double* v, double* r) { _multibody->velocityTerm(x, v, r); }, R);
}

PetscErrorCode Assembler::constraintGradientProduct(Vec X, Vec W, Vec R) {
  return jointVector(
      X, W, [&](const double* x, const double* w, double* r) { _multibody->gradientProduct(x, w, _constraintScale, r); },
      R);
}

PetscErrorCode Assembler::constraintGradientMatrices(Vec X, Vec W, Mat C, Mat dC) {
  PetscFunctionBeginUser;
  LocalRead x, w;
  PetscCall(beginLocal(X, _xWork, &x));
  PetscCall(beginLocal(W, _vWork, &w));
  for (Mat A : {C, dC})
    if (A) PetscCall(MatZeroEntries(A));
  PetscCall(_multibody->gradientProductJacobian(x.a, w.a, _constraintScale, C, dC, _fixedLocal));
  PetscCall(endLocal(&x));
  PetscCall(endLocal(&w));
  for (Mat A : {C, dC})
    if (A) {
      PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
      PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
    }
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::constraintViolation(Vec X, Vec V, PetscReal* position, PetscReal* velocity) {
  PetscFunctionBeginUser;
  LocalRead x, v;
  PetscCall(beginLocal(X, _xWork, &x));
  PetscCall(beginLocal(V, _vWork, &v));
  double local[2];
  _multibody->violation(x.a, v.a, &local[0], &local[1]);
  PetscCall(endLocal(&x));
  PetscCall(endLocal(&v));
  double global[2];
  PetscCallMPI(MPI_Allreduce(local, global, 2, MPI_DOUBLE, MPI_MAX, _dofs.comm()));
  *position = global[0];
  *velocity = global[1];
  PetscFunctionReturn(0);
}

// The ghosted local form of `from`: its own, ghosts updated in place, when it has our layout (its
// owned values stay as they are, so a read-locked input is fine); else a copy in `work`.
PetscErrorCode Assembler::beginLocal(Vec from, Vec work, LocalRead* view) {
  bool own;
  PetscFunctionBeginUser;
  PetscCall(_dofs.sharesGhosts(from, &own));
  view->owner = own ? from : work;
  if (!own) PetscCall(VecCopy(from, work));
  PetscCall(updateGhosts(view->owner));
  PetscCall(VecGhostGetLocalForm(view->owner, &view->local));
  PetscCall(VecGetArrayRead(view->local, &view->a));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::endLocal(LocalRead* view) {
  PetscFunctionBeginUser;
  PetscCall(VecRestoreArrayRead(view->local, &view->a));
  PetscCall(VecGhostRestoreLocalForm(view->owner, &view->local));
  PetscFunctionReturn(0);
}

// A zeroed ghosted local form to sum element contributions into: R's own when R has our layout
// and is none of the inputs being read, else _rWork's.
PetscErrorCode Assembler::beginLocalSum(Vec R, std::initializer_list<Vec> inputs, LocalSum* sum) {
  bool own;
  PetscFunctionBeginUser;
  PetscCall(_dofs.sharesGhosts(R, &own));
  for (Vec in : inputs) own = own && in != R;
  sum->owner = own ? R : _rWork;
  PetscCall(VecGhostGetLocalForm(sum->owner, &sum->local));
  PetscCall(VecSet(sum->local, 0.0));
  PetscCall(VecGetArray(sum->local, &sum->a));
  PetscFunctionReturn(0);
}

// The ghosts' sums added to their owners: sum->owner holds the owned result.
PetscErrorCode Assembler::endLocalSum(LocalSum* sum) {
  PetscFunctionBeginUser;
  PetscCall(VecRestoreArray(sum->local, &sum->a));
  PetscCall(VecGhostRestoreLocalForm(sum->owner, &sum->local));
  PetscCall(addGhostsToOwners(sum->owner));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::deliver(const LocalSum& sum, Vec R) {
  PetscFunctionBeginUser;
  if (sum.owner != R) PetscCall(VecCopy(sum.owner, R));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::updateGhosts(Vec work) {
  PetscFunctionBeginUser;
  if (_haveGhosts) {
    PetscCall(VecGhostUpdateBegin(work, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecGhostUpdateEnd(work, INSERT_VALUES, SCATTER_FORWARD));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::addGhostsToOwners(Vec work) {
  PetscFunctionBeginUser;
  if (_haveGhosts) {
    PetscCall(VecGhostUpdateBegin(work, ADD_VALUES, SCATTER_REVERSE));
    PetscCall(VecGhostUpdateEnd(work, ADD_VALUES, SCATTER_REVERSE));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::staticResidual(Vec X, PetscReal loadFactor, Vec R) {
  PetscFunctionBeginUser;
  PetscCall(assembleResidual(X, nullptr, loadFactor, R, SupportRows::Value));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::residual(Vec X, Vec V, PetscReal t, Vec R, SupportRows rows) {
  PetscFunctionBeginUser;
  PetscCall(assembleResidual(X, V, _model.loadFactor(t), R, rows));
  PetscCall(addTimedLoads(t, R, -1.0, rows == SupportRows::Value));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::assembleResidual(Vec X, Vec V, PetscReal loadFactor, Vec R, SupportRows rows) {
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(evResidual, 0, 0, 0, 0));
  LocalRead x, v;
  LocalSum r;
  PetscCall(beginLocal(X, _xWork, &x));
  if (V) PetscCall(beginLocal(V, _vWork, &v));
  PetscCall(beginLocalSum(R, {X, V}, &r));
  PetscCallCXX(_impl->residual(x.a, v.a, loadFactor, r.a));
  PetscCallCXX(_multibody->residual(x.a, _constraintScale, loadFactor, r.a));
  PetscCall(endLocalSum(&r));
  // owned rows: nodal forces and supports
  PetscScalar* owned;
  PetscCall(VecGetArray(r.owner, &owned));
  for (const auto& [i, f] : _nodalForceOwned) owned[i] -= loadFactor * f;
  if (rows == SupportRows::Value)
    for (PetscInt i : _fixedOwned) owned[i] = x.a[i];
  PetscCall(VecRestoreArray(r.owner, &owned));
  PetscCall(endLocal(&x));
  if (V) PetscCall(endLocal(&v));
  PetscCall(deliver(r, R));
  PetscCall(PetscLogEventEnd(evResidual, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

// The unit diagonal of supported rows (the element matrices were masked), then final assembly.
PetscErrorCode Assembler::assembleWithSupportDiagonal(Mat J) const {
  PetscFunctionBeginUser;
  const PetscInt row0 = _dofs.ownedBegin() * _dofs.blockSize();
  for (PetscInt i : _fixedOwned) PetscCall(MatSetValue(J, row0 + i, row0 + i, 1.0, ADD_VALUES));
  PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::staticJacobian(Vec X, PetscReal loadFactor, Mat J) {
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(evJacobian, 0, 0, 0, 0));
  LocalRead x;
  PetscCall(beginLocal(X, _xWork, &x));
  PetscCall(MatZeroEntries(J));
  PetscCall(_impl->jacobian(x.a, loadFactor, J, _fixedLocal));
  PetscCall(_multibody->jacobian(x.a, _constraintScale, 0.0, loadFactor, J, _fixedLocal));
  PetscCall(endLocal(&x));
  PetscCall(assembleWithSupportDiagonal(J));
  PetscCall(PetscLogEventEnd(evJacobian, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::dynamicJacobian(Vec X, Vec V, PetscReal t, PetscReal shiftV, PetscReal shiftA, Mat J, Mat D) {
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(evDynJacobian, 0, 0, 0, 0));
  LocalRead x, v;
  PetscCall(beginLocal(X, _xWork, &x));
  if (V) PetscCall(beginLocal(V, _vWork, &v));
  PetscCall(MatZeroEntries(J));
  if (D) PetscCall(MatZeroEntries(D));
  const double loadFactor = _model.loadFactor(t);
  PetscCall(_impl->dynamicJacobian(x.a, v.a, loadFactor, shiftV, shiftA, J, D, _fixedLocal));
  PetscCall(_multibody->jacobian(x.a, _constraintScale, shiftA, loadFactor, J, _fixedLocal));
  PetscCall(endLocal(&x));
  if (V) PetscCall(endLocal(&v));
  PetscCall(assembleWithSupportDiagonal(J));
  if (D) {
    PetscCall(MatAssemblyBegin(D, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(D, MAT_FINAL_ASSEMBLY));
  }
  PetscCall(PetscLogEventEnd(evDynJacobian, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::externalForce(Vec F) {
  PetscFunctionBeginUser;
  Vec X0, R1;
  PetscCall(VecDuplicate(F, &X0));
  PetscCall(VecDuplicate(F, &R1));
  PetscCall(VecSet(X0, 0.0));
  // supported rows included (Reaction rows): the energy balance needs the loads' power on moving supports
  PetscCall(assembleResidual(X0, nullptr, 0.0, F, SupportRows::Reaction));   // f_int(0)
  PetscCall(assembleResidual(X0, nullptr, 1.0, R1, SupportRows::Reaction));  // f_int(0) - f_ext
  PetscCall(VecAXPY(F, -1.0, R1));
  PetscCall(VecDestroy(&X0));
  PetscCall(VecDestroy(&R1));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::massMatrix(Mat M, bool maskSupports) {
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(evMass, 0, 0, 0, 0));
  PetscCall(MatZeroEntries(M));
  PetscCall(_impl->mass(M, maskSupports ? _fixedLocal : _noneFixed));
  PetscCall(_multibody->mass(M, maskSupports ? _fixedLocal : _noneFixed));
  PetscCall(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
  PetscCall(PetscLogEventEnd(evMass, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::prescribedMotion(PetscReal t, Vec X, Vec V, Vec A) const {
  PetscFunctionBeginUser;
  if (_moved.empty() && _movedCoordinates.empty()) PetscFunctionReturn(0);
  PetscScalar *x = nullptr, *v = nullptr, *a = nullptr;
  if (X) PetscCall(VecGetArray(X, &x));
  if (V) PetscCall(VecGetArray(V, &v));
  if (A) PetscCall(VecGetArray(A, &a));
  const int D = _model.dim();
  for (const MovedBlock& m : _moved) {
    const model::HubMotion& hub = _model.hubMotions()[m.hub];
    double u[3], du[3], ddu[3];
    hub.state(m.block, &_model.initialCoordinates()[hub.blocks[m.block] * D], D, t, u, du, ddu);
    for (int i = 0; i < D; ++i) {
      if (x) x[m.owned + i] = u[i];
      if (v) v[m.owned + i] = du[i];
      if (a) a[m.owned + i] = ddu[i];
    }
  }
  for (const auto& [owned, k] : _movedCoordinates) {
    // the scene's angle is the one at t = 0: phi = angle + f(t) - f(0) (user-guide, "Turning hubs")
    const model::TimeFunction& function = _model.prescribedCoordinates()[k].function;
    const model::TimeValue f = function.at(t);
    if (x) x[owned] = f.f - function.at(0.0).f;
    if (v) v[owned] = f.df;
    if (a) a[owned] = f.ddf;
  }
  if (X) PetscCall(VecRestoreArray(X, &x));
  if (V) PetscCall(VecRestoreArray(V, &v));
  if (A) PetscCall(VecRestoreArray(A, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::zeroSupportedRows(Vec R) const {
  PetscFunctionBeginUser;
  PetscScalar* r;
  PetscCall(VecGetArray(R, &r));
  for (PetscInt i : _fixedOwned) r[i] = 0.0;
  PetscCall(VecRestoreArray(R, &r));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::gyroscopicMatrix(Mat G) {
  PetscFunctionBeginUser;
  PetscCall(MatZeroEntries(G));
  PetscCall(_impl->gyroscopic(G, _fixedLocal));
  PetscCall(MatAssemblyBegin(G, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(G, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::strainEnergy(Vec X, PetscReal* U) {
  PetscFunctionBeginUser;
  LocalRead x;
  PetscCall(beginLocal(X, _xWork, &x));
  double local = _impl->strainEnergy(x.a);
  PetscCall(endLocal(&x));
  PetscCallMPI(MPI_Allreduce(&local, U, 1, MPI_DOUBLE, MPI_SUM, _dofs.comm()));
  PetscFunctionReturn(0);
}

PetscReal Assembler::coordinateNorm() const {
  double local = 0.0, global = 0.0;
  const PetscInt n = _dofs.ownedBlocks() * _dofs.blockSize();
  for (PetscInt i = 0; i < n; ++i) local += _q0Local[i] * _q0Local[i];
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, _dofs.comm());
  return std::sqrt(global);
}

PetscErrorCode Assembler::freeDofs(IS* is) const {
  PetscFunctionBeginUser;
  const PetscInt bs = _dofs.blockSize(), n = _dofs.ownedBlocks() * bs, row0 = _dofs.ownedBegin() * bs;
  std::vector<PetscInt> idx;
  for (PetscInt i = 0; i < n; ++i)
    if (!_fixedLocal[i]) idx.push_back(row0 + i);
  PetscCall(ISCreateGeneral(_dofs.comm(), static_cast<PetscInt>(idx.size()), idx.data(), PETSC_COPY_VALUES, is));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::addTimedLoads(PetscReal t, Vec R, PetscReal scale, bool skipSupported) const {
  PetscFunctionBeginUser;
  if (_model.timedLoads().empty()) PetscFunctionReturn(0);
  const PetscInt bs = _dofs.blockSize(), first = _dofs.ownedBegin(), owned = _dofs.ownedBlocks();
  PetscScalar* r;
  PetscCall(VecGetArray(R, &r));
  for (const model::TimedLoad& l : _model.timedLoads()) {
    const double g = scale * l.function.at(t).f;
    for (size_t k = 0; k < l.dofs.size(); ++k) {
      const PetscInt blk = _dofs.globalBlock()[l.dofs[k] / bs] - first;
      const PetscInt i = blk * bs + l.dofs[k] % bs;
      if (blk >= 0 && blk < owned && !(skipSupported && _fixedLocal[i])) r[i] += g * l.values[k];
    }
  }
  PetscCall(VecRestoreArray(R, &r));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::gatherToRoot(Vec X, std::vector<double>& out) {
  PetscFunctionBeginUser;
  PetscCall(toModelOrder(X, out));
  for (size_t i = 0; i < out.size(); ++i) out[i] += _model.initialCoordinates()[i];
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::toModelOrder(Vec X, std::vector<double>& out) {
  PetscFunctionBeginUser;
  if (!_toRoot) PetscCall(VecScatterCreateToZero(X, &_toRoot, &_rootVec));
  PetscCall(VecScatterBegin(_toRoot, X, _rootVec, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(_toRoot, X, _rootVec, INSERT_VALUES, SCATTER_FORWARD));
  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(_dofs.comm(), &rank));
  out.clear();
  if (rank == 0) {
    const PetscScalar* a;
    PetscCall(VecGetArrayRead(_rootVec, &a));
    const PetscInt bs = _dofs.blockSize();
    out.resize(_model.numDofs());
    for (int b = 0; b < _model.numBlocks(); ++b)
      for (PetscInt i = 0; i < bs; ++i) out[b * bs + i] = a[_dofs.globalBlock()[b] * bs + i];
    PetscCall(VecRestoreArrayRead(_rootVec, &a));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::fromModelOrder(const std::vector<double>& in, Vec X) {
  PetscFunctionBeginUser;
  if (!_toRoot) PetscCall(VecScatterCreateToZero(X, &_toRoot, &_rootVec));
  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(_dofs.comm(), &rank));
  if (rank == 0) {
    PetscCheck(in.size() == static_cast<size_t>(_model.numDofs()), PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ,
               "fromModelOrder: %zu values for %d coordinates", in.size(), _model.numDofs());
    PetscScalar* a;
    PetscCall(VecGetArray(_rootVec, &a));
    const PetscInt bs = _dofs.blockSize();
    for (int b = 0; b < _model.numBlocks(); ++b)
      for (PetscInt i = 0; i < bs; ++i) a[_dofs.globalBlock()[b] * bs + i] = in[b * bs + i];
    PetscCall(VecRestoreArray(_rootVec, &a));
  }
  PetscCall(VecScatterBegin(_toRoot, _rootVec, X, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(_toRoot, _rootVec, X, INSERT_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(0);
}

}  // namespace strand::assembly
