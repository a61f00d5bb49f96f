// Joints: index-3 generalized-alpha (rho_inf = 0.9) against BDF2 on the GGL stabilized index-2 form
// (issue 3; docs/performance.md, "Joints"), cost and accuracy from one run, on one core:
//  - the 20-link chain (0.1 m, 0.1 kg links, released horizontally, 0.5 s; tests/support/Scenes.hpp
//    rigidChain): wall time per step, Newton iterations per step, the largest energy error (relative
//    to m g L / 2), position and velocity drift |g|, |G v|;
//  - the link carried by a driven hub (2 s; tests/support/CarriedLink.hpp): the largest drive-torque
//    and ground-force errors against the exact solution; its time per step includes the checking
//    monitor (a gather and a support force every step).
// One JSON line per (case, integrator, step); -repeat N keeps the fastest of N runs.
#include <petscsys.h>
#include <petsctime.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "strand/solvers/Dynamics.hpp"
#include "strand/solvers/Schemes.hpp"
#include "support/CarriedLink.hpp"
#include "support/Scenes.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

model::DynamicsDesc schemeOf(model::Integrator integrator, double dt, double tEnd) {
  model::DynamicsDesc d;  // rho_inf 0.9, BDF order 2: the defaults
  d.integrator = integrator;
  d.dt = dt;
  d.tEnd = tEnd;
  return d;
}

struct ChainResult {
  double seconds = 1e300, energy = 0.0, position = 0.0, velocity = 0.0;
  long steps = 0, newton = 0;
  std::string failure;
};

ChainResult runChain(const model::DynamicsDesc& d) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  solvers::Problem p(comm, rigidChain(20, 0.1, 0.1));
  Vec X, V;
  PetscCallAbort(comm, p.createInitialState(&X, &V));
  solvers::Dynamics dyn(p.assembler(), d);
  PetscCallAbort(comm, dyn.setFromOptions());
  ChainResult r;
  double e0 = 0.0;
  solvers::Dynamics::StepCallback cb = [&](const solvers::DynamicsStep& s, Vec, Vec) -> PetscErrorCode {
    if (s.step == 0) e0 = s.energy();
    r.energy = std::max(r.energy, std::fabs(s.energy() - e0));
    r.position = std::max(r.position, s.constraintPosition);
    r.velocity = std::max(r.velocity, s.constraintVelocity);
    r.steps = s.step;
    r.newton += s.newtonIterations;
    return 0;
  };
  PetscLogDouble t0, t1;
  PetscCallAbort(comm, PetscTime(&t0));
  PetscCallAbort(comm, dyn.run(X, V, cb, &r.failure));
  PetscCallAbort(comm, PetscTime(&t1));
  r.seconds = t1 - t0;
  VecDestroy(&X);
  VecDestroy(&V);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  PetscInt repeat = 3;
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-repeat", &repeat, nullptr));
  const double chainScale = 2.0 * 9.81 * 1.0;  // m_total g L / 2 = 2 kg * 9.81 m/s^2 * 2 m / 2
  for (model::Integrator integrator : {model::Integrator::GeneralizedAlpha, model::Integrator::Bdf}) {
    for (double dt : {1e-3, 5e-4}) {
      const model::DynamicsDesc d = schemeOf(integrator, dt, 0.5);
      ChainResult best;
      for (PetscInt k = 0; k < repeat; ++k) {
        const ChainResult r = runChain(d);
        if (r.seconds < best.seconds) best = r;
      }
      PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                            "{\"bench\": \"joints\", \"case\": \"chain20\", \"integrator\": \"%s\", \"dt\": %.6e, "
                            "\"steps\": %ld, \"us_per_step\": %.6e, \"newton_per_step\": %.4f, \"energy_error\": %.6e, "
                            "\"constraint_position\": %.3e, \"constraint_velocity\": %.3e, \"failure\": \"%s\"}\n",
                            solvers::schemeName(d).c_str(), dt, best.steps, 1e6 * best.seconds / std::max(best.steps, 1L),
                            static_cast<double>(best.newton) / std::max(best.steps, 1L), best.energy / chainScale,
                            best.position, best.velocity, best.failure.c_str()));
    }
    for (double dt : {2e-3, 1e-3, 5e-4}) {
      const model::DynamicsDesc d = schemeOf(integrator, dt, 2.0);
      CarriedLink best;
      best.seconds = 1e300;
      for (PetscInt k = 0; k < repeat; ++k) {
        const CarriedLink r = carryLink(d);
        if (r.seconds < best.seconds) best = r;
      }
      PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                            "{\"bench\": \"joints\", \"case\": \"carried_link\", \"integrator\": \"%s\", \"dt\": %.6e, "
                            "\"steps\": %ld, \"us_per_step\": %.6e, \"newton_per_step\": %.4f, \"torque_error\": %.6e, "
                            "\"force_error\": %.6e, \"energy_error\": %.6e, \"failure\": \"%s\"}\n",
                            solvers::schemeName(d).c_str(), dt, best.steps, 1e6 * best.seconds / std::max(best.steps, 1L),
                            static_cast<double>(best.newton) / std::max(best.steps, 1L), best.torque, best.force,
                            best.energy, best.failure.c_str()));
    }
  }
  PetscCall(PetscFinalize());
  return 0;
}
