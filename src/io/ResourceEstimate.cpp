// Memory estimate of a scene before anything is allocated (io/ResourceEstimate.hpp).
#include "strand/io/ResourceEstimate.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include "strand/core/Error.hpp"
#include "strand/elements/ElementRegistry.hpp"

namespace strand::io {

namespace {

constexpr double kBytesPerElement = 16e3;         // statics, dynamics of a 3D cable (see the header)
constexpr double kModalBytesPerElement = 24e3;    // modes, sweeps, before the mode shapes
constexpr double kCableElementCoordinates = 12.0;  // the 3D cable's, which the per-element bytes are for
constexpr double kBytesPerProcess = 100e6;        // PETSc, MPI, HDF5, the executable
constexpr double kReplicated = 0.25;              // share of the per-element cost every rank holds
constexpr double kPetscIndexMax = 2147483647.0;   // Debian's PETSc has 32-bit indices
constexpr double kOutputPointsMax = INT_MAX / 3;  // centerline points x 3 as an int

// MemAvailable of /proc/meminfo [bytes], or +inf when unknown.
double memAvailable() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kb = 0.0;
  std::string unit;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024.0;
  return std::numeric_limits<double>::infinity();
}

// The memory limit of this process's cgroup (v2, then v1) [bytes], or +inf.
double cgroupLimit() {
  for (const char* path : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
    std::ifstream in(path);
    std::string text;
    if (in >> text && text != "max") {
      char* end = nullptr;
      const double v = std::strtod(text.c_str(), &end);
      if (end && *end == '\0' && v > 0.0) return v;
    }
  }
  return std::numeric_limits<double>::infinity();
}

// Unknowns of a hub_beam's dense system (deformation coordinates plus the hub angle).
double hubBeamSize(const model::HubBeamDesc& h) {
  switch (h.method) {
    case model::HubBeamMethod::Fem: return 3.0 * h.elements + 1.0;
    case model::HubBeamMethod::Rpim: return 2.0 * h.nodes + 1.0;
    case model::HubBeamMethod::AssumedModes: return h.axialModes + h.bendingModes + 1.0;
  }
  return 0.0;
}

[[noreturn]] void refuse(const model::SourceMark& at, const std::string& reason) {
  throw InputError(at.where() + ": " + reason);
}

}  // namespace

ResourceEstimate estimateResources(const model::SceneDescription& scene, bool modal, int ranks, int ranksOnHost) {
  ResourceEstimate e;
  const double share = kReplicated * ranksOnHost + (1.0 - kReplicated) * ranksOnHost / std::max(1, ranks);
  e.bytes = kBytesPerProcess * ranksOnHost;
  if (scene.hubBeam.present) {  // every rank integrates the whole dense system
    const double n = hubBeamSize(scene.hubBeam);
    e.coordinates = n;
    e.bytes += ranksOnHost * 8.0 * n * n * sizeof(double);
    e.largest = scene.hubBeam.mark;
    e.largest.key += ".discretization";
    return e;
  }
  const double perElement = modal ? kModalBytesPerElement : kBytesPerElement;
  const double samples = scene.output.samplesPerElement;
  // mode shapes are held as frames (centerline samples and nodal coordinates) until written
  const double shapes = modal ? scene.modes.count * samples * 3.0 * sizeof(double) : 0.0;
  double most = -1.0;
  for (const model::BodyDesc& b : scene.bodies) {
    const elements::KindInfo& kind = elements::kindInfo(b.kind);
    const double elements = b.elements, nodeCoordinates = 3.0 * kind.blocksPerNode;  // blocks of 3 (BAIJ bs = 3)
    e.coordinates += (elements + 1.0) * nodeCoordinates;
    // element matrices and their share of the sparse matrices grow with the square of the element's size
    const double grow = std::max(1.0, std::pow(2.0 * nodeCoordinates / kCableElementCoordinates, 2));
    const double bytes =
        elements * ((perElement * grow + shapes + (modal ? nodeCoordinates * scene.modes.count * sizeof(double) : 0.0)) * share +
                    samples * 3.0 * sizeof(double));
    e.bytes += bytes + b.geometry.points.size() * sizeof(model::Vec3) * ranksOnHost;
    if (bytes > most) {
      most = bytes;
      e.largest = b.mark;
      e.largest.key += ".elements";
    }
  }
  // rigid bodies (12 coordinates) and joints (up to 6 multipliers, as in a 3D body's frame)
  e.coordinates += 12.0 * scene.rigidBodies.size() + 6.0 * scene.joints.size();
  e.bytes += (scene.rigidBodies.size() + scene.joints.size()) * perElement * share;
  return e;
}

