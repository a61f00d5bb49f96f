// Belt-pulley contact in the assembly (internal to the Assembler; issue 34, docs/contact.md).
//
// For each body in contact (Model::contacts()) and each of its local elements, the contact force
// per unit reference length f(r, v) of contact/PulleyContact.hpp is integrated against each listed
// pulley with `points` Gauss points on the element:
//   Q_a = L_e sum_g W_g w_a(eta_g) f(r_g, v_g),   r_g = sum_b w_b(eta_g) q_b,   v_g = sum_b w_b(eta_g) v_b
// (w_a: the kind's centerline interpolation, its weight on block a). Q is an applied force: the
// residual takes -Q, the Newton matrix -dQ/dq - shiftV dQ/dv, the damping matrix -dQ/dv. Pulleys
// turn at a prescribed speed and have no DOFs, so each element's contact stays within its own
// blocks: the element pattern holds it, and nothing is reserved per pulley.
#pragma once
#include <petscmat.h>

#include <vector>

#include "strand/contact/PulleyContact.hpp"
#include "strand/model/DofMap.hpp"
#include "strand/model/Model.hpp"

namespace strand::assembly {

class PulleyContacts {
public:
  PulleyContacts(const model::Model& model, const model::DofMap& dofs, const std::vector<double>& q0Local);
  bool empty() const { return _bodies.empty(); }

  // r -= scale Q (ghosted-local arrays; x displacements, v velocities or null: the belt at rest).
  void residual(const double* x, const double* v, double t, double* r, double scale = 1.0) const;
  // J += -dQ/dq - shiftV dQ/dv, and D += -dQ/dv when D is given (rows and columns of fixed DOFs
  // left out).
  PetscErrorCode jacobian(const double* x, const double* v, double t, double shiftV, Mat J, Mat D,
                          const std::vector<char>& fixed) const;

  // load[3 p .. 3 p + 2] += what this rank's contact points exert on pulley p: force x, y and the
  // torque about its centre (counterclockwise positive), sum_g weight_g (-f, (d x -f)_z).
  void pulleyLoads(const double* x, const double* v, double t, double* load) const;

  // What a contact point found, for output: per local body, element and pulley, the point states.
  struct PointState {
    int body, element, pulley, point;  // model body, element index in it, pulley, Gauss point
    double r[2];                       // the point's position
    contact::ContactPoint state;
  };
  std::vector<PointState> points(const double* x, const double* v, double t) const;

private:
  struct LocalBody {
    int set = 0;                  // index into Model::contacts()
    int stride = 0;               // blocks per element
    std::vector<int> elements;    // this body's local elements: index k in the group's LocalGroup
    std::vector<int> index;       // ... and their index in the body
    const model::DofMap::LocalGroup* group = nullptr;
    std::vector<double> w;        // points x stride interpolation weights
    std::vector<double> weight;   // per point: Gauss weight times element length
  };
  // r and v at Gauss point g of local element k (q0 + x; v null: zero).
  void pointState(const LocalBody& b, int k, int g, const double* x, const double* v, double* r, double* vel) const;
  std::vector<contact::PulleyState> pulleysAt(double t) const;

  const model::Model& _model;
  const std::vector<double>& _q0;
  std::vector<LocalBody> _bodies;
};

}  // namespace strand::assembly
