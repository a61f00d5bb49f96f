// Parameter sweeps of the linearized modes (`strand sweep`): angular speed (gamma or omega), the
// mass ratio alpha or the location beta of a point mass (seed 003). At each point: the steady state
// (SNES, warm-started from the previous point), the modes (ModalSolver, reusing its factorization
// pattern and warm-started for angular-speed sweeps), MAC against the previous point, vibration
// nodes; afterwards tracking and veering / crossing detection (ModeTracking.hpp).
#pragma once
#include <petscsys.h>

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "strand/model/SceneDescription.hpp"
#include "strand/solvers/ModeTracking.hpp"

namespace strand::solvers {

struct SweepResult {
  std::string parameterName;                     // gamma, omega, mass_ratio, mass_location, transport_speed
  std::vector<double> parameter;                 // per point
  std::vector<double> gamma;                     // dimensionless angular speed per point
  std::vector<std::vector<double>> omega;        // [point][sorted mode], rad/s
  std::vector<std::vector<double>> omegaBar;     // omega sqrt(rho A L^4 / EI)
  std::vector<std::vector<double>> residual;     // relative residual per mode
  std::vector<std::vector<double>> macNext;      // [point][a * count + b], point to point + 1
  std::vector<std::vector<int>> label;           // tracked mode of each sorted mode
  std::vector<std::vector<std::string>> kind;    // [point][sorted mode]: what it is (solvers/ModeLabels.hpp)
  std::vector<LociEvent> events;                 // veering and crossing
  std::vector<std::vector<std::vector<double>>> nodes;  // [point][mode]: vibration nodes x / L on body 0
  std::vector<std::vector<std::vector<double>>> shapes; // [point][mode]: body-0 node displacements (rank 0)
  std::string method;                            // modal method used
  // transport_speed sweeps: the divergence (critical) speed of the steady flow, where the lowest
  // frequency falls to zero (ModalSolver::divergenceFactor); NaN when not computed, +inf if none
  double criticalSpeed = std::numeric_limits<double>::quiet_NaN();
  double maxRealPart = 0.0;                      // quadratic problems: max |Re lambda| / |lambda|
  double seconds = 0.0;                          // wall time of the sweep
  std::string failure;                           // non-empty: the steady state failed at a point
  bool stopped = false;                          // the stop check ended the sweep after a point
};

using SweepProgress = std::function<void(int point, const SweepResult&)>;

// `stop`, if given, is asked after every point on every rank; when it returns true on any rank the
// sweep ends there (result->stopped; tracking and events over the points done).
PetscErrorCode runSweep(MPI_Comm comm, const model::SceneDescription& scene, SweepResult* result,
                        const SweepProgress& progress = nullptr, const std::function<bool()>& stop = nullptr);

}  // namespace strand::solvers
