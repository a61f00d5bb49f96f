#include "PulleyContacts.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "strand/elements/ElementKinds.hpp"
#include "strand/math/Gauss.hpp"

namespace strand::assembly {

namespace {

// The frozen-state iteration's tolerance on a point's friction force, relative to mu p (settle).
constexpr double kSettleTolerance = 1e-4;

// The torque about the pulley's centre of the belt's pull -f at d = r - c: (d x (-f))_z.
double torqueOf(const double* d, const double* f) { return -(d[0] * f[1] - d[1] * f[0]); }

// tau = torqueOf(d, f) and its derivatives in r, v (2 each) and omega.
struct PointTorque {
  double tau, dr[2], dv[2], domega;
};
PointTorque pointTorque(const double* d, const double* f, const double* dfdr, const double* dfdv, const double* dfdw) {
  PointTorque t;
  t.tau = torqueOf(d, f);
  t.dr[0] = -(f[1] + d[0] * dfdr[2] - d[1] * dfdr[0]);
  t.dr[1] = -(-f[0] + d[0] * dfdr[3] - d[1] * dfdr[1]);
  for (int j = 0; j < 2; ++j) t.dv[j] = -(d[0] * dfdv[2 + j] - d[1] * dfdv[j]);
  t.domega = -(d[0] * dfdw[1] - d[1] * dfdw[0]);
  return t;
}

// The Newton (J) and damping (D) entries of an element's coupling to a free pulley's block (phi, x):
// belt rows x (phi, x) columns (n x 2), (phi, x) rows x belt columns (2 x n) and the block's own
// 2 x 2 (row-major). Without a slide the x row and column stay zero (x is held).
struct PulleyCoupling {
  std::vector<double> colJ, colD, rowJ, rowD;  // n x 2 and 2 x n
  double selfJ[4] = {0, 0, 0, 0}, selfD[4] = {0, 0, 0, 0};
  void zero(size_t n) {
    for (auto* m : {&colJ, &colD, &rowJ, &rowD}) m->assign(2 * n, 0.0);
    for (int i = 0; i < 4; ++i) selfJ[i] = selfD[i] = 0.0;
  }
};

PetscErrorCode insertCoupling(Mat J, Mat D, int stride, const PetscInt* gb, PetscInt pg, const PulleyCoupling& c) {
  PetscFunctionBeginUser;
  PetscCall(MatSetValuesBlocked(J, stride, gb, 1, &pg, c.colJ.data(), ADD_VALUES));
  PetscCall(MatSetValuesBlocked(J, 1, &pg, stride, gb, c.rowJ.data(), ADD_VALUES));
  PetscCall(MatSetValuesBlocked(J, 1, &pg, 1, &pg, c.selfJ, ADD_VALUES));
  if (D) {
    PetscCall(MatSetValuesBlocked(D, stride, gb, 1, &pg, c.colD.data(), ADD_VALUES));
    PetscCall(MatSetValuesBlocked(D, 1, &pg, stride, gb, c.rowD.data(), ADD_VALUES));
    PetscCall(MatSetValuesBlocked(D, 1, &pg, 1, &pg, c.selfD, ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

}  // namespace

PulleyContacts::PulleyContacts(const model::Model& model, const model::DofMap& dofs,
                               const std::vector<double>& q0Local)
    : _model(model), _q0(q0Local) {
  for (size_t s = 0; s < model.contacts().size(); ++s) {
    const model::PulleyContactSet& set = model.contacts()[s];
    const model::Body& body = model.bodies()[set.body];
    for (const model::DofMap::LocalGroup& local : dofs.localGroups()) {
      const model::ElementGroup& group = model.groups()[local.group];
      if (group.kind != body.kind) continue;
      LocalBody b;
      b.set = static_cast<int>(s);
      b.stride = local.stride;
      b.group = &local;
      for (int k = 0; k < local.size(); ++k) {
        const int e = local.elements[k];
        if (group.body[e] != set.body) continue;
        b.elements.push_back(k);
        b.index.push_back(group.index[e]);
      }
      const math::QuadratureRule rule = math::gaussLegendre(set.points);
      b.w.resize(static_cast<size_t>(rule.size()) * b.stride);
      for (int g = 0; g < rule.size(); ++g) {
        elements::withKind(body.kind, [&](auto tag) {
          using K = typename decltype(tag)::type;
          K::interpolation(body.discretization, rule.x[g], &b.w[static_cast<size_t>(g) * b.stride]);
        });
        b.weight.push_back(rule.w[g] * body.elementLength);
      }
      b.reach = 2.0 * body.elementLength;
      b.history = _z.size();
      _z.resize(_z.size() + b.elements.size() * set.pulleys.size() * b.weight.size(), 0.0);
      _state.resize(_z.size(), 0);  // none held: the first solve lets the law decide
      _changed.resize(_z.size(), 0);
      _hasHistory |= set.law.friction == contact::FrictionLaw::Bristle;
      if (!b.elements.empty()) _bodies.push_back(std::move(b));
    }
  }
  for (int p = 0; p < static_cast<int>(model.pulleys().size()); ++p) {
    const model::PulleyDesc& d = model.pulleys()[p];
    _slide.push_back(d.hasSlide ? std::array<double, 2>{d.slide.direction[0], d.slide.direction[1]}
                                : std::array<double, 2>{0.0, 0.0});
    const int blk = model.pulleyBlock(p);
    const PetscInt g = blk < 0 ? -1 : dofs.globalBlock()[blk];
    _pulleyGlobal.push_back(g);
    _pulleyLocal.push_back(g < 0 ? -1 : dofs.localBlock(g));
    if (g >= dofs.ownedBegin() && g < dofs.ownedEnd()) _ownedFree.push_back(p);
  }
}

std::vector<contact::PulleyState> PulleyContacts::pulleysAt(double t, const double* x, const double* v) const {
  std::vector<contact::PulleyState> out;
  for (size_t p = 0; p < _model.pulleys().size(); ++p) {
    const model::PulleyDesc& d = _model.pulleys()[p];
    contact::PulleyState s;
    s.radius = d.radius;
    const PetscInt blk = _pulleyLocal[p];
    const double slide = blk >= 0 ? _q0[blk * 2 + 1] + x[blk * 2 + 1] : 0.0;  // a tensioner's x
    const double rate = blk >= 0 && v ? v[blk * 2 + 1] : 0.0;
    for (int i = 0; i < 2; ++i) {  // c = c0 + x e, v_c = x' e
      s.c[i] = d.center[i] + slide * _slide[p][i];
      s.vc[i] = rate * _slide[p][i];
    }
    if (!d.free()) s.omega = d.speed.at(t).f;
    else if (v && blk >= 0) s.omega = v[blk * 2];
    out.push_back(s);
  }
  return out;
}

bool PulleyContacts::mayTouch(const LocalBody& b, int k, const double* x, const contact::PulleyState& p,
                              const contact::ContactLaw& law) const {
  const PetscInt dof = b.group->localBlocksOf(b.elements[k])[0] * 2;  // node 1's position block
  const double dx = _q0[dof] + x[dof] - p.c[0], dy = _q0[dof + 1] + x[dof + 1] - p.c[1];
  const double reach = p.radius + law.offset + b.reach;
  return dx * dx + dy * dy <= reach * reach;
}

void PulleyContacts::pointState(const LocalBody& b, int k, int g, const double* x, const double* v, double* r,
                                double* vel) const {
  const PetscInt* lb = b.group->localBlocksOf(b.elements[k]);
  const double* w = &b.w[static_cast<size_t>(g) * b.stride];
  r[0] = r[1] = vel[0] = vel[1] = 0.0;
  for (int a = 0; a < b.stride; ++a) {
    if (w[a] == 0.0) continue;
    for (int i = 0; i < 2; ++i) {
      const PetscInt dof = lb[a] * 2 + i;
      r[i] += w[a] * (_q0[dof] + x[dof]);
      if (v) vel[i] += w[a] * v[dof];
    }
  }
}

template <class F>
void PulleyContacts::forEachNearPoint(const double* x, const double* v,
                                      const std::vector<contact::PulleyState>& pulleys, F&& f) const {
  std::vector<char> near(pulleys.size(), 0);
  for (const LocalBody& b : _bodies) {
    const model::PulleyContactSet& set = _model.contacts()[b.set];
    for (int k = 0; k < static_cast<int>(b.elements.size()); ++k) {
      bool any = false;
      for (int p : set.pulleys) any |= (near[p] = mayTouch(b, k, x, pulleys[p], set.law));
      if (!any) continue;
      const size_t np = set.pulleys.size(), ng = b.weight.size();
      for (int g = 0; g < static_cast<int>(ng); ++g) {
        double rg[2], vg[2];
        pointState(b, k, g, x, v, rg, vg);
        for (size_t i = 0; i < np; ++i)
          if (near[set.pulleys[i]]) f(b, set, k, g, set.pulleys[i], b.history + (k * np + i) * ng + g, rg, vg);
      }
    }
  }
}

const contact::BristleHistory* PulleyContacts::historyAt(size_t h, double t, contact::BristleHistory* buf) const {
  if (!_hasHistory) return nullptr;
  *buf = {_z[h], t - _tn, _state[h]};
  return buf;
}

void PulleyContacts::residual(const double* x, const double* v, double t, double* r, double scale) const {
  if (_bodies.empty()) return;
  const std::vector<contact::PulleyState> pulleys = pulleysAt(t, x, v);
  forEachNearPoint(x, v, pulleys, [&](const LocalBody& b, const model::PulleyContactSet& set, int k, int g, int p,
                                      size_t h, const double* rg, const double* vg) {
    double f[2];
    contact::BristleHistory buf;
    if (!contact::pointForce(set.law, pulleys[p], rg, vg, f, historyAt(h, t, &buf))) return;
    const PetscInt* lb = b.group->localBlocksOf(b.elements[k]);
    const double* w = &b.w[static_cast<size_t>(g) * b.stride];
    for (int a = 0; a < b.stride; ++a)
      for (int i = 0; i < 2; ++i) r[lb[a] * 2 + i] -= scale * b.weight[g] * w[a] * f[i];
    if (_pulleyLocal[p] >= 0) {  // the belt's torque on a free pulley, and its pull -f along a slide
      const double d[2] = {rg[0] - pulleys[p].c[0], rg[1] - pulleys[p].c[1]};
      r[_pulleyLocal[p] * 2] -= scale * b.weight[g] * torqueOf(d, f);
      r[_pulleyLocal[p] * 2 + 1] += scale * b.weight[g] * (f[0] * _slide[p][0] + f[1] * _slide[p][1]);
    }
  });
}

PetscErrorCode PulleyContacts::jacobian(const double* x, const double* v, double t, double shiftV, Mat J, Mat D,
                                        const std::vector<char>& fixed) const {
  PetscFunctionBeginUser;
  if (_bodies.empty()) PetscFunctionReturn(0);
  const std::vector<contact::PulleyState> pulleys = pulleysAt(t, x, v);
  std::vector<double> Kj, Kd;
  std::vector<PulleyCoupling> coupling(pulleys.size());  // per free pulley, this element's entries
  std::vector<char> near(pulleys.size(), 0);
  for (const LocalBody& b : _bodies) {
    const model::PulleyContactSet& set = _model.contacts()[b.set];
    const int n = b.stride * 2;
    const size_t np = set.pulleys.size(), ng = b.weight.size();
    for (int k = 0; k < static_cast<int>(b.elements.size()); ++k) {
      bool touching = false, nearAny = false;
      for (int p : set.pulleys) nearAny |= (near[p] = mayTouch(b, k, x, pulleys[p], set.law));
      if (nearAny || D) {
        Kj.assign(static_cast<size_t>(n) * n, 0.0);
        Kd.assign(static_cast<size_t>(n) * n, 0.0);
      }
      for (int p : set.pulleys)
        if (_pulleyLocal[p] >= 0) coupling[p].zero(n);
      for (int g = 0; g < static_cast<int>(b.weight.size()) && nearAny; ++g) {
        double rg[2], vg[2];
        pointState(b, k, g, x, v, rg, vg);
        const double* w = &b.w[static_cast<size_t>(g) * b.stride];
        const double W = b.weight[g];
        for (size_t li = 0; li < np; ++li) {
          const int p = set.pulleys[li];
          double f[2], dr[4], dv[4], dw[2];
          contact::BristleHistory buf;
          const contact::BristleHistory* h = historyAt(b.history + (k * np + li) * ng + g, t, &buf);
          if (!near[p] || !contact::pointTangent(set.law, pulleys[p], rg, vg, f, dr, dv, dw, h).closed) continue;
          touching = true;
          for (int a = 0; a < b.stride; ++a)
            for (int c = 0; c < b.stride; ++c) {
              const double s = W * w[a] * w[c];
              if (s == 0.0) continue;
              for (int i = 0; i < 2; ++i)
                for (int j = 0; j < 2; ++j) {
                  const size_t at = static_cast<size_t>(a * 2 + i) * n + c * 2 + j;
                  Kj[at] -= s * (dr[i * 2 + j] + shiftV * dv[i * 2 + j]);
                  Kd[at] -= s * dv[i * 2 + j];
                }
            }
          if (_pulleyLocal[p] < 0) continue;
          PulleyCoupling& cp = coupling[p];
          const double d[2] = {rg[0] - pulleys[p].c[0], rg[1] - pulleys[p].c[1]};
          const PointTorque tq = pointTorque(d, f, dr, dv, dw);
          // the slide: c = c0 + x e moves d = r - c by -x e and u = v - v_c by -x' e, so
          // df/dx = -df/dd e, df/dx' = -df/du e; the slide's generalized force is Q_x = -f.e
          const double* e = _slide[p].data();
          double dre[2], dve[2], edr[2], edv[2];  // df/dd e, df/du e, e^T df/dd, e^T df/du
          for (int i = 0; i < 2; ++i) {
            dre[i] = dr[i * 2] * e[0] + dr[i * 2 + 1] * e[1];
            dve[i] = dv[i * 2] * e[0] + dv[i * 2 + 1] * e[1];
            edr[i] = e[0] * dr[i] + e[1] * dr[2 + i];
            edv[i] = e[0] * dv[i] + e[1] * dv[2 + i];
          }
          const size_t n2 = static_cast<size_t>(n);
          for (int a = 0; a < b.stride; ++a)
            for (int i = 0; i < 2; ++i) {
              const size_t row = static_cast<size_t>(a * 2 + i) * 2;
              // belt row (a, i), phi column: -dQ/domega (a velocity); x column: -dQ/dx - shiftV dQ/dx'
              cp.colJ[row] -= W * w[a] * shiftV * dw[i];
              cp.colD[row] -= W * w[a] * dw[i];
              cp.colJ[row + 1] += W * w[a] * (dre[i] + shiftV * dve[i]);
              cp.colD[row + 1] += W * w[a] * dve[i];
              // phi row, belt column (a, i): -dtau/dq - shiftV dtau/dv; x row: -dQ_x/dq - shiftV dQ_x/dv
              cp.rowJ[a * 2 + i] -= W * w[a] * (tq.dr[i] + shiftV * tq.dv[i]);
              cp.rowD[a * 2 + i] -= W * w[a] * tq.dv[i];
              cp.rowJ[n2 + a * 2 + i] += W * w[a] * (edr[i] + shiftV * edv[i]);
              cp.rowD[n2 + a * 2 + i] += W * w[a] * edv[i];
            }
          const double tqe = tq.dr[0] * e[0] + tq.dr[1] * e[1], tqve = tq.dv[0] * e[0] + tq.dv[1] * e[1];
          const double edw = e[0] * dw[0] + e[1] * dw[1];
          const double ere = e[0] * dre[0] + e[1] * dre[1], eve = e[0] * dve[0] + e[1] * dve[1];
          cp.selfJ[0] -= W * shiftV * tq.domega;  // (phi, phi)
          cp.selfD[0] -= W * tq.domega;
          cp.selfJ[1] += W * (tqe + shiftV * tqve);  // (phi, x): dtau/dx = -dtau/dd e
          cp.selfD[1] += W * tqve;
          cp.selfJ[2] += W * shiftV * edw;  // (x, phi): dQ_x/domega = -e.df/domega
          cp.selfD[2] += W * edw;
          cp.selfJ[3] -= W * (ere + shiftV * eve);  // (x, x): dQ_x/dx = e^T df/dd e
          cp.selfD[3] -= W * eve;
        }
      }
      const PetscInt* lb = b.group->localBlocksOf(b.elements[k]);
      const PetscInt* gb = b.group->globalBlocksOf(b.elements[k]);
      auto isFixed = [&](int a) { return fixed[lb[a / 2] * 2 + a % 2] != 0; };
      if (touching) {
        for (int a = 0; a < n; ++a)
          for (int c = 0; c < n; ++c)
            if (isFixed(a) || isFixed(c)) Kj[static_cast<size_t>(a) * n + c] = Kd[static_cast<size_t>(a) * n + c] = 0.0;
        PetscCall(MatSetValuesBlocked(J, b.stride, gb, b.stride, gb, Kj.data(), ADD_VALUES));
      }
      // D holds no element terms of its own without Kelvin-Voigt damping: every element's block is
      // inserted, zeros where it does not touch, or assembly squeezes the slots out and a later
      // contact finds no room (J has the elements' stiffness there)
      if (D) PetscCall(MatSetValuesBlocked(D, b.stride, gb, b.stride, gb, Kd.data(), ADD_VALUES));
      // every element's couplings to the free pulleys are inserted, zeros where it does not touch:
      // assembly squeezes out unused slots, and a later contact would find no room
      for (int p : set.pulleys) {
        if (_pulleyLocal[p] < 0) continue;
        PulleyCoupling& cp = coupling[p];
        for (int a = 0; a < n; ++a)
          if (isFixed(a))
            for (int c = 0; c < 2; ++c) cp.colJ[a * 2 + c] = cp.colD[a * 2 + c] = cp.rowJ[c * n + a] = cp.rowD[c * n + a] = 0.0;
        PetscCall(insertCoupling(J, D, b.stride, gb, _pulleyGlobal[p], cp));
      }
    }
  }
  PetscFunctionReturn(0);
}

void PulleyContacts::pulleyResidual(const double* x, const double* v, double* r) const {
  for (int p : _ownedFree) {
    const model::PulleyDesc& d = _model.pulleys()[p];
    const PetscInt at = _pulleyLocal[p] * 2;
    if (v) r[at] += d.damping * v[at];
    if (d.hasSlide) r[at + 1] += d.slide.stiffness * (_q0[at + 1] + x[at + 1]) + (v ? d.slide.damping * v[at + 1] : 0.0);
  }
}

PetscErrorCode PulleyContacts::pulleyMatrices(double shiftV, double shiftA, Mat J, Mat D) const {
  PetscFunctionBeginUser;
  for (int p : _ownedFree) {
    const model::PulleyDesc& d = _model.pulleys()[p];
    const PetscInt g = _pulleyGlobal[p] * 2;
    if (J) PetscCall(MatSetValue(J, g, g, shiftV * d.damping + shiftA * d.inertia, ADD_VALUES));
    if (D) PetscCall(MatSetValue(D, g, g, d.damping, ADD_VALUES));
    if (!d.hasSlide) continue;
    const model::SlideDesc& s = d.slide;
    if (J) PetscCall(MatSetValue(J, g + 1, g + 1, s.stiffness + shiftV * s.damping + shiftA * s.mass, ADD_VALUES));
    if (D) PetscCall(MatSetValue(D, g + 1, g + 1, s.damping, ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode PulleyContacts::mass(Mat M) const {
  PetscFunctionBeginUser;
  for (int p : _ownedFree) {
    const model::PulleyDesc& d = _model.pulleys()[p];
    const PetscInt g = _pulleyGlobal[p] * 2;
    PetscCall(MatSetValue(M, g, g, d.inertia, ADD_VALUES));
    if (d.hasSlide) PetscCall(MatSetValue(M, g + 1, g + 1, d.slide.mass, ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

double PulleyContacts::springEnergy(const double* x) const {
  double U = 0.0;
  for (int p : _ownedFree) {
    const model::PulleyDesc& d = _model.pulleys()[p];
    const PetscInt at = _pulleyLocal[p] * 2 + 1;
    const double slide = _q0[at] + x[at];
    if (d.hasSlide) U += 0.5 * d.slide.stiffness * slide * slide;
  }
  return U;
}

void PulleyContacts::pulleyLoads(const double* x, const double* v, double t, double* load) const {
  const std::vector<contact::PulleyState> pulleys = pulleysAt(t, x, v);
  forEachNearPoint(x, v, pulleys, [&](const LocalBody& b, const model::PulleyContactSet& set, int, int g, int p,
                                      size_t h, const double* rg, const double* vg) {
    double f[2];
    contact::BristleHistory buf;
    if (!contact::pointForce(set.law, pulleys[p], rg, vg, f, historyAt(h, t, &buf))) return;
    const double d[2] = {rg[0] - pulleys[p].c[0], rg[1] - pulleys[p].c[1]};
    load[kLoadStride * p] -= b.weight[g] * f[0];
    load[kLoadStride * p + 1] -= b.weight[g] * f[1];
    load[kLoadStride * p + 2] += b.weight[g] * torqueOf(d, f);
  });
  for (int p : _ownedFree) {
    load[kLoadStride * p + 3] += pulleys[p].omega;
    load[kLoadStride * p + 4] += _q0[_pulleyLocal[p] * 2 + 1] + x[_pulleyLocal[p] * 2 + 1];
  }
}

void PulleyContacts::points(const double* x, const double* v, double t,
                            std::vector<Assembler::ContactPointOut>& out) const {
  const std::vector<contact::PulleyState> pulleys = pulleysAt(t, x, v);
  forEachNearPoint(x, v, pulleys, [&](const LocalBody& b, const model::PulleyContactSet& set, int k, int g, int p,
                                      size_t h, const double* rg, const double* vg) {
    double f[2], dr[4], dv[4], dw[2];
    contact::BristleHistory buf;
    out.push_back({set.body, b.index[k], p, g, {rg[0], rg[1]},
                   contact::pointTangent(set.law, pulleys[p], rg, vg, f, dr, dv, dw, historyAt(h, t, &buf))});
  });
}

void PulleyContacts::energy(const double* x, const double* v, double t, double* stored, double* power) const {
  const std::vector<contact::PulleyState> pulleys = pulleysAt(t, x, v);
  const double still[2] = {0.0, 0.0};
  forEachNearPoint(x, v, pulleys, [&](const LocalBody& b, const model::PulleyContactSet& set, int, int g, int p,
                                      size_t h, const double* rg, const double* vg) {
    contact::BristleHistory buf;
    const contact::PointEnergy e = contact::pointEnergy(set.law, pulleys[p], rg, v ? vg : still,
                                                        !_model.pulleys()[p].free(), historyAt(h, t, &buf));
    *stored += b.weight[g] * e.stored;
    *power += b.weight[g] * e.power;
  });
}

void PulleyContacts::commit(const double* x, const double* v, double t) {
  if (_hasHistory) {
    const std::vector<contact::PulleyState> pulleys = pulleysAt(t, x, v);
    std::vector<double> z(_z.size(), 0.0);  // off contact: relaxed
    forEachNearPoint(x, v, pulleys, [&](const LocalBody&, const model::PulleyContactSet& set, int, int, int p,
                                        size_t h, const double* rg, const double* vg) {
      if (set.law.friction != contact::FrictionLaw::Bristle) return;
      double f[2], dr[4], dv[4], dw[2];
      contact::BristleHistory buf;
      const contact::ContactPoint c =
          contact::pointTangent(set.law, pulleys[p], rg, vg, f, dr, dv, dw, historyAt(h, t, &buf));
      if (c.touching) z[h] = -c.friction / set.law.tangentialStiffness;
    });
    _z.swap(z);
  }
  std::fill(_changed.begin(), _changed.end(), 0);  // a new step: no change seen yet
  _changedAnywhere = false;
  _tn = t;
}

int PulleyContacts::settle(const double* x, const double* v, double t, bool release) {
  if (!_hasHistory) return 0;
  if (release) {  // the law decides at the points that changed at the last settle (all if none did, on any rank)
    for (size_t h = 0; h < _state.size(); ++h)
      if (!_changedAnywhere || _changed[h]) _state[h] = 0;
    _changedAnywhere = false;
    std::fill(_changed.begin(), _changed.end(), 0);
    return 0;
  }
  const std::vector<contact::PulleyState> pulleys = pulleysAt(t, x, v);
  std::vector<signed char> state(_state.size(), 0);  // off contact: as the law decides when it lands
  std::fill(_changed.begin(), _changed.end(), 0);
  int changed = 0;
  forEachNearPoint(x, v, pulleys, [&](const LocalBody&, const model::PulleyContactSet& set, int, int, int p,
                                      size_t h, const double* rg, const double* vg) {
    if (set.law.friction != contact::FrictionLaw::Bristle) return;
    double f[2], dr[4], dv[4], dw[2];
    const contact::BristleHistory free = {_z[h], t - _tn, 0};  // none held: the law's own state
    const contact::ContactPoint c = contact::pointTangent(set.law, pulleys[p], rg, vg, f, dr, dv, dw, &free);
    if (!c.touching) return;
    const double limit = set.law.mu * c.pressure;
    state[h] = static_cast<signed char>(c.sticking ? 1 : (c.friction > 0.0 ? 2 : 3));  // the law's own
    if (_state[h] == 0 || _state[h] == state[h]) return;
    // a point whose held state's force is within kSettleTolerance mu p of the law's keeps it: at
    // the cone's edge the two states give the same solution, and flipping it would cycle
    const double held = _state[h] == 1 ? c.trial : (_state[h] == 2 ? limit : -limit);
    if (std::abs(held - c.friction) <= kSettleTolerance * limit) {
      state[h] = _state[h];
    } else {
      _changed[h] = 1;
      ++changed;
    }
  });
  _state.swap(state);
  return changed;
}

std::vector<PulleyContacts::HistoryEntry> PulleyContacts::history() const {
  std::vector<HistoryEntry> out;
  for (const LocalBody& b : _bodies) {
    const model::PulleyContactSet& set = _model.contacts()[b.set];
    const size_t np = set.pulleys.size(), ng = b.weight.size();
    for (size_t k = 0; k < b.elements.size(); ++k)
      for (size_t i = 0; i < np; ++i)
        for (size_t g = 0; g < ng; ++g) {
          const double z = _z[b.history + (k * np + i) * ng + g];
          if (z != 0.0) out.push_back({set.body, b.index[k], set.pulleys[i], static_cast<int>(g), z});
        }
  }
  return out;
}

void PulleyContacts::restore(const std::vector<HistoryEntry>& entries, double tn) {
  std::fill(_z.begin(), _z.end(), 0.0);
  _tn = tn;
  for (const LocalBody& b : _bodies) {
    const model::PulleyContactSet& set = _model.contacts()[b.set];
    const size_t np = set.pulleys.size(), ng = b.weight.size();
    std::vector<int> at;  // body element index -> k
    for (size_t k = 0; k < b.elements.size(); ++k) {
      if (b.index[k] >= static_cast<int>(at.size())) at.resize(b.index[k] + 1, -1);
      at[b.index[k]] = static_cast<int>(k);
    }
    for (const HistoryEntry& e : entries) {
      if (e.body != set.body || e.element >= static_cast<int>(at.size()) || at[e.element] < 0) continue;
      const auto i = std::find(set.pulleys.begin(), set.pulleys.end(), e.pulley) - set.pulleys.begin();
      if (i == static_cast<long>(np) || e.point >= static_cast<int>(ng)) continue;
      _z[b.history + (at[e.element] * np + i) * ng + e.point] = e.z;
    }
  }
}

}  // namespace strand::assembly
