// The memory a run will need, estimated from the scene before anything is allocated (issue 32 item
// 9: `elements: 2147483647` used GBs and ended in bad_alloc or hung; a hub_beam with 20,000,000
// elements overflowed an int). The estimate is conservative and independent of the element kinds'
// internals: every node is taken to carry up to 4 blocks of 3 coordinates; per element it costs
// what the measured runs cost per element, scaled to 12 coordinates per node and doubled:
//   measured (3D cable, 6 coordinates per node, one rank): generalized-alpha 4.4 kB, BDF 7 kB per
//   element at 1e5 elements; modes 11.7 kB per element with 20 modes at 2e4 elements.
// So 16 kB per element (statics, dynamics) and 24 kB plus the mode shapes (modes, sweeps), plus
// 100 MB per process. The part of it that every rank holds whole (the model, about a quarter) is
// counted once per rank on the host. A hub_beam is a dense system: 8 dense matrices of its size.
#pragma once
#include <mpi.h>

#include <string>

#include "strand/model/SceneDescription.hpp"

namespace strand::io {

struct ResourceEstimate {
  double bytes = 0.0;          // on one host with `ranksOnHost` of the run's `ranks` processes
  double coordinates = 0.0;    // unknowns, at most 12 per node
  model::SourceMark largest;   // the item that costs the most (a body's elements, a hub_beam's size)
};

// `modal`: the run computes modes (strand modes, analysis: modes, strand sweep).
ResourceEstimate estimateResources(const model::SceneDescription& scene, bool modal, int ranks, int ranksOnHost);

// The memory this process may use: the least of MemAvailable, the cgroup limit and RLIMIT_AS.
double availableMemory();

// Throws InputError (the same on every rank) when the scene cannot be represented (more
// coordinates than a PETSc index, more output points per body than an int) or when the estimate
// exceeds `limit` bytes on some host (limit <= 0: availableMemory() of each host). The message
// names the item that costs the most, the estimate and the limit. Collective.
void checkResources(MPI_Comm comm, const model::SceneDescription& scene, bool modal, double limit);

// "12G", "512M", "2e9": bytes (K, M, G, T: powers of 1024); -1 when the text is not a size.
double parseBytes(const std::string& text);

// "1.5 GB", "312 MB": for messages.
std::string formatBytes(double bytes);

}  // namespace strand::io
