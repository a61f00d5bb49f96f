// Checkpoints of `strand run` for dynamic scenes (docs/user-guide.md, "Batch jobs"): the options,
// and the glue between solvers::Dynamics (ResumeState) and io::Checkpoint (model-numbered HDF5).
#pragma once
#include <mpi.h>
#include <petscvec.h>

#include <string>

#include "strand/io/Checkpoint.hpp"
#include "strand/model/SceneDescription.hpp"
#include "strand/solvers/Dynamics.hpp"
#include "strand/solvers/Problem.hpp"

namespace strand::drivers {

struct CheckpointOptions {
  std::string path;     // -checkpoint FILE, default <output stem>.ckpt.h5
  int every = 0;        // -checkpoint_every N steps (0: only at the wall-time limit)
  double wallTime = 0;  // -wall_time SECONDS (0: none)
  std::string restart;  // -restart FILE
};

// The options (InputError on negative values); `output` gives the default checkpoint path.
CheckpointOptions checkpointOptions(const std::string& output);

// Writes the integrator's state at the current TS time (X, V: its coordinates and velocities).
void writeDynamicsCheckpoint(MPI_Comm comm, const model::SceneDescription& scene, solvers::Problem& problem,
                             solvers::Dynamics& dyn, Vec X, Vec V, const std::string& path);

// Reads `path` and checks it against the scene (coordinates, dt, time before t_end); InputError
// names the file and what differs. Collective.
io::CheckpointData readRestart(MPI_Comm comm, const model::SceneDescription& scene, const model::Model& model,
                               const std::string& path);

// InputError unless the checkpoint was written by the integrator `dyn` runs (scheme, parameters, TS
// type): called before any output is opened.
void checkRestartIntegrator(const io::CheckpointData& data, const std::string& path, const solvers::Dynamics& dyn);

// Loads X, V and the integrator's state from `data` into dyn (its next run() continues there) and
// returns the checkpointed step. InputError if the integrator differs or a vector is missing.
int resumeDynamics(MPI_Comm comm, const io::CheckpointData& data, const std::string& path, solvers::Problem& problem,
                   solvers::Dynamics& dyn, Vec X, Vec V);

}  // namespace strand::drivers
