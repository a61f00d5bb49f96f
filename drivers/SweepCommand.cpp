// `strand sweep SCENE`: the modes of the scene along its `sweep` (angular speed, mass ratio or
// mass location), tracked by MAC, with veering and crossing detected; writes HDF5 + CSV.
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "Commands.hpp"
#include "FileSafety.hpp"
#include "Progress.hpp"
#include "Signals.hpp"
#include "SolveGuard.hpp"
#include "strand/core/Error.hpp"
#include "strand/io/SceneReader.hpp"
#include "strand/io/SweepWriter.hpp"
#include "strand/solvers/Sweep.hpp"

namespace strand::drivers {
namespace {

std::string pointLine(int i, int points, const solvers::SweepResult& r) {
  std::string s = "point " + std::to_string(i + 1) + "/" + std::to_string(points) + "  " + r.parameterName + " " +
                  fmt("%.6g", r.parameter.back()) + "  omega_bar";
  const auto& w = r.omegaBar.back();
  for (size_t k = 0; k < w.size() && k < 8; ++k) s += " " + fmt("%.6g", w[k]);
  if (w.size() > 8) s += " ...";
  return s;
}

// After a failure inside a point: the points that are complete in every table, nothing of the
// interrupted one (tracking and events are computed after the sweep, so there are none).
void keepCompletePoints(solvers::SweepResult& r) {
  size_t p = std::min({r.parameter.size(), r.gamma.size(), r.omega.size(), r.omegaBar.size(), r.residual.size()});
  if (!r.nodes.empty()) p = std::min(p, r.nodes.size());
  if (!r.shapes.empty()) p = std::min(p, r.shapes.size());
  r.parameter.resize(p);
  r.gamma.resize(p);
  r.omega.resize(p);
  r.omegaBar.resize(p);
  r.residual.resize(p);
  if (r.nodes.size() > p) r.nodes.resize(p);
  if (r.shapes.size() > p) r.shapes.resize(p);
  if (r.kind.size() > p) r.kind.resize(p);
  r.macNext.resize(std::min(r.macNext.size(), p > 0 ? p - 1 : 0));
  r.label.clear();
  r.events.clear();
}

}  // namespace

int runSweepScene(const char* scenePath) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  int rank;
  MPI_Comm_rank(comm, &rank);
  auto say = [&](const std::string& s) {
    if (rank == 0) std::printf("%s\n", s.c_str());
  };
  return guarded(comm, [&] {
    const model::SceneDescription scene = io::readScene(scenePath);
    if (!scene.sweep.present)
      throw InputError(scene.sweep.mark.where() + ": no 'sweep' section: `strand sweep` needs sweep: {parameter, from, "
                       "to, points} (docs/scene-reference.md#sweep); use `strand modes` for one point");
    checkMemory(comm, scene, true);
    const std::string out = outputPath(scene);
    RunFiles files = sceneFiles(scene);
    files.results.push_back({"the output", out});
    files.companions = {{"the sweep's CSV file", io::sweepCsvPath(out)}, {"the sweep's CSV file", io::sweepEventsCsvPath(out)}};
    checkRunFiles(files, overwriteRequested());
    int size;
    MPI_Comm_size(comm, &size);
    say("strand " + std::string(kVersion) + ": " + scene.file + ": sweep of " + std::to_string(scene.sweep.points) +
        " points, " + std::to_string(scene.modes.count) + " modes, " + std::to_string(size) + " rank(s)");
    Progress progress(comm);
    solvers::SweepResult r;
    const std::string error = guardSolve(comm, [&] {
      return solvers::runSweep(
          comm, scene, &r, [&](int i, const solvers::SweepResult& res) { progress.update(pointLine(i, scene.sweep.points, res)); },
          [] { return stopSignal() != 0; });
    });
    if (!error.empty()) {
      keepCompletePoints(r);
      r.failure = "the sweep failed after " + std::to_string(r.parameter.size()) + " point(s): " + error;
    }
    progress.finish();
    io::writeSweep(comm, out, io::SweepInfo{scene.file, kVersion, scene.dimension}, r);
    for (const auto& e : r.events)
      say(e.kind + " of loci " + std::to_string(e.lower + 1) + "-" + std::to_string(e.lower + 2) + " at " +
          r.parameterName + " " + fmt("%.6g", e.parameter) + ": gap " + fmt("%.4g", e.gap) + " at omega_bar " +
          fmt("%.6g", e.frequency) + ", MAC mixing " + fmt("%.2f", e.mixing) + ", exchange " +
          fmt("%.2f", e.exchange) + (e.modeShift ? " (mode shift)" : ""));
    if (r.events.empty()) say("no veering or crossing among the " + std::to_string(scene.modes.count) + " lowest loci");
    if (!std::isnan(r.criticalSpeed))
      say(std::isinf(r.criticalSpeed)
              ? std::string("the steady flow does not diverge at any transport speed")
              : "critical (divergence) transport speed " + fmt("%.6g", r.criticalSpeed) +
                    " m/s: the lowest frequency falls to zero there; above it the span is statically unstable");
    if (!r.failure.empty()) {
      if (rank == 0) std::fprintf(stderr, "strand: error: %s\n", r.failure.c_str());
      say("output so far: " + out + " (readable, status = failed)");
      return kExitDiverged;
    }
    if (r.stopped) {
      say("stopped by " + std::string(signalName(stopSignal())) + " after " + std::to_string(r.parameter.size()) +
          " of " + std::to_string(scene.sweep.points) + " points; output so far: " + out + " (status = stopped)");
      return kExitStopped;
    }
    say("method " + r.method + ", wall time " + fmt("%.3f s", r.seconds) + " (" +
        fmt("%.4f s", r.seconds / std::max<size_t>(1, r.parameter.size())) + " per point); output: " + out + " (+ " +
        io::sweepCsvPath(out) + ", " + io::sweepEventsCsvPath(out) + ")");
    return kExitSuccess;
  });
}

}  // namespace strand::drivers
