// The two-pulley belt drive of Pechstein & Gerstmayr (2013) as the THREAD belt-drive study sets it
// up (tests/support/Belts.hpp, twoPulleyDrive; meshes/two-pulley-drive.yaml), 2.45 s of it, on one
// core (issue 34; docs/performance.md, "Two-pulley drive"). Issue 34's target: at most 40 s wall with
// the span tensions within 2 % of the converged values (an open peer took 799 s here).
//
// One JSON line per case (elements, dt, contact points, friction law, integrator): wall time,
// steps, Newton iterations per step, the contact's share of the run (log event
// Strand:Asm:Contact), and at t = 2.45 s the driven pulley's speed and the span tensions T1, T2 (at
// the middles of the spans, from the stretch), with their relative differences from the reference
// run (400 elements, dt = 1e-4 s, 4 points, bristle, generalized-alpha; the last line) and
// "error", the larger of the two tensions'. The work-precision chart of docs/performance.md:
//   strand plot lines two_pulley_drive.jsonl -x seconds -y error --group series --loglog -o chart.png
#include <petscsys.h>
#include <petsctime.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "strand/solvers/Dynamics.hpp"
#include "support/Belts.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

struct Case {
  int elements;
  double dt;
  int points;
  const char* law;  // "bristle" (k_t 1e8), "bristle_1e9", "coulomb" or "creep_rate" (v_s = 0.1 m/s: at 0.03 the
                    // creep-rate law fails at 1.37 s)
  const char* integrator;  // "alpha" (generalized-alpha rho_inf 0.8) or "bdf2" (not with a free pulley yet)
};

struct Run {
  Case c{};
  int elements = 0;
  double dt = 0, seconds = 0, contactShare = 0, newtonPerStep = 0, omega2 = 0, T[2] = {0, 0};
  int steps = 0;
  std::string failure;
};

Run run(const Case& c) {
  Run r;
  r.c = c;
  r.elements = c.elements;
  r.dt = c.dt;
  model::SceneDescription sc = twoPulleyDrive(c.elements, std::string(c.law) == "bristle_1e9" ? 1e9 : 1e8);
  sc.contacts[0].points = c.points;
  if (std::string(c.law) == "coulomb" || std::string(c.law) == "creep_rate") {
    sc.contacts[0].law.friction =
        std::string(c.law) == "coulomb" ? contact::FrictionLaw::RegularizedCoulomb : contact::FrictionLaw::CreepRate;
    sc.contacts[0].law.slipVelocity = 0.1;
  }
  solvers::Problem p(PETSC_COMM_WORLD, sc);
  Vec X, V;
  PetscCallAbort(PETSC_COMM_WORLD, p.createInitialState(&X, &V));
  model::DynamicsDesc d;
  d.rhoInf = 0.8;
  if (std::string(c.integrator) == "bdf2") {
    d.integrator = model::Integrator::Bdf;
    d.bdfOrder = 2;
  } else {
    d.stepCuts = 3;  // the stiff bristle law fails Newton in a few steps (docs/contact.md)
  }
  d.dt = c.dt;
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
    const double c0 = contactSeconds();
    PetscLogDouble t0, t1;
    PetscCallAbort(PETSC_COMM_WORLD, PetscTime(&t0));
    PetscCallAbort(PETSC_COMM_WORLD, dyn.run(X, V, cb, &r.failure));
    PetscCallAbort(PETSC_COMM_WORLD, PetscTime(&t1));
    r.seconds = t1 - t0;
    r.contactShare = (contactSeconds() - c0) / r.seconds;
    r.newtonPerStep = r.steps > 0 ? double(iterations) / r.steps : 0.0;
  }
  std::vector<assembly::Assembler::PulleyLoad> load;
  std::vector<double> q;
  PetscCallAbort(PETSC_COMM_WORLD, p.assembler().pulleyLoads(X, V, d.tEnd, load));
  r.omega2 = load[1].speed;
  PetscCallAbort(PETSC_COMM_WORLD, p.assembler().gatherToRoot(X, q));
  const model::Body& b = p.model().bodies()[0];
  if (!q.empty())
    for (int k = 0; k < 2; ++k)  // at the middles of the spans; the upper one (k = 1) is the tight one
      r.T[1 - k] = cableTension(8000.0, nodeStretch(b, q, nodeNearest(b, q, 0.05 * std::acos(-1.0), k ? 0.1 : -0.1)));
  VecDestroy(&X);
  VecDestroy(&V);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  PetscCall(PetscLogDefaultBegin());
  const std::vector<Case> cases = {
      {25, 2e-4, 4, "bristle", "alpha"},  {50, 2e-4, 4, "bristle", "alpha"},  {100, 2e-4, 4, "bristle", "alpha"},
      {200, 2e-4, 4, "bristle", "alpha"}, {50, 2e-4, 2, "bristle", "alpha"},  {100, 2e-4, 2, "bristle", "alpha"},
      {50, 1e-4, 4, "bristle", "alpha"},  {100, 1e-4, 4, "bristle", "alpha"}, {100, 2e-4, 4, "coulomb", "alpha"},
      {100, 2e-4, 4, "creep_rate", "alpha"}, {100, 2e-4, 4, "bristle_1e9", "alpha"},
      {50, 2e-4, 4, "bristle", "bdf2"}, {100, 2e-4, 4, "bristle", "bdf2"},
      {400, 1e-4, 4, "bristle", "alpha"}};
  std::vector<Run> runs;
  for (const Case& c : cases) runs.push_back(run(c));
  const Run& ref = runs.back();
  for (const Run& r : runs) {
    const bool ok = r.failure.empty() && ref.failure.empty();
    auto rel = [&](double a, double b) { return ok ? std::abs(a / b - 1.0) : -1.0; };
    const double e1 = rel(r.T[0], ref.T[0]), e2 = rel(r.T[1], ref.T[1]);
    std::printf("{\"case\": \"two_pulley_drive\", \"series\": \"%s %s, %d points, dt %g\", \"elements\": %d, "
                "\"dt\": %g, \"points\": %d, \"law\": \"%s\", \"integrator\": \"%s\", \"t_end\": 2.45, "
                "\"steps\": %d, \"seconds\": %.3f, \"newton_per_step\": %.2f, \"contact_share\": %.3f, "
                "\"omega_driven\": %.6f, \"T1\": %.3f, \"T2\": %.3f, \"T1_vs_reference\": %.2e, "
                "\"T2_vs_reference\": %.2e, \"omega_vs_reference\": %.2e, \"error\": %.2e, \"failure\": \"%s\"}\n",
                r.c.law, r.c.integrator, r.c.points, r.c.dt, r.elements, r.dt, r.c.points, r.c.law, r.c.integrator,
                r.steps, r.seconds, r.newtonPerStep, r.contactShare, r.omega2, r.T[0], r.T[1], e1, e2,
                rel(r.omega2, ref.omega2), ok ? std::max(e1, e2) : -1.0, r.failure.c_str());
  }
  PetscCall(PetscFinalize());
  return 0;
}
