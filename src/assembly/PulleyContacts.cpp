#include "PulleyContacts.hpp"

#include <algorithm>

#include "strand/elements/ElementKinds.hpp"
#include "strand/math/Gauss.hpp"

namespace strand::assembly {

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
      if (!b.elements.empty()) _bodies.push_back(std::move(b));
    }
  }
}

std::vector<contact::PulleyState> PulleyContacts::pulleysAt(double t) const {
  std::vector<contact::PulleyState> out;
  for (const model::PulleyDesc& p : _model.pulleys()) {
    contact::PulleyState s;
    s.c[0] = p.center[0];
    s.c[1] = p.center[1];
    s.omega = p.speed.at(t).f;
    s.radius = p.radius;
    out.push_back(s);
  }
  return out;
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

void PulleyContacts::residual(const double* x, const double* v, double t, double* r, double scale) const {
  if (_bodies.empty()) return;
  const std::vector<contact::PulleyState> pulleys = pulleysAt(t);
  for (const LocalBody& b : _bodies) {
    const model::PulleyContactSet& set = _model.contacts()[b.set];
    const int points = static_cast<int>(b.weight.size());
    for (int k = 0; k < static_cast<int>(b.elements.size()); ++k) {
      const PetscInt* lb = b.group->localBlocksOf(b.elements[k]);
      for (int g = 0; g < points; ++g) {
        double rg[2], vg[2];
        pointState(b, k, g, x, v, rg, vg);
        for (int p : set.pulleys) {
          double f[2];
          if (!contact::pointForce(set.law, pulleys[p], rg, vg, f)) continue;
          const double* w = &b.w[static_cast<size_t>(g) * b.stride];
          for (int a = 0; a < b.stride; ++a)
            for (int i = 0; i < 2; ++i) r[lb[a] * 2 + i] -= scale * b.weight[g] * w[a] * f[i];
        }
      }
    }
  }
}

PetscErrorCode PulleyContacts::jacobian(const double* x, const double* v, double t, double shiftV, Mat J, Mat D,
                                        const std::vector<char>& fixed) const {
  PetscFunctionBeginUser;
  if (_bodies.empty()) PetscFunctionReturn(0);
  const std::vector<contact::PulleyState> pulleys = pulleysAt(t);
  std::vector<double> Kj, Kd;
  for (const LocalBody& b : _bodies) {
    const model::PulleyContactSet& set = _model.contacts()[b.set];
    const int points = static_cast<int>(b.weight.size()), n = b.stride * 2;
    Kj.assign(static_cast<size_t>(n) * n, 0.0);
    Kd.assign(static_cast<size_t>(n) * n, 0.0);
    for (int k = 0; k < static_cast<int>(b.elements.size()); ++k) {
      bool touching = false;
      for (int g = 0; g < points; ++g) {
        double rg[2], vg[2];
        pointState(b, k, g, x, v, rg, vg);
        for (int p : set.pulleys) {
          double f[2], dr[4], dv[4], dw[2];
          if (!contact::pointTangent(set.law, pulleys[p], rg, vg, f, dr, dv, dw).closed) continue;
          if (!touching) {
            std::fill(Kj.begin(), Kj.end(), 0.0);
            std::fill(Kd.begin(), Kd.end(), 0.0);
            touching = true;
          }
          const double* w = &b.w[static_cast<size_t>(g) * b.stride];
          for (int a = 0; a < b.stride; ++a)
            for (int c = 0; c < b.stride; ++c) {
              const double s = b.weight[g] * w[a] * w[c];
              if (s == 0.0) continue;
              for (int i = 0; i < 2; ++i)
                for (int j = 0; j < 2; ++j) {
                  const size_t at = static_cast<size_t>(a * 2 + i) * n + c * 2 + j;
                  Kj[at] -= s * (dr[i * 2 + j] + shiftV * dv[i * 2 + j]);
                  Kd[at] -= s * dv[i * 2 + j];
                }
            }
        }
      }
      if (!touching) continue;
      const PetscInt* lb = b.group->localBlocksOf(b.elements[k]);
      for (int a = 0; a < n; ++a)
        for (int c = 0; c < n; ++c)
          if (fixed[lb[a / 2] * 2 + a % 2] || fixed[lb[c / 2] * 2 + c % 2])
            Kj[static_cast<size_t>(a) * n + c] = Kd[static_cast<size_t>(a) * n + c] = 0.0;
      const PetscInt* gb = b.group->globalBlocksOf(b.elements[k]);
      PetscCall(MatSetValuesBlocked(J, b.stride, gb, b.stride, gb, Kj.data(), ADD_VALUES));
      if (D) PetscCall(MatSetValuesBlocked(D, b.stride, gb, b.stride, gb, Kd.data(), ADD_VALUES));
    }
  }
  PetscFunctionReturn(0);
}

void PulleyContacts::pulleyLoads(const double* x, const double* v, double t, double* load) const {
  const std::vector<contact::PulleyState> pulleys = pulleysAt(t);
  for (const LocalBody& b : _bodies) {
    const model::PulleyContactSet& set = _model.contacts()[b.set];
    for (int k = 0; k < static_cast<int>(b.elements.size()); ++k)
      for (int g = 0; g < static_cast<int>(b.weight.size()); ++g) {
        double rg[2], vg[2];
        pointState(b, k, g, x, v, rg, vg);
        for (int p : set.pulleys) {
          double f[2];
          if (!contact::pointForce(set.law, pulleys[p], rg, vg, f)) continue;
          const double d[2] = {rg[0] - pulleys[p].c[0], rg[1] - pulleys[p].c[1]};
          load[3 * p] -= b.weight[g] * f[0];
          load[3 * p + 1] -= b.weight[g] * f[1];
          load[3 * p + 2] -= b.weight[g] * (d[0] * f[1] - d[1] * f[0]);
        }
      }
  }
}

std::vector<PulleyContacts::PointState> PulleyContacts::points(const double* x, const double* v, double t) const {
  std::vector<PointState> out;
  const std::vector<contact::PulleyState> pulleys = pulleysAt(t);
  for (const LocalBody& b : _bodies) {
    const model::PulleyContactSet& set = _model.contacts()[b.set];
    for (int k = 0; k < static_cast<int>(b.elements.size()); ++k)
      for (int g = 0; g < static_cast<int>(b.weight.size()); ++g) {
        double rg[2], vg[2];
        pointState(b, k, g, x, v, rg, vg);
        for (int p : set.pulleys) {
          double f[2], dr[4], dv[4], dw[2];
          out.push_back({set.body, b.index[k], p, g, {rg[0], rg[1]},
                         contact::pointTangent(set.law, pulleys[p], rg, vg, f, dr, dv, dw)});
        }
      }
  }
  return out;
}

}  // namespace strand::assembly
