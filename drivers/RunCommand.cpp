// `strand run` and `strand modes`: read a scene, build the problem, solve, write HDF5 + XDMF.
//
// Bad input is found before any output file exists (scene reader and model build first), so a
// wrong scene leaves nothing behind. A diverging solve keeps every frame written so far, marks the
// file with status = "diverged" and exits with code 3 and a message naming the load step (statics)
// or the time and step (dynamics).
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <sstream>

#include "Checkpointing.hpp"
#include "Commands.hpp"
#include "FileSafety.hpp"
#include "Progress.hpp"
#include "Signals.hpp"
#include "SolveGuard.hpp"
#include "strand/core/Error.hpp"
#include "strand/io/Checkpoint.hpp"
#include "strand/io/Frames.hpp"
#include "strand/io/OutputWriter.hpp"
#include "strand/io/Probes.hpp"
#include "strand/io/ResourceEstimate.hpp"
#include "strand/io/SceneReader.hpp"
#include "strand/solvers/Dynamics.hpp"
#include "strand/solvers/ModalSolver.hpp"
#include "strand/solvers/ModeLabels.hpp"
#include "strand/solvers/Problem.hpp"
#include "strand/solvers/StaticSolver.hpp"

namespace strand::drivers {

const char* kVersion = "0.1.0";

std::string outputPath(const model::SceneDescription& scene) {
  char buf[PETSC_MAX_PATH_LEN] = "";
  PetscBool set = PETSC_FALSE;
  PetscOptionsGetString(nullptr, nullptr, "-o", buf, sizeof(buf), &set);
  if (set) return buf;
  const std::string path =
      scene.output.file.empty() ? std::filesystem::path(scene.file).stem().string() + ".h5" : scene.output.file;
  PetscBool restart = PETSC_FALSE;
  PetscOptionsHasName(nullptr, nullptr, "-restart", &restart);
  if (!restart) return path;
  // a restarted run must not overwrite the output of the run it continues, nor an earlier restart's
  const std::filesystem::path p(path);
  for (int k = 1;; ++k) {
    const std::string suffix = k == 1 ? "_restart" : "_restart" + std::to_string(k);
    const std::filesystem::path candidate = p.parent_path() / (p.stem().string() + suffix + p.extension().string());
    if (!std::filesystem::exists(candidate)) return candidate.string();
  }
}

void applyOptions(MPI_Comm comm, const std::function<PetscErrorCode()>& setFromOptions) {
  const std::string error = guardSolve(comm, setFromOptions);
  if (!error.empty()) throw InputError("PETSc options: " + error);
}

// -output_commit_interval <s> (default 2): the output file is committed at least this often while
// buffered frames or series wait (OutputWriter.hpp, "Buffering"); 0 commits at every write.
io::OutputWriter::CommitPolicy outputCommitPolicy() {
  io::OutputWriter::CommitPolicy policy;
  PetscReal interval = policy.intervalSeconds;
  PetscBool set = PETSC_FALSE;
  PetscOptionsGetReal(nullptr, nullptr, "-output_commit_interval", &interval, &set);
  if (set && !(interval >= 0.0 && std::isfinite(interval)))
    throw InputError("-output_commit_interval " + fmt("%g", interval) + ": a time in seconds >= 0 (default 2)");
  policy.intervalSeconds = interval;
  return policy;
}

void checkMemory(MPI_Comm comm, const model::SceneDescription& scene, bool modal) {
  char buf[64] = "";
  PetscBool set = PETSC_FALSE;
  PetscOptionsGetString(nullptr, nullptr, "-max_memory", buf, sizeof(buf), &set);
  const double limit = set ? io::parseBytes(buf) : 0.0;
  if (set && limit <= 0.0) throw InputError(std::string("-max_memory ") + buf + ": not a size (e.g. 64G, 512M)");
  io::checkResources(comm, scene, modal, limit);
}

namespace {

// The rotation vector theta (axis times angle, world frame) of R = A A0^T, the rotation of a 3D rigid
// body since t = 0, from its frame blocks a_k (3 x 3 consecutive) now (a) and at t = 0 (a0).
void incrementalRotation(const double* a0, const double* a, double* theta) {
  double R[3][3] = {};
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) R[i][j] += a[3 * k + i] * a0[3 * k + j];
  const double c = std::clamp(0.5 * (R[0][0] + R[1][1] + R[2][2] - 1.0), -1.0, 1.0), angle = std::acos(c);
  const double w[3] = {R[2][1] - R[1][2], R[0][2] - R[2][0], R[1][0] - R[0][1]}, s = std::sin(angle);
  for (int i = 0; i < 3; ++i) theta[i] = s > 1e-12 ? 0.5 * angle / s * w[i] : 0.5 * w[i];
}

bool hasLoads(const model::SceneDescription& s) {
  auto nz = [](const model::Vec3& v) { return v[0] != 0.0 || v[1] != 0.0 || v[2] != 0.0; };
  return nz(s.loads.gravity) || !s.loads.nodal.empty() || !s.loads.distributed.empty() ||
         (s.rotation.present && s.rotation.omega != 0.0);  // the centrifugal load of a rotating frame
}

class SceneRun {
public:
  SceneRun(MPI_Comm comm, const model::SceneDescription& scene, RunMode mode)
      : _comm(comm), _scene(scene), _mode(mode), _problem(comm, scene), _progress(comm) {
    MPI_Comm_rank(comm, &_rank);
  }

