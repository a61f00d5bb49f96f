#include "strand/solvers/Sweep.hpp"

#include <cmath>
#include <memory>

#include "strand/elements/ElementRegistry.hpp"
#include "strand/solvers/ModalSolver.hpp"
#include "strand/solvers/ModeLabels.hpp"
#include "strand/solvers/Problem.hpp"
#include "strand/solvers/StaticSolver.hpp"

namespace strand::solvers {

namespace {

const char* parameterName(model::SweepParameter p) {
  switch (p) {
    case model::SweepParameter::Gamma: return "gamma";
    case model::SweepParameter::Omega: return "omega";
    case model::SweepParameter::MassRatio: return "mass_ratio";
    case model::SweepParameter::TransportSpeed: return "transport_speed";
    default: return "mass_location";
  }
}

// A mode shape x = xr + i xi and M x, kept for MAC values between any two points.
struct StoredShape {
  Vec xr = nullptr, xi = nullptr, mr = nullptr, mi = nullptr;
  double norm2 = 0.0;  // x^H M x
};

PetscErrorCode storeShape(Mat M, Vec xr, Vec xi, StoredShape* s) {
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(xr, &s->xr));
  PetscCall(VecCopy(xr, s->xr));
  PetscCall(VecDuplicate(xr, &s->mr));
  PetscCall(MatMult(M, xr, s->mr));
  if (xi) {
    PetscCall(VecDuplicate(xi, &s->xi));
    PetscCall(VecCopy(xi, s->xi));
    PetscCall(VecDuplicate(xi, &s->mi));
    PetscCall(MatMult(M, xi, s->mi));
  }
  PetscScalar a = 0.0, b = 0.0;
  PetscCall(VecDot(s->xr, s->mr, &a));
  if (xi) PetscCall(VecDot(s->xi, s->mi, &b));
  s->norm2 = a + b;
  PetscFunctionReturn(0);
}

// MAC of every shape of `prev` with every shape of `next` (row-major prev x next): four
// multi-dot products per shape of `next` instead of eight dots per pair.
PetscErrorCode macTable(const std::vector<StoredShape>& prev, const std::vector<StoredShape>& next,
                        std::vector<double>* out) {
  PetscFunctionBeginUser;
  const PetscInt n = static_cast<PetscInt>(prev.size());
  const bool complex = !prev.empty() && prev[0].xi && !next.empty() && next[0].xi;
  std::vector<Vec> pr(n), pi(n);
  for (PetscInt a = 0; a < n; ++a) pr[a] = prev[a].xr, pi[a] = prev[a].xi;
  std::vector<PetscScalar> rr(n), ii(n, 0.0), ri(n, 0.0), ir(n, 0.0);
  out->assign(prev.size() * next.size(), 0.0);
  for (size_t b = 0; b < next.size(); ++b) {
    PetscCall(VecMDot(next[b].mr, n, pr.data(), rr.data()));  // x_r^T M y_r (M symmetric)
    if (complex) {
      PetscCall(VecMDot(next[b].mi, n, pi.data(), ii.data()));
      PetscCall(VecMDot(next[b].mi, n, pr.data(), ri.data()));
      PetscCall(VecMDot(next[b].mr, n, pi.data(), ir.data()));
    }
    for (PetscInt a = 0; a < n; ++a) {
      const double re = rr[a] + ii[a], im = ri[a] - ir[a];
      (*out)[a * next.size() + b] = (re * re + im * im) / (prev[a].norm2 * next[b].norm2);
    }
  }
  PetscFunctionReturn(0);
}

// |x^H M y|^2 / ((x^H M x)(y^H M y)) for complex x, y stored as real and imaginary parts.
double mac(const StoredShape& x, const StoredShape& y) {
  auto dot = [](Vec a, Vec b) {
    PetscScalar d = 0.0;
    if (a && b) VecDot(a, b, &d);
    return static_cast<double>(d);
  };
  const double re = dot(x.xr, y.mr) + dot(x.xi, y.mi), im = dot(x.xr, y.mi) - dot(x.xi, y.mr);
  return (re * re + im * im) / (x.norm2 * y.norm2);
}

// Vibration nodes of a mode shape on body 0: interior zeros of its dominant displacement component
// w(x), as x / L. Within each element w is the kind's centerline interpolant (the cable's cubic
// Hermite of the nodal values and slopes, seed 003 Eq. 69-71), so the nodes converge like the shape
// (h^4 for the cable), not like a chord (h^2).
// Elements whose end values differ in sign are searched: 8 sub-intervals bracket the zero, which
// is then bisected. (Two zeros inside one element, with equal end signs, mean a mesh too coarse
// for that mode and are not reported.)
std::vector<double> vibrationNodes(const model::Model& m, const std::vector<double>& disp) {
  const model::Body& b = m.bodies()[0];
  const int d = m.dim();
  double e[3] = {0, 0, 0};
  for (int pb : b.posBlock)
    for (int i = 0; i < d; ++i) e[i] += disp[pb * d + i] * disp[pb * d + i];
  int c = 0;
  for (int i = 1; i < d; ++i)
    if (e[i] > e[c]) c = i;
  double amax = 0.0;
  for (int pb : b.posBlock) amax = std::max(amax, std::fabs(disp[pb * d + c]));
  std::vector<double> nodes;
  const double tiny = 1e-8 * amax;
  for (int n = 0; n < b.elements; ++n) {
    const double w1 = disp[b.posBlock[n] * d + c], w2 = disp[b.posBlock[n + 1] * d + c];
    if ((w1 > 0) == (w2 > 0) && std::fabs(w1) >= tiny && std::fabs(w2) >= tiny) continue;
    auto w = [&](double eta) {
      double weight[elements::kMaxBlocksPerElement], sum = 0.0;
      b.info().interpolation(b.discretization, eta, weight);
      for (int a = 0; a < 2 * b.blocksPerNode; ++a) sum += weight[a] * disp[b.nodeBlocks[n * b.blocksPerNode + a] * d + c];
      return sum;
    };
    constexpr int kSub = 8;
    for (int j = 0; j < kSub; ++j) {
      double a = double(j) / kSub, z = double(j + 1) / kSub, fa = w(a), fz = w(z);
      if (std::fabs(fa) < tiny || std::fabs(fz) < tiny || (fa > 0) == (fz > 0)) continue;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (a + z), fm = w(mid);
        if ((fm > 0) == (fa > 0)) a = mid, fa = fm;
        else z = mid;
      }
      nodes.push_back((n + 0.5 * (a + z)) / b.elements);
    }
  }
  return nodes;
}

