#include "strand/solvers/Schemes.hpp"

#include <cmath>

namespace strand::solvers {

namespace {
bool adaptiveBdf(const model::DynamicsDesc& d) { return d.integrator == model::Integrator::Bdf && d.adaptive; }
}  // namespace

std::string schemeName(const model::DynamicsDesc& desc) {
  switch (desc.integrator) {
    case model::Integrator::Newmark: return "Newmark (average acceleration)";
    case model::Integrator::Hht: return "HHT-alpha";
    case model::Integrator::Bdf:
      return "BDF" + std::to_string(desc.bdfOrder) + (adaptiveBdf(desc) ? " (adaptive step)" : " (fixed step)");
    case model::Integrator::Rk4: return "RK4 (explicit)";
    case model::Integrator::Abm4: return "Adams-Bashforth-Moulton 4 (explicit)";
    default: return "generalized-alpha";
  }
}

AlphaParams alphaParams(const model::DynamicsDesc& desc) {
  if (desc.integrator == model::Integrator::Hht) {
    const double a = desc.hhtAlpha;
    return {0.0, a, 0.5 + a, 0.25 * (1.0 + a) * (1.0 + a)};
  }
  if (desc.integrator == model::Integrator::GeneralizedAlpha) return GeneralizedAlphaParamsFromRadius(desc.rhoInf);
  return {0.0, 0.0, 0.5, 0.25};  // Newmark
}

PetscErrorCode configureTimeStepping(TS ts, const model::DynamicsDesc& desc) {
  PetscFunctionBeginUser;
  const bool adaptive = adaptiveBdf(desc);
  PetscCall(TSSetTimeStep(ts, desc.dt));
  PetscCall(TSSetMaxTime(ts, desc.tEnd));
  PetscCall(TSSetMaxSteps(ts, adaptive ? PETSC_MAX_INT - 1
                                       : static_cast<PetscInt>(std::ceil(desc.tEnd / desc.dt - 1e-9)) + 1));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  // fixed step: the first Newton failure ends the run with a message instead of a silent cut;
  // adaptive: a failed Newton is a rejected step, retried with a smaller one
  PetscCall(TSSetMaxSNESFailures(ts, adaptive ? -1 : 1));
  PetscCall(TSSetErrorIfStepFails(ts, PETSC_FALSE));
  TSAdapt adapt;
  PetscCall(TSGetAdapt(ts, &adapt));
  PetscCall(TSAdaptSetType(adapt, adaptive ? TSADAPTBASIC : TSADAPTNONE));
  if (adaptive) {
    PetscCall(TSSetTolerances(ts, desc.atol, nullptr, desc.rtol, nullptr));
    PetscCall(TSAdaptSetStepLimits(adapt, kMinStepFraction * desc.dt, desc.tEnd));
  }
  PetscFunctionReturn(0);
}

std::string stabilityNote(const model::DynamicsDesc& desc) {
  if (desc.integrator != model::Integrator::Bdf || desc.bdfOrder < 3) return {};
  // band of h omega on the imaginary axis where the largest root exceeds 1, and that root's maximum
  static const char* const kBand[] = {"0 < h omega < 1.94 (up to 4.6 % per step)", "0 < h omega < 4.71 (up to 19 %)",
                                      "0.71 < h omega < 9.39 (up to 38 %)"};
  return "BDF" + std::to_string(desc.bdfOrder) + " is not A-stable: an undamped mode with " +
         kBand[std::min(desc.bdfOrder, 5) - 3] + " grows; use BDF2 or generalized-alpha. ";
}

}  // namespace strand::solvers
