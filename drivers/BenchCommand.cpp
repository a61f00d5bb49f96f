// `strand bench work-precision SCENE`: speed against accuracy of the time integrators on a dynamic
// scene (issue 3). Runs every scheme of -schemes at every step of -dts (no output files), measures
// the wall time of the integration and the error at t_end against a reference run, and writes JSON
// lines (stdout and <stem>_work_precision.jsonl) plus a PNG of error against wall time
// (<stem>_work_precision.png, drivers/plot/strand_plot.py). Error: the largest distance between
// a cable node's (or rigid body's) position and the reference's, in metres.
#include <petscsys.h>
#include <petsctime.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "Commands.hpp"
#include "strand/core/Error.hpp"
#include "strand/io/SceneReader.hpp"
#include "strand/solvers/Dynamics.hpp"
#include "strand/solvers/Problem.hpp"

namespace strand::drivers {
namespace {

std::string option(const char* name, const std::string& fallback) {
  char buf[PETSC_MAX_PATH_LEN] = "";
  PetscBool set = PETSC_FALSE;
  PetscOptionsGetString(nullptr, nullptr, name, buf, sizeof(buf), &set);
  return set ? buf : fallback;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, sep))
    if (!item.empty()) out.push_back(item);
  return out;
}

// "generalized_alpha[:rho]", "newmark", "hht[:alpha]", "bdf[:order]", "rk4", "abm4" -> the scene's
// dynamics with that scheme; InputError names the option otherwise.
model::DynamicsDesc schemeFrom(const std::string& spec, model::DynamicsDesc d) {
  const auto parts = split(spec, ':');
  const std::string name = parts.empty() ? "" : parts[0];
  const bool arg = parts.size() > 1;
  auto number = [&] {
    try {
      return std::stod(parts[1]);
    } catch (const std::exception&) {
      throw InputError("-schemes: '" + spec + "': '" + parts[1] + "' is not a number");
    }
  };
  d.adaptive = false;
  if (name == "generalized_alpha") {
    d.integrator = model::Integrator::GeneralizedAlpha;
    if (arg) d.rhoInf = number();
  } else if (name == "newmark") {
    d.integrator = model::Integrator::Newmark;
  } else if (name == "hht") {
    d.integrator = model::Integrator::Hht;
    if (arg) d.hhtAlpha = number();
  } else if (name == "bdf") {
    d.integrator = model::Integrator::Bdf;
    d.bdfOrder = arg ? static_cast<int>(number()) : 2;
    if (d.bdfOrder < 1 || d.bdfOrder > 5) throw InputError("-schemes: '" + spec + "': BDF order must lie in 1..5");
  } else if (name == "rk4") {
    d.integrator = model::Integrator::Rk4;
  } else if (name == "abm4") {
    d.integrator = model::Integrator::Abm4;
  } else {
    throw InputError("-schemes: unknown scheme '" + spec +
                     "'; allowed: generalized_alpha[:rho_inf], newmark, hht[:alpha], bdf[:order], rk4, abm4");
  }
  return d;
}

struct Outcome {
  std::vector<double> positions;  // node and rigid-body positions at t_end (all ranks)
  double seconds = 0.0, newtonPerStep = 0.0;
  long steps = 0;
  std::string failure;
};

Outcome integrate(MPI_Comm comm, const model::SceneDescription& scene, const model::DynamicsDesc& d) {
  solvers::Problem p(comm, scene);
  Vec X, V;
  PetscCallAbort(comm, p.createInitialState(&X, &V));
  solvers::Dynamics dyn(p.assembler(), d);
  PetscCallAbort(comm, dyn.setFromOptions());
  Outcome o;
  long newton = 0;
  solvers::Dynamics::StepCallback cb = [&](const solvers::DynamicsStep& s, Vec, Vec) -> PetscErrorCode {
    newton += s.newtonIterations;
    o.steps = s.step;
    return 0;
  };
  PetscLogDouble t0, t1;
  PetscTime(&t0);
  PetscCallAbort(comm, dyn.run(X, V, cb, &o.failure));
  PetscTime(&t1);
  o.seconds = t1 - t0;
  o.newtonPerStep = o.steps > 0 ? double(newton) / o.steps : 0.0;
  std::vector<double> q;
  PetscCallAbort(comm, p.assembler().gatherToRoot(X, q));
  const model::Model& m = p.model();
  const int dim = m.dim();
  std::vector<int> blocks;
  for (const model::Body& b : m.bodies()) blocks.insert(blocks.end(), b.posBlock.begin(), b.posBlock.end());
  for (const model::RigidBody& r : m.rigidBodies()) blocks.push_back(r.posBlock);
  o.positions.assign(blocks.size() * dim, 0.0);
  if (!q.empty())
    for (size_t k = 0; k < blocks.size(); ++k)
      for (int i = 0; i < dim; ++i) o.positions[k * dim + i] = q[blocks[k] * dim + i];
  MPI_Bcast(o.positions.data(), static_cast<int>(o.positions.size()), MPI_DOUBLE, 0, comm);
  VecDestroy(&X);
  VecDestroy(&V);
  return o;
}

double distance(const std::vector<double>& a, const std::vector<double>& b, int dim) {
  double worst = 0.0;
  for (size_t k = 0; k + dim <= a.size(); k += dim) {
    double s = 0.0;
    for (int i = 0; i < dim; ++i) s += (a[k + i] - b[k + i]) * (a[k + i] - b[k + i]);
    worst = std::max(worst, std::sqrt(s));
  }
  return worst;
}