// Position displacements of body 0's nodes, node by node (dim values each).
std::vector<double> bodyDisplacements(const model::Model& m, const std::vector<double>& disp) {
  std::vector<double> out;
  for (int pb : m.bodies()[0].posBlock)
    for (int c = 0; c < m.dim(); ++c) out.push_back(disp[pb * m.dim() + c]);
  return out;
}

// Each event is re-measured by a local sweep of `refine` + 1 points between the points where its
// shapes were compared: a coarse grid overestimates the minimum gap and, landing beside the closest
// approach, can see pure shapes at a veering and call it a crossing.
PetscErrorCode refineEvents(MPI_Comm comm, const model::SceneDescription& scene, SweepResult* out) {
  PetscFunctionBeginUser;
  for (LociEvent& e : out->events) {
    model::SceneDescription sub = scene;
    sub.sweep.from = out->parameter[e.left];
    sub.sweep.to = out->parameter[e.right];
    sub.sweep.points = scene.sweep.refine + 1;
    sub.sweep.refine = 0;
    SweepResult local;
    PetscCall(runSweep(comm, sub, &local));
    const LociEvent* best = nullptr;
    for (const LociEvent& f : local.events)
      if (f.lower == e.lower && (!best || f.gap < best->gap)) best = &f;
    if (!local.failure.empty() || !best) continue;  // keep the coarse numbers
    e.parameter = best->parameter;
    e.gap = best->gap;
    e.frequency = best->frequency;
    e.mixing = std::min(e.mixing, best->mixing);
    e.kind = e.mixing < 0.9 ? "veering" : "crossing";
    e.refined = true;
  }
  PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode runSweep(MPI_Comm comm, const model::SceneDescription& scene, SweepResult* out,
                        const SweepProgress& progress, const std::function<bool()>& stop) {
  PetscFunctionBeginUser;
  const model::SweepDesc& sw = scene.sweep;
  const bool speedSweep = sw.parameter == model::SweepParameter::Gamma || sw.parameter == model::SweepParameter::Omega;
  const double t0 = MPI_Wtime();
  out->parameterName = parameterName(sw.parameter);
  const ModalOptions opt = modalOptions(scene.modes);
  const double length = model::Model(scene).bodies()[0].length;  // of the body carrying the swept mass

  std::unique_ptr<Problem> problem;
  std::unique_ptr<ModalSolver> modal;
  Vec X = nullptr;
  Vec Xold = nullptr;           // steady state of the point before the last, for the predictor
  double sOld = 0.0, sCur = 0.0;  // continuation variable at the last two points
  Mat Mmac = nullptr;  // fixed inner product for MAC: the mass matrix of the first point
  std::vector<std::vector<StoredShape>> stored;
  for (int i = 0; i < sw.points; ++i) {
    const double p = sw.from + (sw.to - sw.from) * i / (sw.points - 1);
    if (!problem || !speedSweep) {
      model::SceneDescription sc = scene;
      if (sw.parameter == model::SweepParameter::TransportSpeed) {
        for (model::BodyDesc& b : sc.bodies)
          if (!elements::kindInfo(b.kind).constantMass) {
            b.hasMaterialMotion = true;
            b.materialMotion = model::TimeFunction{};
            b.materialMotion.kind = model::TimeFunction::Kind::Linear;
            b.materialMotion.rate = -p / b.initialStretch;
          }
      } else if (!speedSweep) {
        model::PointMassDesc& pm = sc.bodies[0].pointMasses[sw.mass];
        const model::BodyDesc& b = sc.bodies[0];
        if (sw.parameter == model::SweepParameter::MassRatio)
          pm.mass = p * elements::kindInfo(b.kind).properties(b.section).rhoA * length;
        else pm.at = p * length;
      }
      std::unique_ptr<Problem> next = std::make_unique<Problem>(comm, sc);
      Vec Xn;
      PetscCall(next->dofs().createVector(&Xn));
      if (X) PetscCall(VecCopy(X, Xn));  // same mesh and partition: warm start
      else PetscCall(next->assembler().initialState(Xn));
      PetscCall(VecDestroy(&X));
      X = Xn;
      modal.reset();
      problem = std::move(next);
      modal = std::make_unique<ModalSolver>(problem->assembler(), opt);
      if (!Mmac) {
        PetscCall(problem->dofs().createMatrix(&Mmac, "sweep_", MATAIJ));
        PetscCall(problem->assembler().massMatrixAt(X, Mmac));  // with the ALE kinds' mass
      }
    }
    const double T = problem->model().scales().time();
    double omega = problem->model().rotation().omega;
    if (sw.parameter == model::SweepParameter::Gamma) omega = p / T;
    if (sw.parameter == model::SweepParameter::Omega) omega = p;
    problem->setAngularSpeed(omega);
    // Secant predictor in s = Omega^2 (the centrifugal load is linear in it) or in the mass
    // parameter: X <- X_i-1 + (s - s_i-1) / (s_i-1 - s_i-2) (X_i-1 - X_i-2). Newton then needs
    // one or two iterations instead of three or four (docs/performance.md).
    const double s = speedSweep ? omega * omega : p;
    if (i >= 2 && sCur != sOld) {
      Vec D;
      PetscCall(VecDuplicate(X, &D));
      PetscCall(VecWAXPY(D, -1.0, Xold, X));
      PetscCall(VecCopy(X, Xold));
      PetscCall(VecAXPY(X, (s - sCur) / (sCur - sOld), D));
      PetscCall(VecDestroy(&D));
    } else if (i >= 1) {
      if (!Xold) PetscCall(VecDuplicate(X, &Xold));
      PetscCall(VecCopy(X, Xold));
    }
    sOld = sCur;
    sCur = s;
    {
      StaticSolver steady(problem->assembler(), i == 0 ? scene.statics.loadSteps : 1);
      PetscCall(steady.setFromOptions());
      PetscCall(steady.solve(X, nullptr, &out->failure));
    }
    if (!out->failure.empty()) {
      out->failure = "sweep point " + std::to_string(i) + " (" + out->parameterName + " = " + std::to_string(p) +
                     "): " + out->failure;
      break;
    }
    ModalResult r;
    PetscCall(modal->solve(X, &r));
    if (sw.parameter == model::SweepParameter::TransportSpeed && p > 0.0 && std::isnan(out->criticalSpeed)) {
      double s = 0.0;  // a straight span's K_e and K_q / v^2 do not change with v: once is enough (a curved
                       // span's do: NaN, none reported, ModalSolver::divergenceFactor)
      PetscCall(modal->divergenceFactor(&s));
      out->criticalSpeed = s * p;
    }
    out->method = r.method;
    std::vector<ModeLabel> labels;
    PetscCall(labelModes(problem->assembler(), modal->massMatrix(), r, &labels));
    out->kind.emplace_back();
    for (const ModeLabel& l : labels) out->kind.back().push_back(l.name);
    out->maxRealPart = std::max(out->maxRealPart, r.maxRealPart);
    out->parameter.push_back(p);
    out->gamma.push_back(omega * T);
    std::vector<double> wb;
    for (double w : r.omega) wb.push_back(w * T);
    out->omega.push_back(r.omega);
    out->omegaBar.push_back(wb);
    out->residual.push_back(r.relativeResidual);
    std::vector<StoredShape> here(r.omega.size());
    std::vector<std::vector<double>> nodes, shapes;
    const auto& q0 = problem->model().initialCoordinates();
    for (size_t k = 0; k < r.omega.size(); ++k) {
      PetscCall(storeShape(Mmac, r.shapes[k], r.shapesImag.empty() ? nullptr : r.shapesImag[k], &here[k]));
      std::vector<double> q;  // q0 + shape, rank 0 only
      PetscCall(problem->assembler().gatherToRoot(r.shapes[k], q));
      if (q.empty()) {
        nodes.emplace_back();
        shapes.emplace_back();
        continue;
      }
      for (size_t j = 0; j < q.size(); ++j) q[j] -= q0[j];
      nodes.push_back(vibrationNodes(problem->model(), q));
      shapes.push_back(bodyDisplacements(problem->model(), q));
    }
    out->nodes.push_back(nodes);
    out->shapes.push_back(shapes);
    if (!stored.empty()) {
      std::vector<double> m;
      PetscCall(macTable(stored.back(), here, &m));
      out->macNext.push_back(m);
    }
    stored.push_back(here);
    destroyModes(&r);
    if (progress) progress(i, *out);
    if (stop && i + 1 < sw.points) {  // every rank ends after the same point
      int halt = stop() ? 1 : 0;
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &halt, 1, MPI_INT, MPI_MAX, comm));
      if (halt) {
        out->stopped = true;
        break;
      }
    }
  }
  const int count = out->omega.empty() ? 0 : static_cast<int>(out->omega[0].size());
  bool uniform = true;
  for (const auto& w : out->omega) uniform = uniform && static_cast<int>(w.size()) == count;
  if (uniform && count > 0) {
    out->label = trackModes(out->macNext, count);
    out->events = detectLociEvents(out->parameter, out->omegaBar,
                                   [&](int i, int a, int j, int b) { return mac(stored[i][a], stored[j][b]); });
  }
  // MPI: the MAC callbacks above are collective (VecDot); every rank runs the same sequence.
  if (sw.refine > 0 && out->failure.empty()) PetscCall(refineEvents(comm, scene, out));
  for (auto& row : stored)
    for (StoredShape& s : row)
      for (Vec* v : {&s.xr, &s.xi, &s.mr, &s.mi}) PetscCall(VecDestroy(v));
  modal.reset();
  PetscCall(VecDestroy(&X));
  PetscCall(VecDestroy(&Xold));
  PetscCall(MatDestroy(&Mmac));
  out->seconds = MPI_Wtime() - t0;
  PetscFunctionReturn(0);
}

}  // namespace strand::solvers
