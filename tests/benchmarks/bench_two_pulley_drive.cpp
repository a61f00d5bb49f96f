// The two-pulley belt drive of Pechstein & Gerstmayr (2013) as the THREAD belt-drive study sets it
// up (tests/support/Belts.hpp, twoPulleyDrive; meshes/two-pulley-drive.yaml), 2.45 s of it, on one
// core (issue 34; docs/performance.md, "Two-pulley drive"). Issue 34's target: at most 40 s wall with
// the span tensions within 2 % of the converged values (an open peer took 799 s here).
//
// One JSON line per (elements, dt): wall time, steps, Newton iterations per step, the contact's
// share of the run (log event Strand:Asm:Contact), and at t = 2.45 s the driven pulley's speed and
// the span tensions T1, T2 (at the middles of the spans, from the stretch), with their relative
// differences from the finest run that finished (the last of the list that did).
#include <petscsys.h>
#include <petsctime.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "strand/solvers/Dynamics.hpp"
#include "support/Belts.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

double eventSeconds(const char* name) {
  PetscLogEvent ev;
  PetscEventPerfInfo info;
  PetscCallAbort(PETSC_COMM_WORLD, PetscLogEventGetId(name, &ev));
  PetscCallAbort(PETSC_COMM_WORLD, PetscLogEventGetPerfInfo(0, ev, &info));
  return info.time;
}

struct Run {
  int elements = 0;
  double dt = 0, seconds = 0, contactShare = 0, newtonPerStep = 0, omega2 = 0, T[2] = {0, 0};
  int steps = 0;
  std::string failure;
};

double tensionOfStretch(double lambda) { return 8000.0 * 0.5 * (lambda * lambda - 1.0) * lambda; }

Run run(int elements, double dt) {
  Run r;
  r.elements = elements;
  r.dt = dt;
  solvers::Problem p(PETSC_COMM_WORLD, twoPulleyDrive(elements));
  Vec X, V;
  PetscCallAbort(PETSC_COMM_WORLD, p.createInitialState(&X, &V));
  model::DynamicsDesc d;
  d.rhoInf = 0.8;
  d.dt = dt;
  d.tEnd = 2.45;
  long iterations = 0;
  {
    solvers::Dynamics dyn(p.assembler(), d);
    PetscCallAbort(PETSC_COMM_WORLD, dyn.setFromOptions());
    solvers::Dynamics::StepCallback cb = [&](const solvers::DynamicsStep& s, Vec, Vec) -> PetscErrorCode {
      iterations += s.newtonIterations;
      r.steps = s.step;
      return 0;
    };
    const double c0 = eventSeconds("Strand:Asm:Contact");
    PetscLogDouble t0, t1;
    PetscCallAbort(PETSC_COMM_WORLD, PetscTime(&t0));
    PetscCallAbort(PETSC_COMM_WORLD, dyn.run(X, V, cb, &r.failure));
    PetscCallAbort(PETSC_COMM_WORLD, PetscTime(&t1));
    r.seconds = t1 - t0;
    r.contactShare = (eventSeconds("Strand:Asm:Contact") - c0) / r.seconds;
    r.newtonPerStep = r.steps > 0 ? double(iterations) / r.steps : 0.0;
  }
  std::vector<double> load, q;
  PetscCallAbort(PETSC_COMM_WORLD, p.assembler().pulleyLoads(X, V, d.tEnd, load));
  r.omega2 = load[7];
  PetscCallAbort(PETSC_COMM_WORLD, p.assembler().gatherToRoot(X, q));
  const model::Body& b = p.model().bodies()[0];
  if (!q.empty())
    for (int k = 0; k < 2; ++k) {  // the upper span (k = 1, N/2) is the tight one
      const int blk = b.block(k * b.elements / 2, 1);
      r.T[1 - k] = tensionOfStretch(std::hypot(q[2 * blk], q[2 * blk + 1]) / b.blockScale(1));
    }
  VecDestroy(&X);
  VecDestroy(&V);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  PetscCall(PetscLogDefaultBegin());
  std::vector<Run> runs;
  for (auto [n, dt] : std::vector<std::pair<int, double>>{{50, 2e-4}, {100, 2e-4}, {200, 2e-4}, {100, 1e-4}, {400, 1e-4}})
    runs.push_back(run(n, dt));
  const Run* finest = nullptr;
  for (const Run& r : runs)
    if (r.failure.empty()) finest = &r;
  for (const Run& r : runs) {
    auto rel = [&](double a, double b) { return finest && r.failure.empty() ? std::abs(a / b - 1.0) : -1.0; };
    std::printf("{\"case\": \"two_pulley_drive\", \"elements\": %d, \"dt\": %g, \"t_end\": 2.45, \"steps\": %d, "
                "\"seconds\": %.3f, \"newton_per_step\": %.2f, \"contact_share\": %.3f, \"omega_driven\": %.6f, "
                "\"T1\": %.3f, \"T2\": %.3f, \"T1_vs_finest\": %.2e, \"T2_vs_finest\": %.2e, \"omega_vs_finest\": %.2e, "
                "\"finest\": \"%d elements, dt %g\", \"failure\": \"%s\"}\n",
                r.elements, r.dt, r.steps, r.seconds, r.newtonPerStep, r.contactShare, r.omega2, r.T[0], r.T[1],
                finest ? rel(r.T[0], finest->T[0]) : -1.0, finest ? rel(r.T[1], finest->T[1]) : -1.0,
                finest ? rel(r.omega2, finest->omega2) : -1.0, finest ? finest->elements : 0, finest ? finest->dt : 0.0,
                r.failure.c_str());
  }
  PetscCall(PetscFinalize());
  return 0;
}
