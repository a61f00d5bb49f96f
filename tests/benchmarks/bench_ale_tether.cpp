// The cost of a variable-length tether (issue 35; docs/performance.md, "ALE tether"): a 100 m
// steel tether (r = 5 mm) of N elements hanging from a fixed exit with a 50 kg block on a pin
// joint at its end, gravity ramped in over 0.1 s, generalized-alpha (rho_inf 0.5), dt = 1 ms:
//   ale    AleCable2d, the exit paying out at 1 m/s from t = 0 (every element grows; the
//          configuration-dependent mass and the mass-transport inertia assembled every Newton step)
//   cable  AncfCable2d of the same N, the fixed-length tether (constant mass)
// The two run alternately in one process, `-rounds` times (default 3); each run takes `-steps`
// steps after the start (default 300: the gravity ramp takes the first 100, and only after it does
// the payout's kept Newton matrix go stale, docs/performance.md). The ALE cost factor is the
// median over rounds of the ratio of the wall times per step, and the ratio of the fastest rounds
// (a shared host's noise only adds time, so each model's fastest round is the estimate least
// disturbed by it). One JSON line per run, then a summary line. Options: -elements N (default
// 10000), -steps, -rounds, -trace (a line per step: Newton iterations, matrices so far), and the
// dynamics' -dyn_ options. Under mpirun the same on every rank count. With -only ale (or cable)
// one run of that model in tests/benchmarks/parallel_ratio.py's terms:
//   parallel_ratio.py build/tests/benchmarks/bench_ale_tether mpiexec --rounds 3 -only ale -steps 300
#include <petscsys.h>
#include <petsctime.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "strand/elements/ElementRegistry.hpp"
#include "strand/solvers/Dynamics.hpp"
#include "support/Scenes.hpp"

using namespace strand;

