// A dynamic run of a scene built in code: its steps and the end state on every rank.
#pragma once
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "strand/solvers/Dynamics.hpp"
#include "strand/solvers/Problem.hpp"

namespace strand::testing {

struct DynamicRun {
  std::vector<solvers::DynamicsStep> steps;
  std::vector<double> q, v;  // coordinates and velocities at the end (model numbering)
  std::string failure;
};

// What a run may read at each step besides the step's record (collective: every rank calls it).
using StepHook = std::function<PetscErrorCode(solvers::Problem&, const solvers::DynamicsStep&, Vec X, Vec V)>;

// integrator: the scheme (generalized-alpha with rhoInf by default; BDF of order bdfOrder).
inline DynamicRun runDynamics(const model::SceneDescription& sc, double dt, double tEnd, double rhoInf,
                              model::Integrator integrator = model::Integrator::GeneralizedAlpha, int bdfOrder = 2,
                              const StepHook& onStep = nullptr) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  model::DynamicsDesc dd;
  dd.integrator = integrator;
  dd.bdfOrder = bdfOrder;
  dd.rhoInf = rhoInf;
  dd.dt = dt;
  dd.tEnd = tEnd;
  solvers::Problem p(comm, sc);
  Vec X, V;
  PetscCallAbort(comm, p.createInitialState(&X, &V));
  DynamicRun r;
  {
    solvers::Dynamics dyn(p.assembler(), dd);
    PetscCallAbort(comm, dyn.setFromOptions());
    solvers::Dynamics::StepCallback cb = [&](const solvers::DynamicsStep& st, Vec Xs, Vec Vs) -> PetscErrorCode {
      r.steps.push_back(st);
      return onStep ? onStep(p, st, Xs, Vs) : 0;
    };
    PetscCallAbort(comm, dyn.run(X, V, cb, &r.failure));
  }
  PetscCallAbort(comm, p.assembler().gatherToRoot(X, r.q));
  PetscCallAbort(comm, p.assembler().toModelOrder(V, r.v));
  r.q.resize(p.model().numDofs());
  r.v.resize(p.model().numDofs());
  MPI_Bcast(r.q.data(), static_cast<int>(r.q.size()), MPI_DOUBLE, 0, comm);
  MPI_Bcast(r.v.data(), static_cast<int>(r.v.size()), MPI_DOUBLE, 0, comm);
  VecDestroy(&X);
  VecDestroy(&V);
  return r;
}

// The largest |E - E0| of the run's energy balance.
inline double energyDrift(const DynamicRun& r) {
  double drift = 0.0;
  for (const solvers::DynamicsStep& st : r.steps) drift = std::max(drift, std::abs(st.energy() - r.steps.front().energy()));
  return drift;
}

}  // namespace strand::testing
