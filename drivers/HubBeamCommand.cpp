// `strand run SCENE` for a hub_beam scene (src/ffr, issue 5): the floating-frame hub-beam of seed
// 001, integrated on PETSc TS (ffr/HubBeamDynamics.hpp), written as HDF5 + XDMF like any run:
//   /bodies/beam, /frames/beam/centerline (a row per frame): the deformed beam in the inertial frame, sampled at
//       41 points (coordinates: the deformation coordinates d);
//   /series/{time, theta, omega, tip_ux, tip_uy, tip_vy, kinetic, strain, hub_torque, hub_work,
//       energy, newton_iterations, rejected_steps}, one value per step;
//   root attributes status (ok | diverged), discretization, coupling, integrator, dt, wall_time_s.
// The system is small: every rank integrates the same copy; rank 0 writes.
#include <petscsys.h>

#include <cmath>

#include "Commands.hpp"
#include "Progress.hpp"
#include "Signals.hpp"
#include "SolveGuard.hpp"
#include "strand/core/Error.hpp"
#include "strand/ffr/HubBeamDynamics.hpp"
#include "strand/ffr/RadialPointInterpolation.hpp"
#include "strand/io/OutputWriter.hpp"

namespace strand::drivers {

namespace {

constexpr int kSamples = 41;

// The beam's centerline r = Theta (a + x + u_x, u_y) at kSamples points; w_c by the trapezoidal rule
// over the samples (a picture; the tip's u_x in /series is exact).
io::BodyFrame beamFrame(const ffr::HubBeam& hb, double theta, const Eigen::VectorXd& q) {
  const auto d = q.tail(hb.deformationSize());
  const double L = hb.desc().length, a = hb.desc().hubRadius;
  const double c = hb.desc().coupling == model::HubBeamCoupling::FirstOrder ? 1.0 : 0.0;
  io::BodyFrame f;
  f.coordinates.assign(d.data(), d.data() + d.size());
  ffr::ShapeRows r;
  double wc = 0.0, lastSlope2 = 0.0;
  for (int k = 0; k < kSamples; ++k) {
    const double x = L * k / (kSamples - 1);
    hb.basis().shapes(x, r);
    const double slope = r.bendingSlope.dot(d);
    if (k > 0) wc -= 0.25 * (slope * slope + lastSlope2) * L / (kSamples - 1);
    lastSlope2 = slope * slope;
    const double ux = a + x + r.axial.dot(d) + c * wc, uy = r.bending.dot(d);
    f.centerline.insert(f.centerline.end(),
                        {std::cos(theta) * ux - std::sin(theta) * uy, std::sin(theta) * ux + std::cos(theta) * uy, 0.0});
  }
  return f;
}

std::string methodKey(const model::HubBeamDesc& d) {
  return d.mark.where() + ".discretization";
}

}  // namespace

int runHubBeam(MPI_Comm comm, const model::SceneDescription& scene, const std::string& out) {
  int rank;
  MPI_Comm_rank(comm, &rank);
  auto say = [&](const std::string& s) {
    if (rank == 0) std::printf("%s\n", s.c_str());
  };
  const model::HubBeamDesc& desc = scene.hubBeam;
  for (const char* option : {"-restart", "-checkpoint", "-checkpoint_every", "-wall_time"}) {
    PetscBool set = PETSC_FALSE;
    PetscOptionsHasName(nullptr, nullptr, option, &set);
    if (set)
      throw InputError(desc.mark.where() + ": " + option + " is not supported for hub_beam scenes yet (a run takes "
                       "seconds; rerun it instead)");
  }
  std::unique_ptr<ffr::HubBeam> hb;
  try {  // bad input (a singular RPIM moment matrix, a support too small) before any file exists
    hb = std::make_unique<ffr::HubBeam>(desc);
  } catch (const ffr::SingularMomentMatrix& e) {
    throw InputError(methodKey(desc) + ".alpha_c: " + e.what());
  } catch (const std::invalid_argument& e) {
    throw InputError(methodKey(desc) + ".alpha_s: " + e.what());
  }
  const model::DynamicsDesc& dyn = scene.dynamics;
  ffr::HubBeamDynamics solver(*hb, dyn);
  applyOptions(comm, [&] { return solver.setFromOptions(); });

  io::RunInfo info{scene.file, "dynamic", kVersion, 2};
  io::BodyLayout layout{"beam", "HubBeam", 1, 1, hb->deformationSize(), kSamples, {}};
  io::OutputWriter writer(comm, out, info, {layout});
  const std::string coupling = desc.coupling == model::HubBeamCoupling::FirstOrder ? "first_order" : "zero_order";
  writer.setAttribute("discretization", hb->basis().name());
  writer.setAttribute("coupling", coupling);
  writer.setAttribute("integrator", solver.schemeName());
  writer.setAttribute("dt", dyn.dt);
  say("strand " + std::string(kVersion) + ": " + scene.file + ": hub-beam, " + hb->basis().name() + ", " +
      std::to_string(hb->size()) + " unknowns, " + coupling + " coupling, " + (desc.driven ? "driven" : "free") +
      " hub; " + solver.schemeName() + ", dt " + fmt("%g s", dyn.dt));

  Progress progress(comm);
  double nextOut = 0.0;
  long newtonTotal = 0;
  ffr::HubBeamStep last;
  double energy0 = 0.0;  // E at t = 0: a free hub starts with kinetic energy
  auto onStep = [&](const ffr::HubBeamStep& s, const Eigen::VectorXd& q, const Eigen::VectorXd&) {
    const bool final = s.time >= dyn.tEnd * (1.0 - 1e-12);
    bool frame = final || s.step == 0;
    if (dyn.dtOut > 0.0) {
      if (s.time >= nextOut * (1.0 - 1e-12)) {
        frame = true;
        while (nextOut <= s.time * (1.0 + 1e-12)) nextOut += dyn.dtOut;
      }
    } else if (s.step % dyn.outputEvery == 0) {
      frame = true;
    }
    const auto& o = s.obs;
    const std::pair<const char*, double> series[] = {
        {"time", s.time},          {"theta", o.theta},           {"omega", o.omega},
        {"tip_ux", o.tipUx},       {"tip_uy", o.tipUy},          {"tip_vy", o.tipVy},
        {"kinetic", o.kinetic},    {"strain", o.strain},         {"hub_torque", o.hubTorque},
        {"hub_work", s.hubWork},   {"energy", s.energy()},       {"newton_iterations", double(s.newtonIterations)},
        {"rejected_steps", double(s.rejectedSteps)}};
    for (const auto& [name, value] : series) writer.writeScalarSeries(name, value);
    if (frame) writer.writeFrame(s.time, {rank == 0 ? beamFrame(*hb, o.theta, q) : io::BodyFrame{}});
    newtonTotal += s.newtonIterations;
    if (s.step == 0) energy0 = s.energy();
    last = s;
    progress.update("t " + fmt("%.4f s", s.time) + "  omega " + fmt("%.4f rad/s", o.omega) + "  tip (" +
                        fmt("%.4e", o.tipUx) + ", " + fmt("%.4e", o.tipUy) + ") m",
                    s.time / dyn.tEnd);
  };
  std::string failure;
  solver.setStopCheck([&] {  // every rank integrates the same steps: agree after each
    int stop = stopSignal() != 0 ? 1 : 0;
    MPI_Allreduce(MPI_IN_PLACE, &stop, 1, MPI_INT, MPI_MAX, comm);
    return stop != 0;
  });
  PetscLogDouble t0, t1;
  PetscTime(&t0);
  const std::string error = guardSolve(comm, [&] { return solver.run(onStep, &failure); });
  if (!error.empty())
    failure = "the hub-beam integration failed after t = " + fmt("%.6g", last.time) + " s, step " +
              std::to_string(last.step) + ": " + error + ". Try a smaller dynamics.dt, or check the scene's values";
  PetscTime(&t1);
  progress.finish();
  const int code = !failure.empty() ? kExitDiverged : solver.stoppedByRequest() ? kExitStopped : kExitSuccess;
  writer.setAttribute("status", code == kExitSuccess ? "ok" : code == kExitStopped ? "stopped" : "diverged");
  writer.setAttribute("wall_time_s", t1 - t0);
  writer.close();
  if (code == kExitStopped) {
    say("stopped by " + std::string(signalName(stopSignal())) + " at t = " + fmt("%.6g s", last.time) + ", step " +
        std::to_string(last.step) + " (hub_beam runs have no checkpoint); output so far: " + out + " (status = stopped)");
    return code;
  }
  if (code != kExitSuccess) {
    if (rank == 0) std::fprintf(stderr, "strand: error: %s\n", failure.c_str());
    say("output so far: " + out + " (readable, status = diverged)");
    return code;
  }
  say("steps " + std::to_string(last.step) + ", Newton iterations " + std::to_string(newtonTotal) + ", t " +
      fmt("%.6g s", last.time) + ": tip in the floating frame u_x " + fmt("%.9e m", last.obs.tipUx) + ", u_y " +
      fmt("%.9e m", last.obs.tipUy) + "; hub torque " + fmt("%.6g N m", last.obs.hubTorque) +
      "; energy balance drift " + fmt("%.3e J", last.energy() - energy0));
  say("wall time " + fmt("%.3f s", t1 - t0) + "; output: " + out + " (+ " + writer.xdmfPath() + ")");
  return code;
}

}  // namespace strand::drivers
