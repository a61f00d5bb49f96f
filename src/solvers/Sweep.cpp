#include "strand/solvers/Sweep.hpp"

#include <cmath>
#include <memory>

#include "strand/solvers/ModalSolver.hpp"
#include "strand/solvers/Problem.hpp"
#include "strand/solvers/StaticSolver.hpp"

namespace strand::solvers {

namespace {

const char* parameterName(model::SweepParameter p) {
  switch (p) {
    case model::SweepParameter::Gamma: return "gamma";
    case model::SweepParameter::Omega: return "omega";
    case model::SweepParameter::MassRatio: return "mass_ratio";
    default: return "mass_location";
  }
}

// A mode shape x = xr + i xi and M x, kept for MAC values between any two points.
struct StoredShape {
  Vec xr = nullptr, xi = nullptr, mr = nullptr, mi = nullptr;
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
  const double xx = dot(x.xr, x.mr) + dot(x.xi, x.mi), yy = dot(y.xr, y.mr) + dot(y.xi, y.mi);
  return (re * re + im * im) / (xx * yy);
}

// Vibration nodes of a mode shape on body 0: sign changes of its dominant displacement component
// between nodes 1..N (node 0 is the clamp), linearly interpolated, as x / L.
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
  for (int n = 1; n < b.elements; ++n) {
    const double w0 = disp[b.posBlock[n] * d + c], w1 = disp[b.posBlock[n + 1] * d + c];
    if (std::fabs(w0) < tiny || std::fabs(w1) < tiny || (w0 > 0) == (w1 > 0)) continue;
    nodes.push_back((n + w0 / (w0 - w1)) / b.elements);
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

}  // namespace

PetscErrorCode runSweep(MPI_Comm comm, const model::SceneDescription& scene, SweepResult* out,
                        const SweepProgress& progress) {
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
  Mat Mmac = nullptr;  // fixed inner product for MAC: the mass matrix of the first point
  std::vector<std::vector<StoredShape>> stored;
  for (int i = 0; i < sw.points; ++i) {
    const double p = sw.from + (sw.to - sw.from) * i / (sw.points - 1);
    if (!problem || !speedSweep) {
      model::SceneDescription sc = scene;
      if (!speedSweep) {
        model::PointMassDesc& pm = sc.bodies[0].pointMasses[sw.mass];
        const model::BodyDesc& b = sc.bodies[0];
        if (sw.parameter == model::SweepParameter::MassRatio) pm.mass = p * b.rho * b.A * length;
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
        PetscCall(problem->assembler().massMatrix(Mmac));
      }
    }
    const double T = problem->model().scales().time();
    double omega = problem->model().rotation().omega;
    if (sw.parameter == model::SweepParameter::Gamma) omega = p / T;
    if (sw.parameter == model::SweepParameter::Omega) omega = p;
    problem->setAngularSpeed(omega);
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
    out->method = r.method;
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
      const auto& prev = stored.back();
      std::vector<double> m(prev.size() * here.size());
      for (size_t a = 0; a < prev.size(); ++a)
        for (size_t b = 0; b < here.size(); ++b) m[a * here.size() + b] = mac(prev[a], here[b]);
      out->macNext.push_back(m);
    }
    stored.push_back(here);
    destroyModes(&r);
    if (progress) progress(i, *out);
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
  for (auto& row : stored)
    for (StoredShape& s : row)
      for (Vec* v : {&s.xr, &s.xi, &s.mr, &s.mi}) PetscCall(VecDestroy(v));
  modal.reset();
  PetscCall(VecDestroy(&X));
  PetscCall(MatDestroy(&Mmac));
  out->seconds = MPI_Wtime() - t0;
  PetscFunctionReturn(0);
}

}  // namespace strand::solvers
