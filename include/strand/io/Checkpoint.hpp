// Checkpoint files of a dynamic run (HDF5, written and read by rank 0): everything needed to
// continue the trajectory, in model numbering (scene order), so a run checkpointed on n ranks can
// continue on any number of ranks.
//
// Layout: root attributes format = "strand-checkpoint 1", scene, integrator, plus named scalars
// (time, step, dt, the energy monitor's accumulators; attribute per name); one dataset per named
// vector (/X, /V, and the integrator's state, e.g. /A, /a of generalized-alpha).
#pragma once
#include <mpi.h>

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace strand::io {

struct CheckpointData {
  std::string scene, integrator;
  std::map<std::string, double> scalars;               // all ranks
  std::map<std::string, std::vector<double>> vectors;  // rank 0 only (empty elsewhere)
};

// Writes `path` atomically (a temporary file renamed over it: a crash while writing leaves the
// previous checkpoint intact). Collective; rank 0 writes. Throws std::runtime_error on failure.
void writeCheckpoint(MPI_Comm comm, const std::string& path, const CheckpointData& data);

// Reads a checkpoint. Collective: scalars and names reach every rank, vectors rank 0 only.
// Throws InputError naming the file and the reason (missing, not a checkpoint, unreadable, an
// attribute that is not one number or string, a dataset that is not 1-D numbers or has more than
// maxValues entries: the file is input, nothing is read before its type and size are checked).
CheckpointData readCheckpoint(MPI_Comm comm, const std::string& path, size_t maxValues);

}  // namespace strand::io
