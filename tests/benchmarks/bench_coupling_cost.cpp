// What it costs on this host that ranks wait for each other: the same fixed work per rank, once
// with an MPI_Allreduce after every chunk (as a step's ghost exchanges, norms and interface solves
// couple the ranks) and once with no communication at all.
//
// Every rank streams y += a x over its own vectors (default 3e6 doubles, 24 MB each, above the
// caches: a memory-bound load like the sweeps and vector updates of a step) in chunks of `-chunk`
// entries (default 1e6, about 1 ms here; a 1e5-element step synchronizes about every 2 ms),
// `-passes` times over the vectors. Uncoupled, the run takes as long as the slower rank's own
// work; coupled, each chunk takes as long as the slower rank's chunk, so the coupled run is slower
// by the waiting that the host's varying speeds cause (a core slowed now on one rank, now on the
// other), plus the reductions themselves (about 1 us each here). With -compute the load is
// compute-bound instead (multiply-add chains on data in the L1 cache, like an element loop).
// Alternates the two `-rounds` times and prints one JSON line per round and a summary with the
// median of coupled / uncoupled.
// Meaningful under mpirun -n 2; on one rank the ratio is the reductions' own cost.
//   bench_coupling_cost [-n 3000000] [-chunk 1000000] [-passes 1000] [-rounds 5]
//   bench_coupling_cost -compute [-chunk 40000] [-passes 90] ...
#include <petscsys.h>

#include <algorithm>
#include <vector>

#include "support/SlowestRank.hpp"

namespace {

// One chunk of work on entries i0..i1: memory-bound (y += a x, 24 bytes per entry from memory) or
// compute-bound (the same count of entries, each a chain of 16 multiply-adds on the first 512
// entries of y, which stay in the L1 cache).
void chunkOfWork(std::vector<double>& y, const std::vector<double>& x, std::size_t i0, std::size_t i1, bool compute) {
  if (!compute) {
    for (std::size_t i = i0; i < i1; ++i) y[i] += 1e-9 * x[i];
    return;
  }
  for (std::size_t i = i0; i < i1; ++i) {
    double v = y[i % 512];
    for (int k = 0; k < 16; ++k) v = v * 0.999999999 + 1e-12;
    y[i % 512] = v;
  }
}

// seconds for `passes` passes of the work over all entries, chunk by chunk, the slowest rank's
double timedPasses(std::vector<double>& y, const std::vector<double>& x, PetscInt chunk, PetscInt passes, bool compute,
                   bool coupled) {
  const std::size_t n = x.size(), step = static_cast<std::size_t>(chunk);
  return strand::testing::slowestRankSeconds(PETSC_COMM_WORLD, [&] {
    double token = 0.0, sum = 0.0;
    for (PetscInt p = 0; p < passes; ++p)
      for (std::size_t i0 = 0; i0 < n; i0 += step) {
        chunkOfWork(y, x, i0, std::min(n, i0 + step), compute);
        if (coupled) MPI_Allreduce(&token, &sum, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
      }
  });
}

}  // namespace

int main(int argc, char** argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  PetscInt n = 3000000, chunk = 1000000, passes = 1000, rounds = 5;
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-n", &n, nullptr));
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-rounds", &rounds, nullptr));
  PetscBool compute = PETSC_FALSE;
  PetscCall(PetscOptionsGetBool(nullptr, nullptr, "-compute", &compute, nullptr));
  if (compute) chunk = 40000, passes = 90;  // an entry costs 16 dependent multiply-adds: ~1 ms chunks, ~2 s
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-chunk", &chunk, nullptr));
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-passes", &passes, nullptr));
  PetscCheck(n > 0 && chunk > 0 && passes > 0 && rounds > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE,
             "bench_coupling_cost: -n, -chunk, -passes and -rounds must be positive");
  PetscMPIInt ranks;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &ranks));
  std::vector<double> x(static_cast<std::size_t>(n), 1.0), y(static_cast<std::size_t>(n), 2.0);
  timedPasses(y, x, chunk, 1, false, false);  // touch the pages once before timing
  std::vector<double> ratios;
  for (PetscInt r = 0; r < rounds; ++r) {
    const double coupled = timedPasses(y, x, chunk, passes, compute, true);
    const double alone = timedPasses(y, x, chunk, passes, compute, false);
    ratios.push_back(coupled / alone);
    PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                          "{\"bench\": \"coupling_cost\", \"load\": \"%s\", \"ranks\": %d, \"chunk\": %d, "
                          "\"chunks\": %d, "
                          "\"coupled_s\": %.4f, \"uncoupled_s\": %.4f, \"ratio\": %.4f}\n",
                          compute ? "compute" : "memory", static_cast<int>(ranks), static_cast<int>(chunk),
                          static_cast<int>(passes * ((n + chunk - 1) / chunk)), coupled, alone, coupled / alone));
  }
  std::vector<double> sorted = ratios;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t m = sorted.size();
  const double median = m % 2 ? sorted[m / 2] : 0.5 * (sorted[m / 2 - 1] + sorted[m / 2]);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                        "{\"bench\": \"coupling_cost_summary\", \"load\": \"%s\", \"ranks\": %d, \"rounds\": %d, "
                        "\"median_ratio\": %.4f, \"min_ratio\": %.4f, \"max_ratio\": %.4f}\n",
                        compute ? "compute" : "memory", static_cast<int>(ranks), static_cast<int>(rounds), median,
                        sorted.front(), sorted.back()));
  PetscCall(PetscFinalize());
  return y[0] < 0.0;
}
