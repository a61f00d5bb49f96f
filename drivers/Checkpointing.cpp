// Checkpoints of dynamic runs (Checkpointing.hpp).
#include "Checkpointing.hpp"

#include <petscsys.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <filesystem>

#include "Commands.hpp"
#include "strand/core/Error.hpp"

namespace strand::drivers {
namespace {

std::string stringOption(const char* name) {
  char buf[PETSC_MAX_PATH_LEN] = "";
  PetscBool set = PETSC_FALSE;
  PetscOptionsGetString(nullptr, nullptr, name, buf, sizeof(buf), &set);
  return set ? buf : "";
}

}  // namespace

CheckpointOptions checkpointOptions(const std::string& output) {
  CheckpointOptions o;
  o.path = stringOption("-checkpoint");
  if (o.path.empty()) {
    const std::filesystem::path p(output);
    o.path = (p.parent_path() / (p.stem().string() + ".ckpt.h5")).string();
  }
  PetscInt every = 0;
  PetscReal wall = 0.0;
  PetscOptionsGetInt(nullptr, nullptr, "-checkpoint_every", &every, nullptr);
  PetscOptionsGetReal(nullptr, nullptr, "-wall_time", &wall, nullptr);
  if (every < 0) throw InputError("-checkpoint_every " + std::to_string(every) + ": must be >= 0 (steps)");
  if (wall < 0) throw InputError("-wall_time: must be >= 0 (seconds)");
  o.every = static_cast<int>(every);
  o.wallTime = wall;
  o.restart = stringOption("-restart");
  return o;
}

// The scene's integrator state in model numbering (io/Checkpoint.hpp).
void writeDynamicsCheckpoint(MPI_Comm comm, const model::SceneDescription& scene, solvers::Problem& problem,
                             solvers::Dynamics& dyn, Vec X, Vec V, const std::string& path) {
  solvers::ResumeState s;
  PetscCallAbort(comm, dyn.saveState(&s));
  io::CheckpointData c;
  c.scene = scene.file;
  c.integrator = dyn.signature();
  c.scalars = {{"time", s.time},
               {"step", s.step},
               {"dt", scene.dynamics.dt},
               {"coordinates", problem.model().numDofs()},
               {"dissipated_work", s.last.dissipated},
               {"support_work", s.last.supportWork},
               {"energy_initial", s.e0},
               {"energy_scale", s.energyScale},
               {"damping_power", s.lastDampingPower},
               {"support_power", s.lastSupportPower},
               {"load_work", s.last.loadWork},
               {"load_power", s.lastLoadPower},
               {"exact_restart", dyn.exactRestart() ? 1.0 : 0.0}};
  std::vector<std::pair<std::string, Vec>> vecs{{"X", X}, {"V", V}};
  if (s.A) vecs.push_back({"A", s.A});
  if (s.a) vecs.push_back({"a", s.a});
  for (const auto& [name, v] : vecs) PetscCallAbort(comm, problem.assembler().toModelOrder(v, c.vectors[name]));
  // ABM4's history: f_k = (u', v') per entry; fixed-step BDF's: y_k = (u, v); each half in model numbering
  if (s.newtonStart >= 0) c.scalars["newton_start"] = s.newtonStart;  // generalized-alpha's Newton start
  if (s.stepCuts > 0) {  // generalized-alpha mid-way back from a step cut: the next step is nominal / 2^cuts
    c.scalars["step_cuts"] = s.stepCuts;
    c.scalars["nominal_step"] = s.nominalStep;
  }
  if (problem.assembler().hasContactHistory()) {  // the bristle law's deflections: (body, element, pulley, point, z)
    c.scalars["contact_time"] = s.contactTime;
    c.vectors["contact_history"] = s.contactHistory;
  }
  c.scalars["history_count"] = s.historyCount;
  c.scalars["history_step"] = s.historyStep;
  if (!s.historyTimes.empty()) {  // fixed-step BDF: states y_k (not rates) at these times
    c.scalars["bdf_order"] = s.bdfOrder;
    c.scalars["bdf_steps"] = s.bdfSteps;
    for (size_t k = 0; k < s.historyTimes.size(); ++k) c.scalars["history_time_" + std::to_string(k)] = s.historyTimes[k];
  }
  if (s.historyCount > 0) {
    Vec u, v;
    PetscCallAbort(comm, VecDuplicate(X, &u));
    PetscCallAbort(comm, VecDuplicate(X, &v));
    for (int k = 0; k < s.historyCount; ++k) {
      PetscCallAbort(comm, dyn.stateSpace()->unpack(s.history[k], u, v));
      PetscCallAbort(comm, problem.assembler().toModelOrder(u, c.vectors["f" + std::to_string(k) + "_u"]));
      PetscCallAbort(comm, problem.assembler().toModelOrder(v, c.vectors["f" + std::to_string(k) + "_v"]));
    }
    VecDestroy(&u);
    VecDestroy(&v);
  }
  io::writeCheckpoint(comm, path, c);
}

namespace {
// A whole number in [lo, hi] (a step or count written as a double attribute).
bool wholeIn(double v, double lo, double hi) { return v >= lo && v <= hi && v == std::floor(v); }
}  // namespace

// -restart FILE: read and check against the scene (InputError names the file and what differs).
// Every value the restart uses is checked here, before any output exists: a checkpoint is input
// (issue 32 items 1, 2, 5: a NaN dt, a negative time or a step of 1e300 were accepted).
io::CheckpointData readRestart(MPI_Comm comm, const model::SceneDescription& scene, const model::Model& model,
                               const std::string& path) {
  size_t contactSlots = 0;  // the bristle law's history: 5 numbers per point at most
  for (const model::PulleyContactSet& c : model.contacts())
    contactSlots += static_cast<size_t>(model.bodies()[c.body].elements) * c.pulleys.size() * c.points;
  io::CheckpointData data =
      io::readCheckpoint(comm, path, std::max(static_cast<size_t>(model.numDofs()), 5 * contactSlots));
  const auto& sc = data.scalars;
  auto fail = [&](const std::string& why) { throw InputError(path + ": -restart: " + why); };
  for (const auto& [key, value] : sc)  // the energy sums, times and counters alike
    if (!std::isfinite(value)) fail("'" + key + "' is " + fmt("%g", value) + ", not a finite number");
  auto need = [&](const char* key) {
    if (!sc.count(key)) fail(std::string("the checkpoint has no '") + key + "'");
    return sc.at(key);
  };
  const model::DynamicsDesc& d = scene.dynamics;
  if (need("coordinates") != model.numDofs())
    fail("the checkpoint has " + fmt("%.0f", need("coordinates")) + " coordinates, this scene " +
         std::to_string(model.numDofs()) + ": it was written for another model");
  if (std::fabs(need("dt") - d.dt) > 1e-12 * d.dt)
    fail("the checkpoint's dt " + fmt("%g", need("dt")) + " differs from dynamics.dt " + fmt("%g", d.dt) + " of " +
         scene.file);
  const double time = need("time"), step = need("step");
  if (time < 0.0) fail("the checkpoint's time " + fmt("%g", time) + " s is negative");
  if (time >= d.tEnd * (1.0 - 1e-12))
    fail("the checkpoint is at t = " + fmt("%g", time) + " s, not before dynamics.t_end = " + fmt("%g", d.tEnd) +
         " s: nothing to continue");
  if (!wholeIn(step, 0.0, INT_MAX)) fail("the checkpoint's step " + fmt("%g", step) + " is not a step number 0.." + std::to_string(INT_MAX));
  // fixed steps: step n ends at n dt (an adaptive run's steps have no fixed length); step cuts only
  // add steps
  if (!d.adaptive && d.stepCuts == 0 && std::fabs(step - time / d.dt) > 0.5)
    fail("step " + fmt("%.0f", step) + " and t = " + fmt("%.17g", time) + " s do not agree with dt " + fmt("%g", d.dt) +
         " (step n ends at n dt; a run with dynamics.step_cuts may take more steps: give the scene's)");
  if (!d.adaptive && d.stepCuts > 0 && step < time / d.dt - 0.5)
    fail("step " + fmt("%.0f", step) + " at t = " + fmt("%.17g", time) + " s: fewer steps than t / dt " +
         fmt("%g", time / d.dt) + " (step cuts only add steps)");
  if (sc.count("newton_start") && !wholeIn(sc.at("newton_start"), 0.0, 2.0)) fail("newton_start must be 0, 1 or 2");
  if (sc.count("step_cuts") && (!wholeIn(sc.at("step_cuts"), 1.0, 10.0) || !sc.count("nominal_step") ||
                                !(sc.at("nominal_step") > 0.0 && sc.at("nominal_step") <= d.dt * (1.0 + 1e-12))))
    fail("step_cuts must be 1..10 with a nominal_step in (0, dt]");
  if (sc.count("step_cuts") && sc.at("step_cuts") > d.stepCuts)
    fail("the checkpoint is " + fmt("%.0f", sc.at("step_cuts")) + " step cut(s) below dt, more than the scene's " +
         "dynamics.step_cuts (" + std::to_string(d.stepCuts) + ") allow");
  if (sc.count("bdf_order") && !wholeIn(sc.at("bdf_order"), 1.0, 5.0)) fail("bdf_order must be 1..5");
  if (sc.count("bdf_steps") && !wholeIn(sc.at("bdf_steps"), 0.0, INT_MAX)) fail("bdf_steps must be a step count");
  for (const auto& [key, value] : sc)
    if (key.rfind("history_time_", 0) == 0 && (value < 0.0 || value > time)) fail("'" + key + "' is not within [0, time]");
  // every dataset the restart will read, present, of the model's size and finite (checked on rank 0)
  int rank;
  MPI_Comm_rank(comm, &rank);
  std::string problem;
  if (rank == 0) {
    const size_t n = static_cast<size_t>(model.numDofs());
    auto check = [&](const std::string& name) {
      const auto it = data.vectors.find(name);
      if (it == data.vectors.end()) problem = "the checkpoint lacks /" + name;
      else if (it->second.size() != n)
        problem = "/" + name + " has " + std::to_string(it->second.size()) + " values, the model " + std::to_string(n);
      else if (!std::all_of(it->second.begin(), it->second.end(), [](double x) { return std::isfinite(x); }))
        problem = "/" + name + " holds values that are not finite";
    };
    check("X");
    check("V");
    if (data.vectors.count("A") || data.vectors.count("a")) {
      check("A");
      check("a");
    }
    const double count = sc.count("history_count") ? sc.at("history_count") : 0.0;
    if (!wholeIn(count, 0.0, 7.0)) problem = "history_count must be 0..7";
    else if (count > 0.0 && !sc.count("history_step")) problem = "the checkpoint has no 'history_step'";
    else if (sc.count("bdf_order") && !sc.count("bdf_steps")) problem = "the checkpoint has no 'bdf_steps'";
    for (int k = 0; sc.count("bdf_order") && k < static_cast<int>(count) && problem.empty(); ++k)
      if (!sc.count("history_time_" + std::to_string(k)))
        problem = "the checkpoint has no 'history_time_" + std::to_string(k) + "'";
    for (int k = 0; k < static_cast<int>(count) && problem.empty(); ++k) {
      check("f" + std::to_string(k) + "_u");
      check("f" + std::to_string(k) + "_v");
    }
  }
  int len = static_cast<int>(problem.size());
  MPI_Bcast(&len, 1, MPI_INT, 0, comm);
  problem.resize(len);
  MPI_Bcast(problem.data(), len, MPI_CHAR, 0, comm);
  if (!problem.empty()) fail(problem);
  return data;
}

void checkRestartIntegrator(const io::CheckpointData& data, const std::string& path, const solvers::Dynamics& dyn) {
  if (data.integrator != dyn.signature())
    throw InputError(path + ": -restart: the checkpoint was written by " + data.integrator +
                     ", this run integrates with " + dyn.signature());
}

int resumeDynamics(MPI_Comm comm, const io::CheckpointData& data, const std::string& path, solvers::Problem& problem,
                   solvers::Dynamics& dyn, Vec X, Vec V) {
  int rank;
  MPI_Comm_rank(comm, &rank);
  checkRestartIntegrator(data, path, dyn);
  int missing = 0;
  if (rank == 0)
    for (const char* n : {"X", "V"}) missing += data.vectors.count(n) ? 0 : 1;
  MPI_Bcast(&missing, 1, MPI_INT, 0, comm);
  if (missing) throw InputError(path + ": -restart: the checkpoint lacks /X or /V");
  const auto& sc = data.scalars;
  solvers::ResumeState s;
  s.time = sc.at("time");
  s.step = static_cast<int>(std::lround(sc.at("step")));
  s.last.time = s.time;
  s.last.step = s.step;
  s.last.dissipated = sc.count("dissipated_work") ? sc.at("dissipated_work") : 0.0;
  s.last.supportWork = sc.count("support_work") ? sc.at("support_work") : 0.0;
  s.e0 = sc.count("energy_initial") ? sc.at("energy_initial") : 0.0;
  s.energyScale = sc.count("energy_scale") ? sc.at("energy_scale") : 0.0;
  s.lastDampingPower = sc.count("damping_power") ? sc.at("damping_power") : 0.0;
  s.lastSupportPower = sc.count("support_power") ? sc.at("support_power") : 0.0;
  s.last.loadWork = sc.count("load_work") ? sc.at("load_work") : 0.0;
  s.lastLoadPower = sc.count("load_power") ? sc.at("load_power") : 0.0;
  auto load = [&](const char* name, Vec v) {
    static const std::vector<double> none;
    const auto it = data.vectors.find(name);
    PetscCallAbort(comm, problem.assembler().fromModelOrder(it == data.vectors.end() ? none : it->second, v));
  };
  load("X", X);
  load("V", V);
  Vec A = nullptr, a = nullptr;
  int hasAlpha = rank == 0 && data.vectors.count("A") && data.vectors.count("a") ? 1 : 0;
  MPI_Bcast(&hasAlpha, 1, MPI_INT, 0, comm);
  if (!hasAlpha && !dyn.stateSpace())
    throw InputError(path + ": -restart: the checkpoint has no accelerations /A, /a (written with "
                     "-dyn_ts_type alpha2, whose state is private: not restartable)");
  if (hasAlpha) {
    PetscCallAbort(comm, VecDuplicate(X, &A));
    PetscCallAbort(comm, VecDuplicate(X, &a));
    load("A", A);
    load("a", a);
    s.A = A;
    s.a = a;
  }
  if (sc.count("newton_start")) s.newtonStart = static_cast<int>(sc.at("newton_start"));
  if (sc.count("step_cuts")) {
    s.stepCuts = static_cast<int>(sc.at("step_cuts"));
    s.nominalStep = sc.at("nominal_step");
  }
  const int historyCount = sc.count("history_count") ? static_cast<int>(sc.at("history_count")) : 0;
  if (historyCount > 0 && dyn.stateSpace()) {
    s.historyCount = historyCount;
    s.historyStep = sc.at("history_step");
    if (sc.count("bdf_order")) {
      s.bdfOrder = static_cast<int>(sc.at("bdf_order"));
      s.bdfSteps = static_cast<int>(sc.at("bdf_steps"));
      for (int k = 0; k < historyCount; ++k) s.historyTimes.push_back(sc.at("history_time_" + std::to_string(k)));
    }
    Vec hu, hv;
    PetscCallAbort(comm, VecDuplicate(X, &hu));
    PetscCallAbort(comm, VecDuplicate(X, &hv));
    for (int k = 0; k < historyCount; ++k) {
      load(("f" + std::to_string(k) + "_u").c_str(), hu);
      load(("f" + std::to_string(k) + "_v").c_str(), hv);
      PetscCallAbort(comm, dyn.stateSpace()->createState(&s.history[k]));
      PetscCallAbort(comm, dyn.stateSpace()->pack(hu, hv, s.history[k]));
    }
    VecDestroy(&hu);
    VecDestroy(&hv);
  }
  if (problem.assembler().hasContactHistory()) {  // rank 0 read it: every rank takes its own points
    if (!sc.count("contact_time")) throw InputError(path + ": -restart: the checkpoint has no bristle friction history");
    s.contactTime = sc.at("contact_time");
    const auto it = data.vectors.find("contact_history");
    int n = rank == 0 && it != data.vectors.end() ? static_cast<int>(it->second.size()) : 0;
    MPI_Bcast(&n, 1, MPI_INT, 0, comm);
    if (n % 5 != 0) throw InputError(path + ": -restart: /contact_history holds " + std::to_string(n) + " numbers, not 5 per point");
    s.contactHistory.assign(static_cast<size_t>(n), 0.0);
    if (rank == 0 && n > 0) s.contactHistory = it->second;
    MPI_Bcast(s.contactHistory.data(), n, MPI_DOUBLE, 0, comm);
    for (int i = 0; i < n; ++i)
      if (!std::isfinite(s.contactHistory[i]) || (i % 5 < 4 && !wholeIn(s.contactHistory[i], 0.0, 1e9)))
        throw InputError(path + ": -restart: /contact_history[" + std::to_string(i) + "] = " +
                         fmt("%g", s.contactHistory[i]) + " is not " + (i % 5 < 4 ? "an index" : "a finite deflection"));
  }
  PetscCallAbort(comm, dyn.resumeFrom(s));
  VecDestroy(&A);
  VecDestroy(&a);
  for (Vec& v : s.history) VecDestroy(&v);
  return s.step;
}

}  // namespace strand::drivers
