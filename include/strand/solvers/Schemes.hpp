// What a scene's `dynamics` section means for a PETSc TS, shared by the ANCF dynamics
// (Dynamics.hpp) and the floating-frame hub-beam (ffr/HubBeamDynamics.hpp).
#pragma once
#include <petscts.h>

#include <string>

#include "strand/model/SceneDescription.hpp"
#include "strand/solvers/GeneralizedAlpha.hpp"

namespace strand::solvers {

// The scheme's name for messages, e.g. "BDF2 (fixed step)", "generalized-alpha".
std::string schemeName(const model::DynamicsDesc& desc);
// Arnold & Bruls 2007 parameters of the generalized-alpha family (alpha_m, alpha_f weight the start
// of the step): Newmark, HHT from hht_alpha, generalized-alpha from rho_inf. Others: Newmark's.
AlphaParams alphaParams(const model::DynamicsDesc& desc);
// Adaptive BDF: the smallest step the controller may choose, as a fraction of the first step. PETSc
// accepts a step at this limit whatever its error, so the dynamics stop there instead (a collapse).
constexpr double kMinStepFraction = 1e-10;
// Step, final time, step count (landing on t_end), a fixed step's first Newton failure ending the
// run (adaptive BDF: a rejected step), and the adaptor (BDF adaptive: TSADAPTBASIC with rtol/atol).
PetscErrorCode configureTimeStepping(TS ts, const model::DynamicsDesc& desc);
// BDF 3-5 are not A-stable: an undamped mode grows while h omega lies in lower < h omega < upper on
// the imaginary axis, by up to `growth` per step there (largest root of rho(zeta) - i h omega
// sigma(zeta), computed; Hairer & Wanner, Solving ODEs II, V.2). Orders 3, 4, 5 (above 5: 5's).
struct GrowthBand {
  double lower, upper, growth;
};
GrowthBand bdfGrowthBand(int order);
// For a failure message: why the scheme itself can fail on an undamped model (BDF 3-5: the band
// above), or empty.
std::string stabilityNote(const model::DynamicsDesc& desc);

}  // namespace strand::solvers