  int execute() {
    const model::Model& m = _problem.model();
    const bool modal = _mode == RunMode::ForceModes || _scene.analysis == model::Analysis::Modes;
    const std::string out = outputPath(_scene);
    const bool dynamic = !modal && _scene.analysis == model::Analysis::Dynamic;
    // Everything that can refuse the run is checked before the output is opened (issue 32 item 2):
    // the files (item 3), the checkpoint and the integrator it was written by.
    RunFiles files = sceneFiles(_scene);
    files.results.push_back({"the output", out});
    files.companions = {{"the output's XDMF file", io::xdmfPathFor(out)}, {"the output's XDMF file", io::modesXdmfPathFor(out)}};
    std::unique_ptr<solvers::Dynamics> dyn;
    if (dynamic) {
      _checkpoint = checkpointOptions(out);
      files.results.push_back({"-checkpoint", _checkpoint.path});
      files.restart = _checkpoint.restart;
    }
    checkRunFiles(files, overwriteRequested());
    _probes = std::make_unique<io::Probes>(_scene, m, _problem.dofs());  // may refuse the scene
    std::unique_ptr<solvers::StaticSolver> statics;  // its PETSc options are input too
    if (!dynamic && (!modal || hasLoads(_scene))) {
      statics = std::make_unique<solvers::StaticSolver>(_problem.assembler(), _scene.statics.loadSteps);
      applyOptions(_comm, [&] { return statics->setFromOptions(); });
    }
    if (dynamic) {
      dyn = std::make_unique<solvers::Dynamics>(_problem.assembler(), _scene.dynamics);
      applyOptions(_comm, [&] { return dyn->setFromOptions(); });
      if (!_checkpoint.restart.empty()) {
        _restart = readRestart(_comm, _scene, _problem.model(), _checkpoint.restart);
        checkRestartIntegrator(_restart, _checkpoint.restart, *dyn);
      }
    }
    io::RunInfo info{_scene.file, modal ? "modes" : dynamic ? "dynamic" : "static", kVersion, m.dim()};
    const io::OutputWriter::CommitPolicy commitPolicy = outputCommitPolicy();  // input: read before the file exists
    _writer = std::make_unique<io::OutputWriter>(_comm, out, info, io::bodyLayouts(m, _scene.output.samplesPerElement));
    _writer->setCommitPolicy(commitPolicy);
    say("strand " + std::string(kVersion) + ": " + _scene.file + ": " + std::to_string(m.numElements()) +
        " elements, " + std::to_string(m.numDofs()) + " coordinates, " + std::to_string(commSize()) + " rank(s)");
    Vec X;
    PetscCallAbort(_comm, _problem.dofs().createVector(&X));
    PetscCallAbort(_comm, _problem.assembler().initialState(X));
    PetscLogDouble t0, t1;
    PetscTime(&t0);
    int code = kExitSuccess;
    std::string failure;
    if (dynamic) {
      code = dynamicSolve(*dyn, X, &failure);  // writes the initial frame itself
    } else {
      writeFrame(X, nullptr, 0.0, 0.0);
      if (statics) code = staticSolve(*statics, X, &failure);
    }
    if (code == kExitSuccess && modal) code = modes(X, &failure);
    PetscTime(&t1);
    _progress.finish();
    _writer->setAttribute("status", code == kExitSuccess ? "ok" : code == kExitWallTime ? "stopped" : "diverged");
    _writer->setAttribute("wall_time_s", t1 - t0);
    _writer->close();
    if (code == kExitWallTime) {
      say(failure);
      say("output so far: " + out + " (readable, status = stopped)");
    } else if (code != kExitSuccess) {
      if (_rank == 0) std::fprintf(stderr, "strand: error: %s\n", failure.c_str());
      say("output so far: " + out + " (readable, status = diverged)");
    } else {
      summary(X);
      say("wall time " + fmt("%.3f s", t1 - t0) + "; output: " + out + " (+ " + _writer->xdmfPath() + ")");
    }
    VecDestroy(&X);
    return code;
  }

private:
  int commSize() const {
    int s;
    MPI_Comm_size(_comm, &s);
    return s;
  }
  void say(const std::string& s) {
    if (_rank == 0) std::printf("%s\n", s.c_str());
  }