std::string jsonEscape(const std::string& s) {
  std::string out;
  for (char c : s) out += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
  return out;
}

}  // namespace

int runWorkPrecision(const char* scenePath) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  return guarded(comm, [&] {
    const model::SceneDescription scene = io::readScene(scenePath);
    if (scene.analysis != model::Analysis::Dynamic)
      throw InputError(std::string(scenePath) + ": analysis: work-precision needs a dynamic scene");
    checkMemory(comm, scene, false);
    const model::DynamicsDesc& base = scene.dynamics;
    const bool joints = !scene.joints.empty();
    const std::string defaultSchemes = joints ? "generalized_alpha,newmark,hht" : "generalized_alpha,newmark,bdf:2,rk4,abm4";
    std::vector<model::DynamicsDesc> schemes;
    std::vector<std::string> names = split(option("-schemes", defaultSchemes), ',');
    for (const std::string& s : names) {
      schemes.push_back(schemeFrom(s, base));
      if (joints && model::isFirstOrder(schemes.back().integrator))
        throw InputError("-schemes: '" + s + "' takes no joints, and " + scenePath + " has joints");
    }
    auto positive = [](const std::string& text, const char* what) {
      double v = 0.0;
      try {
        v = std::stod(text);
      } catch (const std::exception&) {
        throw InputError(std::string(what) + ": '" + text + "' is not a number");
      }
      if (!(v > 0.0)) throw InputError(std::string(what) + ": '" + text + "' must be a positive step [s]");
      return v;
    };
    std::vector<double> dts;
    for (const std::string& s : split(option("-dts", ""), ',')) dts.push_back(positive(s, "-dts"));
    if (dts.empty())
      for (double f : {4.0, 2.0, 1.0, 0.5, 0.25}) dts.push_back(base.dt * f);
    double dtMin = dts[0];
    for (double h : dts) dtMin = std::min(dtMin, h);
    const std::string refSpec = option("-reference", joints ? "generalized_alpha:0.9" : "rk4");
    const auto refParts = split(refSpec, '@');
    if (refParts.empty()) throw InputError("-reference: give SCHEME[@DT]");
    model::DynamicsDesc ref = schemeFrom(refParts[0], base);
    if (joints && model::isFirstOrder(ref.integrator))
      throw InputError("-reference: '" + refSpec + "' takes no joints, and " + scenePath + " has joints");
    ref.dt = refParts.size() > 1 ? positive(refParts[1], "-reference") : dtMin / 8.0;
    const std::filesystem::path stem = std::filesystem::path(option("-o", std::filesystem::path(scenePath).stem().string()));
    const std::string jsonl = stem.string() + "_work_precision.jsonl", png = stem.string() + "_work_precision.png";
    int rank;
    MPI_Comm_rank(comm, &rank);
    std::ofstream out;
    if (rank == 0) out.open(jsonl);
    auto emit = [&](const std::string& line) {
      if (rank == 0) {
        std::printf("%s\n", line.c_str());
        std::fflush(stdout);
        out << line << "\n";
      }
    };
    const Outcome reference = integrate(comm, scene, ref);
    if (!reference.failure.empty())
      throw SolveError("the reference run (" + refSpec + ", dt " + fmt("%g", ref.dt) + ") failed: " + reference.failure +
                       " Choose another with -reference SCHEME@DT.");
    char line[1024];
    std::snprintf(line, sizeof(line),
                  "{\"bench\": \"work_precision_reference\", \"scene\": \"%s\", \"scheme\": \"%s\", \"dt\": %.6e, "
                  "\"seconds\": %.6e}",
                  jsonEscape(scenePath).c_str(), refSpec.c_str(), ref.dt, reference.seconds);
    emit(line);
    const int dim = scene.dimension;
    for (size_t s = 0; s < schemes.size(); ++s)
      for (double h : dts) {
        model::DynamicsDesc d = schemes[s];
        d.dt = h;
        const Outcome o = integrate(comm, scene, d);
        const bool failed = !o.failure.empty();
        char error[32] = "null";  // failed runs have no error
        if (!failed) std::snprintf(error, sizeof(error), "%.6e", distance(o.positions, reference.positions, dim));
        std::ostringstream text;
        text << "{\"bench\": \"work_precision\", \"scene\": \"" << jsonEscape(scenePath) << "\", \"scheme\": \""
             << names[s] << "\", \"dt\": " << fmt("%.6e", h) << ", \"steps\": " << o.steps
             << ", \"seconds\": " << fmt("%.6e", o.seconds) << ", \"newton_per_step\": " << fmt("%.4f", o.newtonPerStep)
             << ", \"failed\": " << (failed ? "true" : "false") << ", \"error\": " << error << "}";
        emit(text.str());
      }
    if (rank == 0) {
      out.close();
      const std::string cmd = std::string("/usr/bin/python3 ") + STRAND_PLOT_SCRIPT + " lines " + jsonl +
                              " --where bench=work_precision --where failed=False -x seconds -y error --group scheme "
                              "--loglog --xlabel 'wall time [s]' --ylabel 'position error at t_end [m]' --title '" +
                              std::filesystem::path(scenePath).filename().string() + ": error against wall time' -o " +
                              png + " > /dev/null";
      if (std::system(cmd.c_str()) == 0) std::printf("chart: %s\n", png.c_str());
      else std::printf("chart not drawn (needs /usr/bin/python3 with matplotlib): %s\n", cmd.c_str());
    }
    return kExitSuccess;
  });
}

}  // namespace strand::drivers
