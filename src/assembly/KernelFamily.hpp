// The assembly loops of one element kind K (internal to the Assembler; ElementFamily.hpp): gather
// an element's coordinates from the ghosted local forms, call K's kernel, scatter. Written once for
// every kind; K's contract is in include/strand/elements/ElementKind.hpp.
//
// Besides K's internal force and tangent, every kind gets here, from its slot mass m (M = m (x) I)
// and its centerline interpolation:
//   - point masses m_p at eta: m += m_p w(eta) w(eta)^T, their weight m_p w(eta) g;
//   - distributed loads and gravity (K::consistentLoad, the same for every element of a body; or,
//     for kinds with K::kConfigurationLoads, K::distributedLoad per element with its tangent);
//   - the rotating frame of seed 003: the centrifugal load Omega^2 (m (x) P)(q - c~), with the
//     axis point c at the position slots (the interpolation reproduces constants there), its
//     softening -Omega^2 m (x) P and the Coriolis matrix 2 Omega m (x) [e]x.
#pragma once
#include <array>
#include <vector>

#include "ElementFamily.hpp"
#include "ElementInserter.hpp"

namespace strand::assembly {

template <class K>
class KernelFamily final : public ElementFamily {
  static constexpr int D = K::kDim;
  static constexpr int B = K::kBlocks;  // blocks (slots) per element
  static constexpr int N = K::kDof;

public:
  KernelFamily(const model::Model& m, const model::DofMap& dofs, const model::DofMap::LocalGroup& local,
               const std::vector<double>& q0Local)
      : _model(m), _dofs(dofs), _group(m.groups()[local.group]), _local(local), _q0(&q0Local) {
    _slotOf.assign(m.bodies().size(), -1);
    for (size_t bi = 0; bi < m.bodies().size(); ++bi) {
      const model::Body& b = m.bodies()[bi];
      if (b.kind != _group.kind) continue;
      _slotOf[bi] = static_cast<int>(_bodies.size());
      PerBody pb{K::body(b.section, b.discretization), {}, {}, 0};
      K::slotMass(pb.kernel, pb.slotMass.data());
      double p[D];
      for (int i = 0; i < D; ++i) p[i] = b.loadPerLength[i];
      K::consistentLoad(pb.kernel, p, pb.load.data());
      pb.referenceCount = b.referenceValues.empty() ? 0 : K::referenceValueCount(pb.kernel);
      _bodies.push_back(std::move(pb));
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
    for (int a = 0; a < B; ++a) _isPosition[a] = K::kNodeLayout[a % K::kBlocksPerNode] == elements::BlockRole::Position;
    // weight of point masses, m w(eta) g, on the local elements that carry them
    for (int k = 0; k < local.size(); ++k) {
      const model::Body& b = body(k);
      for (const model::PointMass& pm : b.pointMasses) {
        if (pm.element != elementIndex(k)) continue;
        double w[B];
        K::interpolation(b.discretization, pm.eta, w);
        std::array<double, N> f{};
        for (int a = 0; a < B; ++a)
          for (int i = 0; i < D; ++i) f[a * D + i] = pm.mass * w[a] * m.gravity()[i];
        _pointMassLoad.push_back({k, f});
      }
    }
  }

  void residual(const double* x, const double* v, double loadFactor, double* r) const override {
    const double omega2 = _model.rotation().omega * _model.rotation().omega;
    double u[N], q0[N], f[N], ve[N];
    for (int k = 0; k < _local.size(); ++k) {
      const PerBody& pb = perBody(k);
      gather(k, x, u, q0);
      if (v) gatherVelocity(k, v, ve);
      K::force(pb.kernel, element(k), q0, u, v ? ve : static_cast<const double*>(nullptr), f);
      if (omega2 != 0.0) addCentrifugalForce(k, q0, u, loadFactor * omega2, f);
      if constexpr (K::kConfigurationLoads) {
        double Q[N], load[D + 1];
        materialLoad(k, 1.0, load);
        K::distributedLoad(pb.kernel, q0, u, load, Q);
        for (int i = 0; i < N; ++i) f[i] -= loadFactor * Q[i];
      }
      const auto& fe = pb.load;
      const PetscInt* lb = _local.localBlocksOf(k);
      for (int a = 0; a < B; ++a)
        for (int i = 0; i < D; ++i) r[lb[a] * D + i] += f[a * D + i] - loadFactor * fe[a * D + i];
    }
    for (const auto& pl : _pointMassLoad) {
      const PetscInt* lb = _local.localBlocksOf(pl.localElement);
      for (int a = 0; a < B; ++a)
        for (int i = 0; i < D; ++i) r[lb[a] * D + i] -= loadFactor * pl.force[a * D + i];
    }
  }

  PetscErrorCode jacobian(const double* x, double loadFactor, Mat J, const std::vector<char>& fixed) const override {
    PetscFunctionBeginUser;
    const double omega2 = _model.rotation().omega * _model.rotation().omega;
    double u[N], q0[N], Ke[N * N];
    ElementInserter toJ;
    PetscCall(ElementInserter::create(J, _dofs, _local, &toJ, &fixed));
    for (int k = 0; k < _local.size(); ++k) {
      gather(k, x, u, q0);
      K::tangent(perBody(k).kernel, element(k), q0, u, nullptr, nullptr, Ke, nullptr);
      if (omega2 != 0.0) addMassBlocks(k, -loadFactor * omega2, _projector, Ke);  // softening -Omega^2 M_P
      addLoadTangent(k, q0, u, loadFactor, Ke);
      maskFixed(k, fixed, Ke);
      PetscCall(toJ.add(k, Ke));
    }
    PetscFunctionReturn(0);
  }

  // K + shiftV D + shiftA M in one pass over the elements (the Newton matrix of an implicit
  // integrator).
  PetscErrorCode dynamicJacobian(const double* x, const double* v, double loadFactor, double shiftV, double shiftA,
                                 Mat J, Mat Dmat, const std::vector<char>& fixed, const double* a) const override {
    PetscFunctionBeginUser;
    double u[N], q0[N], ve[N], Ke[N * N], De[N * N];
    ElementInserter toJ, toD;
    PetscCall(ElementInserter::create(J, _dofs, _local, &toJ, &fixed));
    if (Dmat) PetscCall(ElementInserter::create(Dmat, _dofs, _local, &toD, &fixed));
    for (int k = 0; k < _local.size(); ++k) {
      const PerBody& pb = perBody(k);
      gather(k, x, u, q0);
      if (v) gatherVelocity(k, v, ve);
      const bool damped = v && K::velocityDependent(pb.kernel);
      K::tangent(pb.kernel, element(k), q0, u, v ? ve : nullptr, nullptr, Ke, damped ? De : nullptr);
      if (damped) {
        for (int i = 0; i < N * N; ++i) Ke[i] += shiftV * De[i];
        if (Dmat) {
          maskFixed(k, fixed, De);
          PetscCall(toD.add(k, De));
        }
      }
      addMassBlocks(k, shiftA, _identity, Ke);
      addLoadTangent(k, q0, u, loadFactor, Ke);
      if (a && v) addInertiaTangent(k, q0, u, ve, a, shiftV, shiftA, Ke);
      maskFixed(k, fixed, Ke);
      PetscCall(toJ.add(k, Ke));
    }
    PetscFunctionReturn(0);
  }

  // Consistent mass with point masses: blocks m_ab I_D.
  PetscErrorCode mass(Mat M, const std::vector<char>& fixed) const override {
    return assembleMassBlocks(M, 1.0, _identity, fixed);
  }

  // Coriolis (gyroscopic) matrix of the rotating frame, G = 2 Omega int rho N^T [e]x N dV (plus
  // point masses): the Coriolis force 2 m Omega e x v on the left-hand side; G is skew-symmetric.
  PetscErrorCode gyroscopic(Mat G, const std::vector<char>& fixed) const override {
    return assembleMassBlocks(G, 2.0 * _model.rotation().omega, _skew, fixed);
  }

  double strainEnergy(const double* x) const override {
    double u[N], q0[N], U = 0.0;
    for (int k = 0; k < _local.size(); ++k) {
      gather(k, x, u, q0);
      U += K::strainEnergy(perBody(k).kernel, element(k), q0, u);
    }
    return U;
  }

  bool constantMass() const override { return K::kConstantMass; }

  void inertia(const double* x, const double* v, const double* a, double* r) const override {
    if constexpr (!K::kConstantMass) {
      double u[N], q0[N], ve[N], ae[N], F[N];
      for (int k = 0; k < _local.size(); ++k) {
        gather(k, x, u, q0);
        gatherVelocity(k, v, ve);
        gatherVelocity(k, a, ae);
        K::inertia(perBody(k).kernel, element(k), q0, u, ve, ae, F);
        const PetscInt* lb = _local.localBlocksOf(k);
        for (int b = 0; b < B; ++b)
          for (int i = 0; i < D; ++i) r[lb[b] * D + i] += F[b * D + i];
      }
    } else {
      (void)x, (void)v, (void)a, (void)r;
    }
  }

  // For M(q) kinds: K::force and K::inertiaLessLoad (the inertia less the distributed load, one pass
  // over the inertia's points) per element, one gather of x, v, a.
  void residualWithInertia(const double* x, const double* v, const double* a, bool damped, double loadFactor,
                           double* r) const override {
    if constexpr (!K::kConstantMass) {
      static_assert(K::kConfigurationLoads, "an M(q) kind's load rides with its inertia (inertiaLessLoad)");
      const double omega2 = _model.rotation().omega * _model.rotation().omega;
      double u[N], q0[N], f[N], ve[N], ae[N], F[N], load[D + 1];
      for (int k = 0; k < _local.size(); ++k) {
        const PerBody& pb = perBody(k);
        gather(k, x, u, q0);
        gatherVelocity(k, v, ve);
        gatherVelocity(k, a, ae);
        K::force(pb.kernel, element(k), q0, u, damped ? ve : static_cast<const double*>(nullptr), f);
        if (omega2 != 0.0) addCentrifugalForce(k, q0, u, loadFactor * omega2, f);
        materialLoad(k, loadFactor, load);
        K::inertiaLessLoad(pb.kernel, element(k), q0, u, ve, ae, load, F);
        const auto& fe = pb.load;
        const PetscInt* lb = _local.localBlocksOf(k);
        for (int b = 0; b < B; ++b)
          for (int i = 0; i < D; ++i) r[lb[b] * D + i] += f[b * D + i] + F[b * D + i] - loadFactor * fe[b * D + i];
      }
      for (const auto& pl : _pointMassLoad) {
        const PetscInt* lb = _local.localBlocksOf(pl.localElement);
        for (int b = 0; b < B; ++b)
          for (int i = 0; i < D; ++i) r[lb[b] * D + i] -= loadFactor * pl.force[b * D + i];
      }
    } else {
      residual(x, damped ? v : nullptr, loadFactor, r);
      (void)a;
    }
  }

  PetscErrorCode inertiaJacobian(const double* x, const double* v, const double* a, double shiftV, double shiftA,
                                 Mat J, const std::vector<char>& fixed) const override {
    PetscFunctionBeginUser;
    if constexpr (!K::kConstantMass) {
      double u[N], q0[N], ve[N], Ke[N * N];
      ElementInserter toJ;
      PetscCall(ElementInserter::create(J, _dofs, _local, &toJ, &fixed));
      for (int k = 0; k < _local.size(); ++k) {
        gather(k, x, u, q0);
        gatherVelocity(k, v, ve);
        for (double& e : Ke) e = 0.0;
        addInertiaTangent(k, q0, u, ve, a, shiftV, shiftA, Ke);
        maskFixed(k, fixed, Ke);
        PetscCall(toJ.add(k, Ke));
      }
    } else {
      (void)x, (void)v, (void)a, (void)shiftV, (void)shiftA, (void)J, (void)fixed;
    }
    PetscFunctionReturn(0);
  }

  PetscErrorCode massAt(const double* x, Mat Mat_, const std::vector<char>& fixed) const override {
    PetscFunctionBeginUser;
    if constexpr (!K::kConstantMass) {
      double u[N], q0[N], zero[N] = {}, M[N * N], C[N * N], Kq[N * N];
      ElementInserter toM;
      PetscCall(ElementInserter::create(Mat_, _dofs, _local, &toM, &fixed));
      for (int k = 0; k < _local.size(); ++k) {
        gather(k, x, u, q0);
        K::inertiaTangent(perBody(k).kernel, element(k), q0, u, zero, zero, nullptr, M, C, Kq);
        maskFixed(k, fixed, M);
        PetscCall(toM.add(k, M));
      }
    } else {
      (void)x, (void)Mat_, (void)fixed;
    }
    PetscFunctionReturn(0);
  }

  double kineticEnergy(const double* x, const double* v, double* loadPower) const override {
    double T = 0.0;
    if constexpr (!K::kConstantMass) {
      static_assert(K::kConfigurationLoads, "an M(q) kind's load power rides with its kinetic energy");
      double u[N], q0[N], ve[N], load[D + 1], P = 0.0;
      for (int k = 0; k < _local.size(); ++k) {
        gather(k, x, u, q0);
        gatherVelocity(k, v, ve);
        T += K::kineticEnergy(perBody(k).kernel, q0, u, ve);
        materialLoad(k, 1.0, load);
        if (loadPower) P += K::loadPower(perBody(k).kernel, q0, u, ve, load);
      }
      if (loadPower) *loadPower += P;
    } else {
      (void)x, (void)v, (void)loadPower;
    }
    return T;
  }

  bool configurationLoads() const override { return K::kConfigurationLoads; }
  void addConfigurationLoads(const double* x, double* r) const override {
    if constexpr (K::kConfigurationLoads) {
      double u[N], q0[N], Q[N], load[D + 1];
      for (int k = 0; k < _local.size(); ++k) {
        gather(k, x, u, q0);
        materialLoad(k, 1.0, load);
        K::distributedLoad(perBody(k).kernel, q0, u, load, Q);
        const PetscInt* lb = _local.localBlocksOf(k);
        for (int a = 0; a < B; ++a)
          for (int i = 0; i < D; ++i) r[lb[a] * D + i] += Q[a * D + i];
      }
    } else {
      (void)x, (void)r;
    }
  }

private:
  struct PerBody {
    typename K::Body kernel;
    std::array<double, B * B> slotMass;  // m_ab of one element (no point masses)
    std::array<double, N> load;          // consistent distributed load of one element
    int referenceCount;                  // reference values per element (0: none)
  };

  const model::Body& body(int k) const { return _model.bodies()[_group.body[_local.elements[k]]]; }
  int elementIndex(int k) const { return _group.index[_local.elements[k]]; }
  const PerBody& perBody(int k) const { return _bodies[_slotOf[_group.body[_local.elements[k]]]]; }

  typename K::Element element(int k) const {
    const PerBody& pb = perBody(k);
    const double* ref = pb.referenceCount ? &body(k).referenceValues[static_cast<size_t>(elementIndex(k)) * pb.referenceCount]
                                          : nullptr;
    return K::element(pb.kernel, ref);
  }

  // The load per unit length on the material of a kind with configuration loads, times factor: the
  // force (D components), then the torque about the centerline on a spin angle (component D; the
  // kinds without one ignore it).
  void materialLoad(int k, double factor, double load[D + 1]) const {
    const model::Body& b = body(k);
    for (int i = 0; i < D; ++i) load[i] = factor * b.loadPerLength[i];
    load[D] = factor * b.spinTorquePerLength;
  }

  // Ke += shiftA M + shiftV dF/dv + dF/du of an M(q) kind's inertia (K::inertiaTangent); nothing
  // for the others.
  void addInertiaTangent(int k, const double* q0, const double* u, const double* ve, const double* a, double shiftV,
                         double shiftA, double* Ke) const {
    if constexpr (!K::kConstantMass) {
      double ae[N], M[N * N], C[N * N], Kq[N * N];
      gatherVelocity(k, a, ae);
      K::inertiaTangent(perBody(k).kernel, element(k), q0, u, ve, ae, nullptr, M, C, Kq);
      for (int i = 0; i < N * N; ++i) Ke[i] += Kq[i] + shiftA * M[i] + shiftV * C[i];
    } else {
      (void)k, (void)q0, (void)u, (void)ve, (void)a, (void)shiftV, (void)shiftA, (void)Ke;
    }
  }

  // Ke -= loadFactor dQ_f/du of a configuration-dependent distributed load (K::kConfigurationLoads).
  void addLoadTangent(int k, const double* q0, const double* u, double loadFactor, double* Ke) const {
    if constexpr (K::kConfigurationLoads) {
      double Kf[N * N], load[D + 1];
      materialLoad(k, 1.0, load);
      K::distributedLoadTangent(perBody(k).kernel, q0, u, load, Kf);
      for (int i = 0; i < N * N; ++i) Ke[i] -= loadFactor * Kf[i];
    } else {
      (void)k, (void)q0, (void)u, (void)loadFactor, (void)Ke;
    }
  }

  // Element reference coordinates q0 and displacements u from ghosted-local arrays.
  void gather(int k, const double* x, double* u, double* q0) const {
    const PetscInt* lb = _local.localBlocksOf(k);
    for (int a = 0; a < B; ++a)
      for (int i = 0; i < D; ++i) {
        u[a * D + i] = x[lb[a] * D + i];
        q0[a * D + i] = (*_q0)[lb[a] * D + i];
      }
  }

  void gatherVelocity(int k, const double* v, double* ve) const {
    const PetscInt* lb = _local.localBlocksOf(k);
    for (int a = 0; a < B; ++a)
      for (int i = 0; i < D; ++i) ve[a * D + i] = v[lb[a] * D + i];
  }

  // Slot mass m_ab = the body's + sum m_p w_a w_b over the element's point masses: the element mass
  // matrix is m (x) I_D.
  void slotMass(int k, double m[B][B]) const {
    const PerBody& pb = perBody(k);
    for (int a = 0; a < B; ++a)
      for (int c = 0; c < B; ++c) m[a][c] = pb.slotMass[a * B + c];
    const model::Body& b = body(k);
    for (const model::PointMass& pm : b.pointMasses) {
      if (pm.element != elementIndex(k)) continue;
      double w[B];
      K::interpolation(b.discretization, pm.eta, w);
      for (int a = 0; a < B; ++a)
        for (int c = 0; c < B; ++c) m[a][c] += pm.mass * w[a] * w[c];
    }
  }

  // A += s m (x) X for a D x D matrix X (row-major): blocks s m_ab X.
  void addMassBlocks(int k, double s, const double* X, double* A) const {
    double m[B][B];
    slotMass(k, m);
    for (int a = 0; a < B; ++a)
      for (int c = 0; c < B; ++c)
        for (int i = 0; i < D; ++i)
          for (int j = 0; j < D; ++j) A[(a * D + i) * N + c * D + j] += s * m[a][c] * X[i * D + j];
  }

  // Centrifugal force on the left-hand side, f -= Omega^2 (m (x) P) (q - c~): the centrifugal
  // load Omega^2 int rho N^T P (r - c) dV, with the axis point c interpolated exactly by the
  // position slots (c~: c at positions, 0 at gradients). Seed 003 Eq. 49: lambda^2 (M q + delta S_x).
  void addCentrifugalForce(int k, const double* q0, const double* u, double omega2, double* f) const {
    double m[B][B];
    slotMass(k, m);
    double w[N];
    for (int a = 0; a < B; ++a)
      for (int i = 0; i < D; ++i) w[a * D + i] = q0[a * D + i] + u[a * D + i] - (_isPosition[a] ? _model.rotation().center[i] : 0.0);
    for (int a = 0; a < B; ++a)
      for (int c = 0; c < B; ++c)
        for (int i = 0; i < D; ++i) {
          double pw = 0.0;
          for (int j = 0; j < D; ++j) pw += _projector[i * D + j] * w[c * D + j];
          f[a * D + i] -= omega2 * m[a][c] * pw;
        }
  }

  // Zero the rows and columns of supported DOFs (their unit diagonal is added once, elsewhere).
  void maskFixed(int k, const std::vector<char>& fixed, double* A) const {
    const PetscInt* lb = _local.localBlocksOf(k);
    for (int a = 0; a < B; ++a)
      for (int i = 0; i < D; ++i)
        if (fixed[lb[a] * D + i]) {
          const int r = a * D + i;
          for (int c = 0; c < N; ++c) A[r * N + c] = A[c * N + r] = 0.0;
        }
  }

  // Assemble s m (x) X over the local elements (supported rows and columns zero).
  PetscErrorCode assembleMassBlocks(Mat A, double s, const double* X, const std::vector<char>& fixed) const {
    PetscFunctionBeginUser;
    double Ae[N * N];
    ElementInserter toA;
    PetscCall(ElementInserter::create(A, _dofs, _local, &toA, &fixed));
    for (int k = 0; k < _local.size(); ++k) {
      for (double& a : Ae) a = 0.0;
      addMassBlocks(k, s, X, Ae);
      maskFixed(k, fixed, Ae);
      PetscCall(toA.add(k, Ae));
    }
    PetscFunctionReturn(0);
  }

  const model::Model& _model;
  const model::DofMap& _dofs;
  const model::ElementGroup& _group;
  const model::DofMap::LocalGroup& _local;
  const std::vector<double>* _q0;  // reference coordinates, ghosted-local numbering
  std::vector<int> _slotOf;        // model body -> index into _bodies (-1: another kind)
  std::vector<PerBody> _bodies;
  double _identity[D * D];
  double _projector[D * D], _skew[D * D];  // P = I - e e^T and [e]x of the rotation axis e
  bool _isPosition[B];
  struct PointMassLoad {
    int localElement;
    std::array<double, N> force;
  };
  std::vector<PointMassLoad> _pointMassLoad;
};

}  // namespace strand::assembly