  // A frame of the state X (V: its velocities, null in statics) at time t (the contact law's time).
  void writeFrame(Vec X, Vec V, double time, double t) {
    std::vector<double> q;
    PetscCallAbort(_comm, _problem.assembler().gatherToRoot(X, q));
    std::unique_ptr<io::ElementContact> contact;
    if (_problem.assembler().hasContact()) contact = gatherContact(X, V, t);
    std::vector<io::BodyFrame> frames;
    if (_rank == 0) frames = io::makeFrames(_problem.model(), q, _scene.output.samplesPerElement, contact.get());
    _writer->writeFrame(time, frames);
  }

  // What the contact law finds at this rank's contact points, per element, reduced onto rank 0
  // (pressures summed, the largest state; null elsewhere).
  std::unique_ptr<io::ElementContact> gatherContact(Vec X, Vec V, double t) {
    std::vector<assembly::Assembler::ContactPointOut> points;
    PetscCallAbort(_comm, _problem.assembler().contactPoints(X, V, t, points));
    auto out = std::make_unique<io::ElementContact>(_problem.model());
    for (const auto& pt : points) out->add(pt.body, pt.element, pt.state.pressure, pt.state.touching, pt.state.sticking);
    for (size_t b = 0; b < out->pressure.size(); ++b) {
      if (out->points[b] == 0) continue;
      for (auto [field, op] : {std::pair{&out->pressure[b], MPI_SUM}, std::pair{&out->state[b], MPI_MAX}})
        MPI_Reduce(_rank == 0 ? MPI_IN_PLACE : field->data(), field->data(), static_cast<int>(field->size()),
                   MPI_DOUBLE, op, 0, _comm);
    }
    if (_rank != 0) out.reset();
    return out;
  }

  // /series/pulley_<name>_{fx, fy, torque, speed}: what the belts exert on each pulley (force, torque
  // about its centre, counterclockwise) and its speed (a free pulley's from V); a tensioner's
  // pulley_<name>_slide, its slide displacement; statics: the belt at rest, speeds at t = 0.
  PetscErrorCode writePulleySeries(Vec X, Vec V, double t) {
    PetscFunctionBeginUser;
    const std::vector<model::PulleyDesc>& pulleys = _problem.model().pulleys();
    if (pulleys.empty()) PetscFunctionReturn(0);
    std::vector<assembly::Assembler::PulleyLoad> load;
    PetscCall(_problem.assembler().pulleyLoads(X, V, t, load));
    for (size_t p = 0; p < pulleys.size(); ++p) {
      const std::string stem = "pulley_" + pulleys[p].name + "_";
      PetscCallCXX(_writer->writeScalarSeries(stem + "fx", load[p].fx));
      PetscCallCXX(_writer->writeScalarSeries(stem + "fy", load[p].fy));
      PetscCallCXX(_writer->writeScalarSeries(stem + "torque", load[p].torque));
      PetscCallCXX(_writer->writeScalarSeries(stem + "speed", load[p].speed));
      if (pulleys[p].hasSlide) PetscCallCXX(_writer->writeScalarSeries(stem + "slide", load[p].slide));
    }
    PetscFunctionReturn(0);
  }

