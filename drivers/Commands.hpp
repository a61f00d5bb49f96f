// Subcommands of the `strand` executable. Each returns a process exit code (strand::ExitCode).
#pragma once
#include <cstdio>
#include <functional>
#include <string>

#include <mpi.h>
#include <petscsys.h>

#include "strand/model/SceneDescription.hpp"

namespace strand::drivers {

enum class RunMode { SceneAnalysis, ForceModes };

// `strand run SCENE` (RunMode::SceneAnalysis) and `strand modes SCENE` (RunMode::ForceModes).
int runScene(const char* scenePath, RunMode mode);

// `strand sweep SCENE`: the scene's `sweep` of the linearized modes (SweepCommand.cpp).
int runSweepScene(const char* scenePath);

// `strand bench work-precision SCENE` (BenchCommand.cpp).
int runWorkPrecision(const char* scenePath);

// `strand run SCENE` for a hub_beam scene (HubBeamCommand.cpp), output to `out`.
int runHubBeam(MPI_Comm comm, const model::SceneDescription& scene, const std::string& out);

extern const char* kVersion;

// Runs `body` on every rank and turns exceptions into exit codes and one message (RunCommand.cpp):
// InputError -> 2 ("bad input"), SolveError -> 3, anything else -> 1 (internal, with the rank).
int guarded(MPI_Comm comm, const std::function<int()>& body);

// printf-style formatting of one number.
inline std::string fmt(const char* f, double a) {
  char b[64];
  std::snprintf(b, sizeof(b), f, a);
  return b;
}
// The output file: -o FILE, else the scene's output.file, else <scene stem>.h5 in the working directory.
std::string outputPath(const model::SceneDescription& scene);

// Runs a solver's setFromOptions; a PETSc error there is bad input (InputError "PETSc options: ...").
void applyOptions(MPI_Comm comm, const std::function<PetscErrorCode()>& setFromOptions);

// Refuses (InputError) a scene whose estimated memory exceeds -max_memory SIZE or what the hosts
// have, before anything is allocated (io/ResourceEstimate.hpp). Collective.
void checkMemory(MPI_Comm comm, const model::SceneDescription& scene, bool modal);

}  // namespace strand::drivers
