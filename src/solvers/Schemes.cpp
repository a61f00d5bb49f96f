#include "strand/solvers/Schemes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

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
  PetscCall(TSSetMaxSteps(ts, adaptive || desc.stepCuts > 0 ? PETSC_MAX_INT - 1
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

GrowthBand bdfGrowthBand(int order) {
  static const GrowthBand kBand[] = {{0.0, 1.9359, 0.046}, {0.0, 4.7137, 0.19}, {0.7110, 9.3914, 0.38}};
  return kBand[std::min(std::max(order, 3), 5) - 3];
}

std::string stabilityNote(const model::DynamicsDesc& desc) {
  if (desc.integrator != model::Integrator::Bdf || desc.bdfOrder < 3) return {};
  const GrowthBand b = bdfGrowthBand(desc.bdfOrder);
  char band[96];
  std::snprintf(band, sizeof band, "%.2g < h omega < %.3g (up to %.2g %%%s)", b.lower, b.upper, 100.0 * b.growth,
                desc.bdfOrder == 3 ? " per step" : "");
  return "BDF" + std::to_string(desc.bdfOrder) + " is not A-stable: an undamped mode with " + band +
         " grows; use BDF2 or generalized-alpha. ";
}

}  // namespace strand::solvers