  // /series/reel_<name>_{angle, speed, content, length}: each reel's angle [rad] and speed [rad/s],
  // the material still wound on it [m] and the unstretched length of the body it pays out
  // (p_N - p_0) [m]: content + length stays the reel's content + the body's initial length.
  PetscErrorCode writeReelSeries(Vec X, Vec V) {
    PetscFunctionBeginUser;
    const model::Model& m = _problem.model();
    if (m.reels().empty()) PetscFunctionReturn(0);
    // per reel phi, phi', p_0, p_N: each read by the rank that owns it, summed onto every rank (no
    // gather of the whole state each step)
    const model::DofMap& dofs = _problem.dofs();
    const int D = m.dim();
    std::vector<double> values(4 * m.reels().size(), 0.0);
    const PetscScalar *x, *v;
    PetscCall(VecGetArrayRead(X, &x));
    PetscCall(VecGetArrayRead(V, &v));
    auto read = [&](const PetscScalar* a, int block, bool coordinate) {  // component 0 of a model block
      const PetscInt g = dofs.globalBlock()[block];
      if (g < dofs.ownedBegin() || g >= dofs.ownedEnd()) return 0.0;
      return a[(g - dofs.ownedBegin()) * D] + (coordinate ? m.initialCoordinates()[block * D] : 0.0);
    };
    for (size_t r = 0; r < m.reels().size(); ++r) {
      const model::Body& b = m.bodies()[m.reelBody(static_cast<int>(r))];
      const int k = b.info().materialBlock(), blk = m.reelBlock(static_cast<int>(r));
      values[4 * r] = read(x, blk, true);
      values[4 * r + 1] = read(v, blk, false);
      values[4 * r + 2] = read(x, b.block(0, k), true);
      values[4 * r + 3] = read(x, b.block(b.elements, k), true);
    }
    PetscCall(VecRestoreArrayRead(X, &x));
    PetscCall(VecRestoreArrayRead(V, &v));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_SUM, _comm));
    for (size_t r = 0; r < m.reels().size(); ++r) {
      const model::ReelDesc& d = m.reels()[r];
      const model::Body& b = m.bodies()[m.reelBody(static_cast<int>(r))];
      const double phi = values[4 * r], length = values[4 * r + 3] - values[4 * r + 2];
      const std::string stem = "reel_" + d.name + "_";
      PetscCallCXX(_writer->writeScalarSeries(stem + "angle", phi));
      PetscCallCXX(_writer->writeScalarSeries(stem + "speed", values[4 * r + 1]));
      PetscCallCXX(_writer->writeScalarSeries(stem + "content", d.content - d.radius * phi));
      PetscCallCXX(_writer->writeScalarSeries(stem + "length", length));
      // a reel that ran empty pays out material it does not have, one that winds the body in
      // shrinks its elements to nothing: stop there (the run ends with this message, its output kept)
      const int stop = !_reelStop.empty() ? 0 : d.content - d.radius * phi < 0.0 ? 1 : length < 1e-3 * b.length ? 2 : 0;
      if (stop == 1)
        _reelStop = "reel '" + d.name + "' ran empty: its content (" + fmt("%g", d.content) +
                    " m) is paid out; give it more 'content' or stop the payout (scene " + _scene.file + ")";
      if (stop == 2)
        _reelStop = "reel '" + d.name + "' wound body '" + b.name + "' in to under 0.1 % of its length (" +
                    fmt("%g", b.length) + " m); its elements shrink to nothing (scene " + _scene.file + ")";
    }
    PetscFunctionReturn(0);
  }

  int staticSolve(solvers::StaticSolver& solver, Vec X, std::string* failure) {
    solver.setStopCheck([] { return stopSignal() != 0; });
    int lastStep = 0;
    double lastFactor = 0.0;
    auto onStep = [&](const solvers::StaticStep& s, Vec Xs) -> PetscErrorCode {
      PetscFunctionBeginUser;
      _newtonTotal += s.newtonIterations;
      lastStep = s.step;
      lastFactor = s.loadFactor;
      _progress.update("load step " + std::to_string(s.step) + "  load factor " + fmt("%.4f", s.loadFactor) +
                       "  Newton " + std::to_string(s.newtonIterations) + "  |R| " + fmt("%.2e", s.residualNorm) +
                       "  e/e1 " + fmt("%.1e", s.energyRatio));
      PetscCallCXX(writeFrame(Xs, nullptr, s.loadFactor, 0.0));
      PetscCallCXX(_writer->writeScalarSeries("load_factor", s.loadFactor));
      PetscCallCXX(_writer->writeScalarSeries("newton_iterations", s.newtonIterations));
      PetscCallCXX(_writer->writeScalarSeries("residual_norm", s.residualNorm));
      PetscCallCXX(_writer->writeScalarSeries("newton_energy_ratio", s.energyRatio));
      PetscCall(_probes->write(*_writer, s.loadFactor, Xs, nullptr, nullptr));
      PetscCall(writePulleySeries(Xs, nullptr, 0.0));
      PetscFunctionReturn(0);
    };
    const std::string error = guardSolve(_comm, [&] { return solver.solve(X, onStep, failure); });
    if (!error.empty())
      *failure = "the static solve failed in load step " + std::to_string(lastStep + 1) + " (from load factor " +
                 fmt("%.4g", lastFactor) + "): " + error + ". Check the supports (a free body or a mechanism has no "
                 "static stiffness) and the scene's values";
    if (failure->empty() && solver.stoppedByRequest()) {
      *failure = "stopped by " + std::string(signalName(stopSignal())) + " after load step " + std::to_string(lastStep) +
                 " (load factor " + fmt("%.4g", lastFactor) + "); a static run has no checkpoint: run it again to finish";
      return kExitStopped;
    }
    return failure->empty() ? kExitSuccess : kExitDiverged;
  }

  // Time integration from the reference shape at rest; a frame every output_every steps and at the
  // end, the energy monitor, Newton iterations, the step size and the rejected steps (since the start)
  // every step (/series).
  int dynamicSolve(solvers::Dynamics& dyn, Vec X, std::string* failure) {
    const model::DynamicsDesc& d = _scene.dynamics;
    Vec V;
    PetscCallAbort(_comm, VecDuplicate(X, &V));
    PetscCallAbort(_comm, _problem.assembler().initialVelocity(V));
    if (!_checkpoint.restart.empty()) {
      _firstStep = resumeDynamics(_comm, _restart, _checkpoint.restart, _problem, dyn, X, V);
      say("restart from " + _checkpoint.restart + " at t = " + fmt("%.6g", _restart.scalars.at("time")) + " s, step " +
          std::to_string(_firstStep));
    }
    _writer->setAttribute("integrator", dyn.schemeName());
    PetscLogDouble start;
    PetscTime(&start);
    bool wallTimeReached = false;
    dyn.setStopCheck([&] {  // the wall-time limit or a batch job's stop signal (Signals.hpp)
      if (_checkpoint.wallTime > 0.0 && !wallTimeReached) {
        PetscLogDouble now;
        PetscTime(&now);
        wallTimeReached = now - start > _checkpoint.wallTime;
      }
      return wallTimeReached || stopSignal() != 0 || !_reelStop.empty();
    });
    _writer->setAttribute("dt", d.dt);
    const bool moving = _problem.model().hasPrescribedMotion();
    const bool joints = _problem.model().hasConstraints();
    const bool timedLoads = _problem.assembler().hasTimedLoads() || _problem.model().hasLoadFunction() ||
                            _problem.assembler().hasConfigurationLoads();  // series load_work
    const bool contact = _problem.assembler().hasContact();
    // next dt_out time (a restart starts with the first multiple at or after its time)
    double nextOut = d.dtOut > 0.0 && !_restart.scalars.empty() ? std::ceil(_restart.scalars.at("time") / d.dtOut - 1e-9) * d.dtOut : 0.0;
    const auto& rigid = _problem.model().rigidBodies();
    const int dim = _problem.model().dim();
    const std::vector<double>& q0 = _problem.model().initialCoordinates();
    solvers::DynamicsStep reached;
    PetscLogDouble lastProgress = 0.0;
    Vec probeForce = nullptr;  // the support forces, when a probe asks for one
    auto onStep = [&](const solvers::DynamicsStep& s, Vec Xs, Vec Vs) -> PetscErrorCode {
      PetscFunctionBeginUser;
      _newtonTotal += s.newtonIterations;
      reached = s;
      const bool last = s.time >= d.tEnd * (1.0 - 1e-12);
      // frames every output_every steps, or at the first step at or after each multiple of dt_out
      const double slack = 1e-9 * d.dt;
      bool frame = last;
      if (d.dtOut > 0.0) {
        if (s.time >= nextOut - slack) frame = true;
        while (nextOut <= s.time + slack) nextOut += d.dtOut;
      } else if (s.step % d.outputEvery == 0) {
        frame = true;
      }
      if (frame) PetscCallCXX(writeFrame(Xs, Vs, s.time, s.time));
      PetscCallCXX(_writer->writeScalarSeries("time", s.time));
      PetscCallCXX(_writer->writeScalarSeries("kinetic_energy", s.kinetic));
      PetscCallCXX(_writer->writeScalarSeries("strain_energy", s.strain));
      PetscCallCXX(_writer->writeScalarSeries("potential_energy", s.potential));
      if (contact) PetscCallCXX(_writer->writeScalarSeries("contact_energy", s.contact));
      PetscCallCXX(_writer->writeScalarSeries("dissipated_work", s.dissipated));
      if (moving) PetscCallCXX(_writer->writeScalarSeries("support_work", s.supportWork));
      if (timedLoads || contact) PetscCallCXX(_writer->writeScalarSeries("load_work", s.loadWork));
      if (joints) {
        PetscCallCXX(_writer->writeScalarSeries("constraint_position", s.constraintPosition));
        PetscCallCXX(_writer->writeScalarSeries("constraint_velocity", s.constraintVelocity));
      }
      if (!rigid.empty() && dim == 3) {  // x, y, z and the rotation vector since t = 0, every step
        std::vector<double> q;
        PetscCall(_problem.assembler().gatherToRoot(Xs, q));
        for (const model::RigidBody& rb : rigid) {
          double x[3] = {0.0, 0.0, 0.0}, theta[3] = {0.0, 0.0, 0.0};
          if (!q.empty()) {
            for (int i = 0; i < 3; ++i) x[i] = q[3 * rb.posBlock + i];
            incrementalRotation(&q0[3 * rb.rotBlock], &q[3 * rb.rotBlock], theta);
          }
          for (int i = 0; i < 3; ++i) {
            PetscCallCXX(_writer->writeScalarSeries("rigid_" + rb.name + "_" + "xyz"[i], x[i]));
            PetscCallCXX(_writer->writeScalarSeries("rigid_" + rb.name + "_theta_" + "xyz"[i], theta[i]));
          }
        }
      } else if (!rigid.empty()) {  // x, y, phi of every rigid body, every step
        std::vector<double> q;
        PetscCall(_problem.assembler().gatherToRoot(Xs, q));
        for (const model::RigidBody& rb : rigid) {
          const double* c = q.empty() ? nullptr : &q[2 * rb.posBlock];
          const double* r = q.empty() ? nullptr : &q[2 * rb.rotBlock];
          PetscCallCXX(_writer->writeScalarSeries("rigid_" + rb.name + "_x", c ? c[0] : 0.0));
          PetscCallCXX(_writer->writeScalarSeries("rigid_" + rb.name + "_y", c ? c[1] : 0.0));
          PetscCallCXX(_writer->writeScalarSeries("rigid_" + rb.name + "_phi", r ? r[0] : 0.0));
        }
      }
      PetscCall(writePulleySeries(Xs, Vs, s.time));
      PetscCall(writeReelSeries(Xs, Vs));
      PetscCallCXX(_writer->writeScalarSeries("energy_balance", s.energy()));
      PetscCallCXX(_writer->writeScalarSeries("newton_iterations", s.newtonIterations));
      PetscCallCXX(_writer->writeScalarSeries("time_step", s.timeStep));
      PetscCallCXX(_writer->writeScalarSeries("rejected_steps", s.rejectedSteps));
      if (!_probes->empty()) {
        if (_probes->needForce()) {
          if (!probeForce) PetscCall(VecDuplicate(Xs, &probeForce));
          PetscCall(dyn.supportForce(probeForce));
        }
        PetscCall(_probes->write(*_writer, s.time, Xs, Vs, probeForce));
      }
      if (_checkpoint.every > 0 && s.step > _firstStep && s.step % _checkpoint.every == 0 && !last && !s.suspect) {
        PetscCallCXX(_writer->flush());  // the output holds every step up to the checkpoint: a restart leaves no gap
        PetscCallCXX(writeDynamicsCheckpoint(_comm, _scene, _problem, dyn, Xs, Vs, _checkpoint.path));
      }
      // the progress line at most every 0.1 s (and at the first and last step): formatting it every
      // step costs 0.4 us, 2 % of the spin-up's step
      PetscLogDouble now;
      PetscCall(PetscTime(&now));
      if (last || s.step == _firstStep || now - lastProgress >= 0.1) {
        lastProgress = now;
        _progress.update("t " + fmt("%.5g", s.time) + " s  step " + std::to_string(s.step) + "  Newton " +
                         std::to_string(s.newtonIterations) + "  E " + fmt("%.6e J", s.energy()),
                         s.time / d.tEnd);
      }
      PetscFunctionReturn(0);
    };
    const std::string error = guardSolve(_comm, [&] { return dyn.run(X, V, onStep, failure); });
    VecDestroy(&probeForce);
    if (!error.empty()) {
      *failure = std::string(dyn.schemeName()) + " failed after t = " + fmt("%.6g", reached.time) + " s, step " +
                 std::to_string(reached.step) + ": " + error + ". Try a smaller dynamics.dt, or check the scene's values";
      VecDestroy(&V);
      return kExitDiverged;
    }
    const std::string newtonStart = dyn.newtonStart();  // the first step's check or a Newton failure may change it
    if (!newtonStart.empty()) {
      _writer->setAttribute("newton_start", newtonStart);
      if (newtonStart != "acceleration")
        say("Newton start in use: the " + newtonStart + " predictor (docs/user-guide.md, \"Newton start\")");
    }
    int code = failure->empty() ? kExitSuccess : kExitDiverged;
    if (code == kExitSuccess && !_reelStop.empty()) {
      solvers::ResumeState at;
      PetscCallAbort(_comm, dyn.saveState(&at));
      *failure = _reelStop + "; stopped at t = " + fmt("%.6g", at.time) + " s, step " + std::to_string(at.step);
      VecDestroy(&V);
      return kExitDiverged;
    }
    if (code == kExitSuccess && dyn.stoppedByRequest()) {
      writeDynamicsCheckpoint(_comm, _scene, _problem, dyn, X, V, _checkpoint.path);
      solvers::ResumeState at;
      PetscCallAbort(_comm, dyn.saveState(&at));
      const std::string why = wallTimeReached ? "at the wall-time limit (-wall_time " + fmt("%g", _checkpoint.wallTime) + " s)"
                                              : "by " + std::string(signalName(stopSignal()));
      *failure = "stopped " + why + " at t = " +
                 fmt("%.6g", at.time) + " s, step " + std::to_string(at.step) + "; checkpoint: " + _checkpoint.path +
                 ". Continue with: strand run " + _scene.file + " -restart " + _checkpoint.path +
                 (dyn.exactRestart() ? "" : " (this integrator restarts its multistep start-up: the continued "
                                            "trajectory differs at the level of its truncation error)");
      code = kExitWallTime;
    }
    VecDestroy(&V);
    return code;
  }

  static constexpr double kModalResidualTolerance = 1e-6;

  int modes(Vec X, std::string* failure) {
    solvers::ModalResult r;
    std::vector<solvers::ModeLabel> labels;
    {
      solvers::ModalSolver solver(_problem.assembler(), solvers::modalOptions(_scene.modes));
      const std::string error = guardSolve(_comm, [&] { return solver.solve(X, &r); });
      for (size_t k = 0; k < r.omega.size() && error.empty(); ++k)
        if (!std::isfinite(r.omega[k]) || !std::isfinite(r.relativeResidual[k]))
          *failure = "the modal solve gave a non-finite frequency (mode " + std::to_string(k + 1) + ")";
      if (!error.empty()) *failure = "the modal solve failed: " + error;
      if (!failure->empty()) {
        *failure += ". Check the supports and the section values";
        solvers::destroyModes(&r);
        return kExitDiverged;
      }
      if (solver.transport()) {
        double factor = 0.0;
        const std::string e = guardSolve(_comm, [&] { return solver.divergenceFactor(&factor); });
        if (e.empty()) reportCriticalSpeed(factor);
        else say("note: the divergence speed could not be computed: " + e);
      }
      const std::string e = guardSolve(
          _comm, [&] { return solvers::labelModes(_problem.assembler(), solver.massMatrix(), r, &labels); });
      if (!e.empty()) say("note: the modes could not be labelled: " + e);
    }
    const double T = _problem.model().scales().time();
    std::vector<double> hz;
    std::vector<std::vector<io::BodyFrame>> shapes;
    // mode shapes are written as the static state plus a scaled mode (scale: 10 % of the longest body)
    double span = 0.0;
    for (const model::Body& b : _problem.model().bodies()) span = std::max(span, b.length);
    Vec Y;
    PetscCallAbort(_comm, VecDuplicate(X, &Y));
    for (size_t k = 0; k < r.omega.size(); ++k) {
      hz.push_back(r.omega[k] / (2.0 * M_PI));
      PetscReal amax;
      PetscCallAbort(_comm, VecNorm(r.shapes[k], NORM_INFINITY, &amax));
      PetscCallAbort(_comm, VecWAXPY(Y, 0.1 * span / amax, r.shapes[k], X));
      std::vector<double> q;
      PetscCallAbort(_comm, _problem.assembler().gatherToRoot(Y, q));
      shapes.push_back(_rank == 0 ? io::makeShapes(_problem.model(), q, _scene.output.samplesPerElement)
                                  : std::vector<io::BodyFrame>{});
      say("mode " + std::to_string(k + 1) + ": " + fmt("%.8g Hz", hz.back()) + "  (" +
          (r.rigid[k] ? std::string("rigid-body mode") : "omega " + fmt("%.8g rad/s", r.omega[k]) + ", omega_bar " +
                                                             fmt("%.8g", r.omega[k] * T)) +
          ", residual " + fmt("%.1e", r.relativeResidual[k]) + ")" +
          (k < labels.size() && !labels[k].name.empty()
               ? "  " + labels[k].name + (labels[k].name == "rigid" ? "" : fmt(" %.0f%%", 100.0 * labels[k].share))
               : ""));
    }
    if (!r.note.empty()) say("note: " + r.note);
    // Every eigenpair whose relative residual exceeds the tolerance is flagged on stderr and in the
    // output (flagged_modes; each mode's relative_residual): its frequency and shape are not to be trusted
    // (issue 36 item 3). -modal_residual_tol sets the tolerance (default 1e-6).
    PetscReal tol = kModalResidualTolerance;
    PetscCallAbort(_comm, PetscOptionsGetReal(nullptr, nullptr, "-modal_residual_tol", &tol, nullptr));
    int flagged = 0;
    for (size_t k = 0; k < r.omega.size(); ++k)
      if (!(r.relativeResidual[k] <= tol)) {
        ++flagged;
        if (_rank == 0)
          std::fprintf(stderr, "strand: warning: mode %zu (%.8g Hz) has relative residual %.1e > %.0e: not converged; "
                               "try more modes (modes.count), -modal_eps_ncv or -modal_st_shift\n",
                       k + 1, hz[k], r.relativeResidual[k], tol);
      }
    _writer->setAttribute("residual_tolerance", tol);
    _writer->setAttribute("flagged_modes", static_cast<double>(flagged));
    if (flagged) say(std::to_string(flagged) + " mode(s) flagged: residual above " + fmt("%.0e", tol) + " (stderr)");
    std::vector<io::OutputWriter::ModeLabelOut> labelsOut;
    for (const solvers::ModeLabel& l : labels) labelsOut.push_back({l.name, l.share});
    _writer->writeModes(hz, shapes, r.relativeResidual, labelsOut);
    VecDestroy(&Y);
    solvers::destroyModes(&r);
    return kExitSuccess;
  }

  // ALE bodies whose material flows: the transport speed at which the steady flow diverges, from
  // the first such body's speed |pdot| lambda (material rate times its initial stretch) and the
  // factor on the rates (ModalSolver::divergenceFactor).
  void reportCriticalSpeed(double factor) {
    double speed = 0.0;
    for (const model::BodyDesc& b : _scene.bodies)
      if (b.hasMaterialMotion && speed == 0.0) speed = std::fabs(b.materialMotion.at(0.0).df) * b.initialStretch;
    _writer->setAttribute("transport_speed", speed);
    if (std::isnan(factor)) {
      say("transport speed " + fmt("%.6g m/s", speed) + "; no critical speed: the span is curved, so its steady "
          "state changes with the speed (its tension rises by rho A v^2, its shape stays: Routh's catenary)");
      return;
    }
    if (std::isinf(factor)) {
      say("transport speed " + fmt("%.6g m/s", speed) + "; the steady flow does not diverge at any speed");
      return;
    }
    say("transport speed " + fmt("%.6g m/s", speed) + "; critical (divergence) speed " + fmt("%.6g m/s", factor * speed) +
        " (" + fmt("%.4g", factor) + " times the current): the lowest frequency falls to zero there");
    _writer->setAttribute("critical_speed", factor * speed);
  }

  void summary(Vec X) {
    std::vector<double> q;
    PetscCallAbort(_comm, _problem.assembler().gatherToRoot(X, q));
    PetscReal U;
    PetscCallAbort(_comm, _problem.assembler().strainEnergy(X, &U));
    if (_rank != 0) return;
    const model::Model& m = _problem.model();
    std::ostringstream s;
    s << "Newton iterations " << _newtonTotal << ", strain energy " << fmt("%.6g J", U);
    say(s.str());
    for (size_t b = 0; b < m.bodies().size(); ++b) {
      const model::Vec3 tip = io::positionOnBody(m, q, static_cast<int>(b), m.bodies()[b].elements - 1, 1.0);
      say("  body '" + m.bodies()[b].name + "': last node at (" + fmt("%.9g", tip[0]) + ", " + fmt("%.9g", tip[1]) +
          ", " + fmt("%.9g", tip[2]) + ")");
    }
  }

  MPI_Comm _comm;
  int _rank = 0;
  model::SceneDescription _scene;
  RunMode _mode;
  solvers::Problem _problem;
  Progress _progress;
  std::unique_ptr<io::OutputWriter> _writer;
  std::unique_ptr<io::Probes> _probes;
  PetscInt _newtonTotal = 0;
  std::string _reelStop;  // why a reel stops the run (writeReelSeries), empty while it may go on
  CheckpointOptions _checkpoint;
  io::CheckpointData _restart;
  int _firstStep = 0;  // the step a restarted run starts from (no checkpoint is rewritten there)
};

}  // namespace