namespace {

model::SceneDescription tether(bool ale, int elements, int steps) {
  const double L = 100.0, r = 5e-3;
  model::SceneDescription sc;
  sc.file = "(bench)";
  sc.dimension = 2;
  sc.analysis = model::Analysis::Dynamic;
  model::BodyDesc b;
  b.name = "tether";
  b.kind = elements::findKind(ale ? "AleCable2d" : "AncfCable2d");
  b.elements = elements;
  b.geometry.kind = model::GeometryKind::Line;
  b.geometry.start = {0, 0, 0};
  b.geometry.end = {0, -L, 0};
  b.section.numbers = {{"E", 2e11}, {"A", M_PI * r * r}, {"I", M_PI * std::pow(r, 4) / 4.0}, {"rho", 7850.0}};
  if (ale) {
    b.hasPayout = true;
    b.payout.kind = model::TimeFunction::Kind::Linear;
    b.payout.rate = 1.0;
  }
  sc.bodies.push_back(b);
  model::SupportDesc top;
  top.at.body = "tether";
  top.at.node = 0;
  top.type = model::SupportType::Pinned;
  sc.supports.push_back(top);
  model::RigidBodyDesc block;
  block.name = "block";
  block.mass = 50.0;
  block.inertia = 0.1;
  block.position = {0, -L, 0};
  sc.rigidBodies.push_back(block);
  model::JointDesc pin;
  pin.type = model::JointType::Pin;
  pin.a.kind = model::JointEndDesc::Kind::CableNode;
  pin.a.body = "tether";
  pin.a.node = -1;
  pin.b.kind = model::JointEndDesc::Kind::RigidPoint;
  pin.b.body = "block";
  sc.joints.push_back(pin);
  sc.loads.gravity = {0, -9.81, 0};
  sc.loads.timed = true;  // gravity ramped in over 0.1 s
  sc.loads.function.kind = model::TimeFunction::Kind::Ramp;
  sc.loads.function.start = 0.0;
  sc.loads.function.end = 0.1;
  sc.loads.function.value = 1.0;
  sc.dynamics.integrator = model::Integrator::GeneralizedAlpha;
  sc.dynamics.rhoInf = 0.5;  // damps the highest axial modes of the fine mesh
  sc.dynamics.dt = 1e-3;
  sc.dynamics.tEnd = steps * 1e-3;
  return sc;
}

struct Run {
  double setup = 0.0, perStep = 0.0, newtonPerStep = 0.0, tipY = 0.0;
  long steps = 0;
  std::string failure;
};

Run run(bool ale, int elements, int steps, bool trace) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  PetscLogDouble t0, t1, t2;
  PetscCallAbort(comm, PetscTime(&t0));
  const model::SceneDescription sc = tether(ale, elements, steps);
  solvers::Problem p(comm, sc);
  Vec X, V;
  PetscCallAbort(comm, p.createInitialState(&X, &V));
  solvers::Dynamics dyn(p.assembler(), sc.dynamics);
  PetscCallAbort(comm, dyn.setFromOptions());
  long newton = 0, taken = 0;
  solvers::Dynamics::StepCallback cb = [&](const solvers::DynamicsStep& s, Vec, Vec) -> PetscErrorCode {
    if (s.step == 0) PetscCall(PetscTime(&t1));  // the consistent start done: time the steps
    newton += s.newtonIterations;
    taken = s.step;
    if (trace) PetscCall(PetscPrintf(comm, "{\"trace\": \"%s\", \"step\": %d, \"newton\": %d, \"matrices\": %ld}\n",
                                     ale ? "ale" : "cable", s.step, s.newtonIterations, dyn.newtonMatrices()));
    return 0;
  };
  Run r;
  PetscCallAbort(comm, dyn.run(X, V, cb, &r.failure));
  PetscCallAbort(comm, PetscTime(&t2));
  r.setup = t1 - t0;
  r.steps = taken;
  r.perStep = (t2 - t1) / std::max(1L, taken);
  r.newtonPerStep = static_cast<double>(newton) / std::max(1L, taken);
  std::vector<double> q;
  PetscCallAbort(comm, p.assembler().gatherToRoot(X, q));
  if (!q.empty()) r.tipY = q[p.model().bodies()[0].posBlock.back() * 2 + 1];
  VecDestroy(&X);
  VecDestroy(&V);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  PetscInt elements = 10000, steps = 300, rounds = 3;
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-elements", &elements, nullptr));
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-steps", &steps, nullptr));
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-rounds", &rounds, nullptr));
  PetscBool trace = PETSC_FALSE;  // -trace: one line per step (Newton iterations, Newton matrices formed so far)
  PetscCall(PetscOptionsGetBool(nullptr, nullptr, "-trace", &trace, nullptr));
  int ranks, rank;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  // -only ale|cable: one run of one model, one line in parallel_ratio.py's terms (steady_ms_per_step:
  // the steps after the consistent start; ms_per_step: the whole run; tip_z: the tether end's y)
  char only[16] = "";
  PetscBool hasOnly = PETSC_FALSE;
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-only", only, sizeof(only), &hasOnly));
  if (hasOnly) {
    const bool ale = std::string(only) == "ale";
    const Run r = run(ale, static_cast<int>(elements), static_cast<int>(steps), trace);
    if (rank == 0)
      std::printf("{\"bench\": \"ale_tether\", \"model\": \"%s\", \"elements\": %d, \"ranks\": %d, \"steps\": %ld, "
                  "\"steady_ms_per_step\": %.4f, \"ms_per_step\": %.4f, \"tip_z\": %.15e, \"failure\": \"%s\"}\n",
                  ale ? "ale" : "cable", static_cast<int>(elements), ranks, r.steps, 1e3 * r.perStep,
                  1e3 * (r.setup + r.perStep * r.steps) / std::max(1L, r.steps), r.tipY, r.failure.c_str());
    PetscCall(PetscFinalize());
    return 0;
  }
  std::vector<double> ratios;
  double fastest[2] = {1e300, 1e300};  // ale, cable
  for (PetscInt k = 0; k < rounds; ++k) {
    Run pair[2];
    for (int a = 0; a < 2; ++a) {
      const bool ale = (a == 0) == (k % 2 == 0);  // alternate which goes first
      pair[ale ? 0 : 1] = run(ale, static_cast<int>(elements), static_cast<int>(steps), trace);
      const Run& r = pair[ale ? 0 : 1];
      if (rank == 0)
        std::printf("{\"bench\": \"ale_tether\", \"model\": \"%s\", \"round\": %d, \"elements\": %d, \"ranks\": %d, "
                    "\"steps\": %d, \"setup_s\": %.4f, \"step_ms\": %.4f, \"newton_per_step\": %.3f, \"failure\": \"%s\"}\n",
                    ale ? "ale" : "cable", static_cast<int>(k), static_cast<int>(elements), ranks,
                    static_cast<int>(steps), r.setup, 1e3 * r.perStep, r.newtonPerStep, r.failure.c_str());
    }
    ratios.push_back(pair[0].perStep / pair[1].perStep);
    for (int a = 0; a < 2; ++a) fastest[a] = std::min(fastest[a], pair[a].perStep);
  }
  std::vector<double> sorted = ratios;
  std::sort(sorted.begin(), sorted.end());
  if (rank == 0) {
    std::printf("{\"bench\": \"ale_tether_summary\", \"elements\": %d, \"ranks\": %d, \"ratios\": [", static_cast<int>(elements),
                ranks);
    for (size_t k = 0; k < ratios.size(); ++k) std::printf("%s%.4f", k ? ", " : "", ratios[k]);
    std::printf("], \"median_ale_cost_factor\": %.4f, \"min\": %.4f, \"max\": %.4f, \"fastest_ale_ms\": %.4f, "
                "\"fastest_cable_ms\": %.4f, \"fastest_rounds_factor\": %.4f}\n",
                sorted[sorted.size() / 2], sorted.front(), sorted.back(), 1e3 * fastest[0], 1e3 * fastest[1],
                fastest[0] / fastest[1]);
  }
  PetscCall(PetscFinalize());
  return 0;
}
