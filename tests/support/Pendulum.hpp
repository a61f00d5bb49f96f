// The flexible pendulum of the integrator tests (issue 3): a 1 m cable, 8 elements, pinned at the
// origin, released horizontally at rest under gravity -9.81 y; EA = 1e4 N, EI = 1 N m^2 (a
// rope-like cable, axial period 35 ms, highest frequency of the discrete model 8.6e3 rad/s).
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <slepceps.h>

#include "strand/solvers/Dynamics.hpp"
#include "support/Scenes.hpp"

namespace strand::testing {

inline model::DynamicsDesc scheme(model::Integrator integrator, double rhoInf, double dt, double tEnd) {
  model::DynamicsDesc d;
  d.integrator = integrator;
  d.rhoInf = rhoInf;
  d.dt = dt;
  d.tEnd = tEnd;
  return d;
}

inline model::SceneDescription flexiblePendulum(double damping = 0.0, double E = 1e8, int elements = 8) {
  Section s;
  s.E = E;
  auto sc = cantilever(2, elements, 1.0, s);
  sc.supports[0].type = model::SupportType::Pinned;
  sc.loads.gravity = {0, -9.81, 0};
  sc.bodies[0].section.set("damping_axial", damping);
  sc.bodies[0].section.set("damping_bending", damping);
  return sc;
}

struct PendulumRun {
  double e0 = 0.0, maxDrift = 0.0, eEnd = 0.0, scale = 0.0;  // energy balance; m g L / 2
  double tipX = 0.0, tipY = 0.0;
  int steps = 0, rejected = 0;
  std::string failure;
};

// Runs the pendulum scene sc with scheme d; a failure is returned, not asserted (expectFailure).
// fromOptions: the PETSc options database may change the TS (Dynamics::setFromOptions).
inline PendulumRun runPendulum(const model::SceneDescription& sc, const model::DynamicsDesc& d, bool expectFailure,
                               bool fromOptions = false) {
  solvers::Problem p(PETSC_COMM_WORLD, sc);
  MPI_Comm comm = PETSC_COMM_WORLD;
  Vec X, V;
  PetscCallAbort(comm, p.createInitialState(&X, &V));
  PendulumRun out;
  out.scale = sc.bodies[0].section.number("rho") * sc.bodies[0].section.number("A") * 1.0 * 9.81 * 0.5;
  solvers::Dynamics dyn(p.assembler(), d);
  if (fromOptions) PetscCallAbort(comm, dyn.setFromOptions());
  solvers::Dynamics::StepCallback cb = [&](const solvers::DynamicsStep& st, Vec, Vec) -> PetscErrorCode {
    if (st.step == 0) out.e0 = st.energy();
    out.maxDrift = std::max(out.maxDrift, std::fabs(st.energy() - out.e0));
    out.eEnd = st.energy();
    out.steps = st.step;
    out.rejected = st.rejectedSteps;
    return 0;
  };
  PetscCallAbort(comm, dyn.run(X, V, cb, &out.failure));
  if (!expectFailure) {
    EXPECT_EQ(out.failure, "");
  }
  std::vector<double> q;
  PetscCallAbort(comm, p.assembler().gatherToRoot(X, q));
  q.resize(p.model().numDofs());
  MPI_Bcast(q.data(), static_cast<int>(q.size()), MPI_DOUBLE, 0, comm);
  const model::Vec3 tip = nodePosition(p, q, 0, -1);
  out.tipX = tip[0];
  out.tipY = tip[1];
  VecDestroy(&X);
  VecDestroy(&V);
  return out;
}

// omega_max of K x = omega^2 M x at the reference state (SLEPc, largest magnitude); unit rows of the
// supported DOFs on both sides give them the eigenvalue 1.
inline double highestFrequency(const model::SceneDescription& sc) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  solvers::Problem p(comm, sc);
  Mat K, M;
  Vec X, supported;
  PetscCallAbort(comm, p.dofs().createMatrix(&K, nullptr));
  PetscCallAbort(comm, p.dofs().createMatrix(&M, nullptr));
  PetscCallAbort(comm, p.dofs().createVector(&X));
  PetscCallAbort(comm, VecDuplicate(X, &supported));
  PetscCallAbort(comm, p.assembler().initialState(X));
  PetscCallAbort(comm, p.assembler().staticJacobian(X, 0.0, K));
  PetscCallAbort(comm, p.assembler().massMatrix(M));
  PetscCallAbort(comm, p.assembler().supportMask(supported));
  PetscCallAbort(comm, MatDiagonalSet(M, supported, ADD_VALUES));
  EPS eps;
  ST st;
  KSP ksp;
  PetscCallAbort(comm, EPSCreate(comm, &eps));
  PetscCallAbort(comm, EPSSetOperators(eps, K, M));
  PetscCallAbort(comm, EPSSetProblemType(eps, EPS_GHEP));
  PetscCallAbort(comm, EPSSetWhichEigenpairs(eps, EPS_LARGEST_MAGNITUDE));
  PetscCallAbort(comm, EPSSetTolerances(eps, 1e-10, 1000));
  PetscCallAbort(comm, EPSGetST(eps, &st));
  PetscCallAbort(comm, STGetKSP(st, &ksp));
  PetscCallAbort(comm, solvers::setDirectSolverDefaults(ksp, false));
  PetscCallAbort(comm, EPSSolve(eps));
  PetscInt nconv;
  PetscCallAbort(comm, EPSGetConverged(eps, &nconv));
  EXPECT_GE(nconv, 1);
  PetscScalar lambda = 0.0;
  if (nconv >= 1) PetscCallAbort(comm, EPSGetEigenvalue(eps, 0, &lambda, nullptr));
  EPSDestroy(&eps);
  MatDestroy(&K);
  MatDestroy(&M);
  VecDestroy(&X);
  VecDestroy(&supported);
  return std::sqrt(PetscRealPart(lambda));
}

inline PendulumRun pendulum(const model::DynamicsDesc& d, double damping = 0.0, bool expectFailure = false) {
  return runPendulum(flexiblePendulum(damping), d, expectFailure);
}

}  // namespace strand::testing