int guarded(MPI_Comm comm, const std::function<int()>& body) {
  int rank;
  MPI_Comm_rank(comm, &rank);
  try {
    return body();
  } catch (const InputError& e) {
    if (rank == 0) std::fprintf(stderr, "strand: bad input: %s\n", e.what());
    return kExitBadInput;
  } catch (const SolveError& e) {
    if (rank == 0) std::fprintf(stderr, "strand: error: %s\n", e.what());
    return kExitDiverged;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strand: internal error on rank %d: %s\n", rank, e.what());
    return kExitInternal;
  }
}

int runScene(const char* scenePath, RunMode mode) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  return guarded(comm, [&] {
    const model::SceneDescription scene = io::readScene(scenePath);
    if (scene.hubBeam.present) {
      checkMemory(comm, scene, false);
      if (mode == RunMode::ForceModes)
        throw InputError(scene.hubBeam.mark.where() + ": 'strand modes' needs a body scene; a hub_beam scene runs "
                         "its dynamics with 'strand run'");
      const std::string out = outputPath(scene);
      RunFiles files = sceneFiles(scene);
      files.results.push_back({"the output", out});
      files.companions.push_back({"the output's XDMF file", io::xdmfPathFor(out)});
      checkRunFiles(files, overwriteRequested());
      return runHubBeam(comm, scene, out);
    }
    if (mode == RunMode::ForceModes) io::requireModalScene(scene);
    checkMemory(comm, scene, mode == RunMode::ForceModes || scene.analysis == model::Analysis::Modes);
    SceneRun run(comm, scene, mode);
    return run.execute();
  });
}

}  // namespace strand::drivers
