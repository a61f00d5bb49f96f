// Belt-pulley contact in the assembly (internal to the Assembler; issue 34, docs/contact.md).
//
// For each body in contact (Model::contacts()) and each of its local elements, the contact force
// per unit reference length f(r, v) of contact/PulleyContact.hpp is integrated against each listed
// pulley with `points` Gauss points on the element:
//   Q_a = L_e sum_g W_g w_a(eta_g) f(r_g, v_g),   r_g = sum_b w_b(eta_g) q_b,   v_g = sum_b w_b(eta_g) v_b
// (w_a: the kind's centerline interpolation, its weight on block a). Q is an applied force: the
// residual takes -Q, the Newton matrix -dQ/dq - shiftV dQ/dv, the damping matrix -dQ/dv.
//
// A driven pulley turns at its prescribed speed and has no DOFs: the element's contact stays within
// its own blocks. A free pulley's angle phi is an unknown (Model::pulleyBlock): it takes the belts'
// torque tau = sum_g W_g L_e (d x (-f))_z on its phi row, the contact force depends on its speed
// omega = dphi/dt (df/domega, into the damping matrix), and the Newton matrix couples each element
// to it (Model::Coupling with a pulley: the pattern is reserved). Its own terms, the inertia J and
// the rotational damping c omega, are added once by the rank that owns its block (addPulleyTerms).
#pragma once
#include <petscmat.h>

#include <array>
#include <vector>

#include "strand/assembly/Assembler.hpp"
#include "strand/contact/PulleyContact.hpp"
#include "strand/model/DofMap.hpp"
#include "strand/model/Model.hpp"

namespace strand::assembly {

class PulleyContacts {
public:
  PulleyContacts(const model::Model& model, const model::DofMap& dofs, const std::vector<double>& q0Local);

  // r -= scale Q on the belts' rows and the free pulleys' phi rows (ghosted-local arrays; x
  // displacements, v velocities or null: the belt at rest, free pulleys still).
  void residual(const double* x, const double* v, double t, double* r, double scale = 1.0) const;
  // J += -dQ/dq - shiftV dQ/dv, and D += -dQ/dv when D is given (rows and columns of fixed DOFs
  // left out).
  PetscErrorCode jacobian(const double* x, const double* v, double t, double shiftV, Mat J, Mat D,
                          const std::vector<char>& fixed) const;
  // The free pulleys' own terms, on the owned ones: r += c omega (the rotational damping; v null:
  // none) on phi and k x + c_s x' on a tensioner's x; J += shiftV c + shiftA J_p on phi and
  // k + shiftV c_s + shiftA m on x, D += c, c_s (each matrix may be null).
  void pulleyResidual(const double* x, const double* v, double* r) const;
  PetscErrorCode pulleyMatrices(double shiftV, double shiftA, Mat J, Mat D) const;
  // M += J_p on the free pulleys' phi, m on a tensioner's x.
  PetscErrorCode mass(Mat M) const;
  // The tensioners' spring energy k x^2 / 2 on this rank's owned pulleys.
  double springEnergy(const double* x) const;

  // load[kLoadStride p ..] += what this rank's contact points exert on pulley p: force x, y, the
  // torque about its centre (counterclockwise), and (owned free pulleys) its speed and slide x.
  static constexpr int kLoadStride = 5;
  void pulleyLoads(const double* x, const double* v, double t, double* load) const;

  // The contact's stored energy and the rest of its power (contact::pointEnergy) summed over this
  // rank's points: *stored += phi, *power += P.
  void energy(const double* x, const double* v, double t, double* stored, double* power) const;

  // out += what the law finds at the Gauss points of this rank's elements near a pulley (mayTouch).
  void points(const double* x, const double* v, double t, std::vector<Assembler::ContactPointOut>& out) const;