double availableMemory() {
  double limit = std::min(memAvailable(), cgroupLimit());
  struct rlimit rl;
  if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY) limit = std::min(limit, double(rl.rlim_cur));
  return limit;
}

void checkResources(MPI_Comm comm, const model::SceneDescription& scene, bool modal, double limit) {
  int ranks, ranksOnHost;
  MPI_Comm_size(comm, &ranks);
  MPI_Comm host;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &host);
  MPI_Comm_size(host, &ranksOnHost);
  MPI_Comm_free(&host);
  const ResourceEstimate e = estimateResources(scene, modal, ranks, ranksOnHost);
  // what cannot be represented, whatever the memory
  if (e.coordinates > kPetscIndexMax)
    refuse(e.largest, "the scene has up to " + std::to_string(static_cast<long long>(e.coordinates)) +
                          " coordinates, more than PETSc's 32-bit indices hold (2147483647)");
  for (const model::BodyDesc& b : scene.bodies)
    if ((double(b.elements) * scene.output.samplesPerElement + 1.0) > kOutputPointsMax)
      refuse({b.mark.file, b.mark.line, b.mark.key + ".elements"},
             std::to_string(b.elements) + " elements x output.samples_per_element " +
                 std::to_string(scene.output.samplesPerElement) + " is more output points than a body may have (" +
                 std::to_string(static_cast<long long>(kOutputPointsMax)) + ")");
  // every rank compares its host's need with its host's memory; the worst case speaks for all
  const double available = limit > 0.0 ? limit : availableMemory();
  struct {
    double ratio;
    int rank;
  } mine{e.bytes / available, 0}, worst{};
  MPI_Comm_rank(comm, &mine.rank);
  MPI_Allreduce(&mine, &worst, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm);
  double numbers[2] = {e.bytes, available};
  MPI_Bcast(numbers, 2, MPI_DOUBLE, worst.rank, comm);
  if (worst.ratio > 1.0)
    refuse(e.largest, "this run needs about " + formatBytes(numbers[0]) + " of memory (a conservative estimate, " +
                          std::to_string(ranksOnHost) + " process(es) on the host), more than the " +
                          formatBytes(numbers[1]) + (limit > 0.0 ? " of -max_memory" : " available") +
                          "; use fewer elements or more hosts, or set the limit with -max_memory SIZE (e.g. 64G)");
}

double parseBytes(const std::string& text) {
  char* end = nullptr;
  double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || !std::isfinite(v) || v <= 0.0) return -1.0;
  const std::string unit(end);
  const std::string units = "KMGT";
  if (unit.empty() || unit == "B") return v;
  const size_t k = units.find(static_cast<char>(std::toupper(static_cast<unsigned char>(unit[0]))));
  if (k == std::string::npos || (unit.size() > 1 && unit.substr(1) != "B")) return -1.0;
  return v * std::pow(1024.0, static_cast<double>(k + 1));
}

std::string formatBytes(double bytes) {
  const char* units[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
  int u = 0;
  while (bytes >= 1000.0 && u < 6) {
    bytes /= 1000.0;
    ++u;
  }
  char buf[64];
  if (std::isfinite(bytes) && bytes < 1000.0) std::snprintf(buf, sizeof buf, "%.3g %s", bytes, units[u]);
  else std::snprintf(buf, sizeof buf, "%.3g bytes", bytes * std::pow(1000.0, u));
  return buf;
}

}  // namespace strand::io
