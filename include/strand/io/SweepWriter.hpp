// Output of `strand sweep`: one HDF5 file and two CSV files (rank 0 writes; collective call).
//
// <path> (HDF5):
//   /                       attrs strand_version, scene_file, analysis = "sweep", parameter (name),
//                           method (modal method), status ("ok" | "failed"), failure (message),
//                           wall_time_s, points, modes, dimension, max_real_part
//   /sweep/parameter        double P           swept values (gamma, omega, mass ratio or location)
//   /sweep/gamma            double P           dimensionless angular speed at each point
//   /sweep/omega            double P x n       sorted frequencies, rad/s
//   /sweep/omega_bar        double P x n       omega sqrt(rho A L^4 / EI)
//   /sweep/residual         double P x n       relative residual of each eigenpair
//   /sweep/label            int    P x n       tracked locus of sorted mode k (its index at point 0)
//   /sweep/loci_omega_bar   double n x P       omega_bar of tracked locus l along the sweep
//   /sweep/mac              double (P-1) x n x n   MAC(sorted a at i, sorted b at i+1)
//   /sweep/shapes           double P x n x nodes x dim   body-0 nodal displacements of each mode
//   /sweep/node_count       int    P x n       vibration nodes of each mode (interior sign changes)
//   /sweep/nodes            double P x n x maxNodes  their positions x / L, NaN-padded
//   /sweep/events/{kind, lower, point, parameter, gap, omega_bar, exchange, mixing, mode_shift,
//                  refined} one entry per veering or crossing (kind: 0 veering, 1 crossing; gap and
//                           omega_bar are dimensionless; point is on the coarse grid, parameter,
//                           gap, omega_bar and mixing come from the local refinement when refined = 1)
// <stem>.csv         one row per point: point, parameter, gamma, omega_bar_1..n (sorted),
//                    locus_1..n (omega_bar of each tracked locus)
// <stem>_events.csv  one row per event: kind, loci (1-based pair), point, parameter, gap_bar,
//                    omega_bar, exchange, mixing, mode_shift, refined
// A sweep that stopped early (status "failed") writes the points computed so far.
#pragma once
#include <mpi.h>

#include <string>

#include "strand/solvers/Sweep.hpp"

namespace strand::io {

struct SweepInfo {
  std::string sceneFile, version;
  int dimension = 3;
};

// Throws std::runtime_error on all ranks when a file cannot be written.
void writeSweep(MPI_Comm comm, const std::string& path, const SweepInfo& info, const solvers::SweepResult& r);

std::string sweepCsvPath(const std::string& h5Path);        // <stem>.csv next to the HDF5 file
std::string sweepEventsCsvPath(const std::string& h5Path);  // <stem>_events.csv

// Omega_bar of each tracked locus along the sweep: loci[l][i] (NaN where locus l was not found).
std::vector<std::vector<double>> trackedLoci(const solvers::SweepResult& r);

}  // namespace strand::io
