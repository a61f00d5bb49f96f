// Belt-pulley contact: the cost of a time step of a closed belt around two pulleys, and the
// contact's share of it (issue 34; docs/performance.md, "Belt-pulley contact"), on one core.
//
// The belt: AncfCable2d, EA = 1e5 N, rho A = 0.1 kg/m, around two fixed pulleys of r = 0.5 m, their
// centres D apart so that the loop has N elements of about 1 cm; pretension initial_stretch 1.001;
// penalty k = 1e7 N/m^2, 4 contact points per element; frictionless, or regularized Coulomb (mu 0.5,
// v_s = 1e-2 m/s; the belt at rest sticks); generalized-alpha rho_inf 0.8, dt = 1e-4 s, 20 steps.
// Only the wraps (2 pi r of the 2 D + 2 pi r loop) touch: the contact search skips the spans.
// One JSON line per (N, friction): wall time per step, Newton iterations per step, and the time in
// the log event Strand:Asm:Contact (the contact's residual, Newton and damping terms) as a share of
// the run. -repeat R keeps the fastest of R runs.
#include <petscsys.h>
#include <petsctime.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "strand/solvers/Dynamics.hpp"
#include "support/Belts.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

model::SceneDescription beltLoop(int elements, bool friction) {
  BeltLoop spec;  // r = 0.5 m, EA = 1e5 N, k = 1e7 N/m^2
  spec.elements = elements;
  spec.distance = 0.5 * (elements * 0.01 - 2.0 * std::acos(-1.0) * spec.radius);  // elements of 1 cm
  spec.stretch = 1.001;
  model::SceneDescription sc = closedBelt(spec);
  sc.analysis = model::Analysis::Dynamic;
  if (friction) {
    contact::ContactLaw& law = sc.contacts[0].law;
    law.friction = contact::FrictionLaw::RegularizedCoulomb;
    law.mu = 0.5;
    law.slipVelocity = 1e-2;
  }
  return sc;
}

}  // namespace

int main(int argc, char** argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  PetscCall(PetscLogDefaultBegin());
  PetscInt repeat = 3;
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-repeat", &repeat, nullptr));
  for (int elements : {1000, 10000})
    for (bool friction : {false, true}) {
      double best = 1e300, contactShare = 0.0, newton = 0.0;
      std::string failure;
      for (PetscInt k = 0; k < repeat; ++k) {
        solvers::Problem p(PETSC_COMM_WORLD, beltLoop(elements, friction));
        Vec X, V;
        PetscCall(p.createInitialState(&X, &V));
        model::DynamicsDesc d;
        d.rhoInf = 0.8;
        d.dt = 1e-4;
        d.tEnd = 20 * d.dt;
        long iterations = 0;
        {
          solvers::Dynamics dyn(p.assembler(), d);
          PetscCall(dyn.setFromOptions());
          solvers::Dynamics::StepCallback cb = [&](const solvers::DynamicsStep& s, Vec, Vec) -> PetscErrorCode {
            iterations += s.newtonIterations;
            return 0;
          };
          const double c0 = contactSeconds();
          PetscLogDouble t0, t1;
          PetscCall(PetscTime(&t0));
          PetscCall(dyn.run(X, V, cb, &failure));
          PetscCall(PetscTime(&t1));
          const double seconds = t1 - t0;
          if (seconds < best) {
            best = seconds;
            contactShare = (contactSeconds() - c0) / seconds;
            newton = iterations / 20.0;
          }
        }
        VecDestroy(&X);
        VecDestroy(&V);
      }
      std::printf("{\"case\": \"belt_loop\", \"elements\": %d, \"friction\": \"%s\", \"steps\": 20, "
                  "\"seconds_per_step\": %.6g, \"newton_per_step\": %.2f, \"contact_share\": %.3f, \"failure\": \"%s\"}\n",
                  elements, friction ? "coulomb" : "none", best / 20.0, newton, contactShare, failure.c_str());
      std::fflush(stdout);
    }
  PetscCall(PetscFinalize());
  return 0;
}