  // The bristle law's history (contact::BristleHistory): one deflection per local element, listed
  // pulley and Gauss point, and the time of the last accepted step. commit() takes the accepted
  // state at time t: each point's deflection becomes -f_t / k_t (0 off contact) and t the new t_n.
  bool hasHistory() const { return _hasHistory; }
  void commit(const double* x, const double* v, double t);
  // The frozen-state iteration (docs/contact.md): each touching point's stick/slip state is held
  // while Newton solves; settle() compares the states the law takes at the converged (x, v, t) with
  // the held ones, holds the new ones and returns how many changed (a point that had none held, or
  // that left contact, counts as agreeing). Before the first settle none is held. release: hold
  // none at the points that changed at the last settle (all when none did on any rank, as
  // after a step's first solve fails), so that the law decides there within Newton; returns 0.
  int settle(const double* x, const double* v, double t, bool release);
  // Whether any point on any rank changed at the last settle (the caller's sum over the ranks): a
  // release then frees only the points that changed, else all, the same way on every rank.
  void changedAnywhere(bool any) { _changedAnywhere = any; }
  // The history as (body, element, pulley, point) -> z and t_n, for checkpoints; restore() puts
  // back what history() wrote (on any rank count: each rank takes its own elements' points).
  struct HistoryEntry {
    int body, element, pulley, point;
    double z;
  };
  std::vector<HistoryEntry> history() const;
  double committedTime() const { return _tn; }
  void restore(const std::vector<HistoryEntry>& entries, double tn);

private:
  struct LocalBody {
    int set = 0;                  // index into Model::contacts()
    int stride = 0;               // blocks per element
    std::vector<int> elements;    // this body's local elements: index k in the group's LocalGroup
    std::vector<int> index;       // ... and their index in the body
    const model::DofMap::LocalGroup* group = nullptr;
    std::vector<double> w;        // points x stride interpolation weights
    std::vector<double> weight;   // per point: Gauss weight times element length
    double reach = 0.0;           // 2 L_e
    size_t history = 0;           // its first slot in _z: (k * pulleys + listed pulley) * points + g
  };
  // Whether local element k may touch pulley p: its first node lies within R + offset + 2 L_e of
  // the centre (every point of an element stretched less than 100 % lies within 2 L_e of its first
  // node). The contact search: one distance per element and pulley instead of the law at every
  // Gauss point.
  bool mayTouch(const LocalBody& b, int k, const double* x, const contact::PulleyState& p,
                const contact::ContactLaw& law) const;
  // f(body, set, k, g, p, h, r, v) at every Gauss point g of every local element k near pulley p,
  // h its bristle history slot: the loop of the residual, the pulley loads and the output.
  template <class F>
  void forEachNearPoint(const double* x, const double* v, const std::vector<contact::PulleyState>& pulleys,
                        F&& f) const;
  // r and v at Gauss point g of local element k (q0 + x; v null: zero).
  void pointState(const LocalBody& b, int k, int g, const double* x, const double* v, double* r, double* vel) const;
  // The pulleys at time t; free ones with omega from v (null: 0), tensioners' centres moved by
  // their slide x (from x) at the rate x' (from v).
  std::vector<contact::PulleyState> pulleysAt(double t, const double* x, const double* v) const;

  const model::Model& _model;
  const std::vector<double>& _q0;
  std::vector<LocalBody> _bodies;
  std::vector<PetscInt> _pulleyLocal;   // per pulley: ghosted-local block of a free pulley, or -1
  std::vector<PetscInt> _pulleyGlobal;  // per pulley: global block of a free pulley, or -1
  std::vector<int> _ownedFree;          // free pulleys whose block this rank owns
  std::vector<std::array<double, 2>> _slide;  // per pulley: a tensioner's slide direction e, or 0
  bool _hasHistory = false;             // some contact uses the bristle law
  std::vector<double> _z;               // committed deflections, per slot
  std::vector<signed char> _state;      // held stick/slip states, per slot (BristleHistory::state)
  std::vector<char> _changed;           // per slot: its state changed at the last settle
  bool _changedAnywhere = false;        // ... at some slot on some rank (changedAnywhere)
  double _tn = 0.0;                     // the time they belong to
  // Slot h's history at time t (null without the bristle law).
  const contact::BristleHistory* historyAt(size_t h, double t, contact::BristleHistory* buf) const;
};

}  // namespace strand::assembly
