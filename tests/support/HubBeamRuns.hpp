// Runs of the floating-frame hub-beam (src/ffr) and of the ANCF spin-up for tests and studies:
// the tip deformation in the hub's frame as time series.
#pragma once
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "strand/ffr/HubBeamDynamics.hpp"
#include "strand/io/SceneReader.hpp"
#include "strand/solvers/Dynamics.hpp"
#include "support/Cli.hpp"
#include "support/Scenes.hpp"

namespace strand::testing {

struct TipSeries {
  std::vector<double> t, ux, uy;
  std::string failure;
  double wallTime = 0.0;
  int steps = 0;
  std::vector<ffr::HubBeamStep> history;  // every step (hub-beam runs with keepSteps)
  double maxAbsUy() const {
    double m = 0.0;
    for (double v : uy) m = std::max(m, std::abs(v));
    return m;
  }
  double maxAbsUx() const {
    double m = 0.0;
    for (double v : ux) m = std::max(m, std::abs(v));
    return m;
  }
  // (max - min) / 2 of u_y for t > from: the residual vibration after the spin-up
  double amplitudeAfter(double from) const {
    double lo = 1e300, hi = -1e300;
    for (size_t k = 0; k < t.size(); ++k)
      if (t[k] > from) lo = std::min(lo, uy[k]), hi = std::max(hi, uy[k]);
    return 0.5 * (hi - lo);
  }
  // linear interpolation of a series at time s
  static double at(const std::vector<double>& ts, const std::vector<double>& v, double s) {
    auto it = std::lower_bound(ts.begin(), ts.end(), s);
    if (it == ts.begin()) return v.front();
    if (it == ts.end()) return v.back();
    const size_t k = it - ts.begin();
    const double w = (s - ts[k - 1]) / (ts[k] - ts[k - 1]);
    return (1 - w) * v[k - 1] + w * v[k];
  }
  // max over this series' times of |this - other| (other interpolated)
  double maxDifferenceUy(const TipSeries& o) const {
    double m = 0.0;
    for (size_t k = 0; k < t.size(); ++k) m = std::max(m, std::abs(uy[k] - at(o.t, o.uy, t[k])));
    return m;
  }
  double maxDifferenceUx(const TipSeries& o) const {
    double m = 0.0;
    for (size_t k = 0; k < t.size(); ++k) m = std::max(m, std::abs(ux[k] - at(o.t, o.ux, t[k])));
    return m;
  }
};

// Seed 001's beam (L = 10 m, A = 4e-4 m^2, I = 2e-7 m^4, rho = 3000 kg/m^3) on a driven hub with the
// spin-up of Eq. 57 (T = 15 s).
inline model::HubBeamDesc seed001HubBeam(double E, double omega0, model::HubBeamMethod method, int size) {
  model::HubBeamDesc d;
  d.present = true;
  d.length = 10.0;
  d.E = E;
  d.A = 4e-4;
  d.I = 2e-7;
  d.rho = 3000.0;
  d.angle.kind = model::TimeFunction::Kind::SpinUp;
  d.angle.omega = omega0;
  d.angle.duration = 15.0;
  d.method = method;
  d.elements = size;
  d.nodes = size;
  d.axialModes = d.bendingModes = size;
  return d;
}

// A hub-beam scene of meshes/ (its hub_beam and dynamics sections): the verification cases start
// from the scenes users run, so a scene and its documented numbers cannot drift apart.
struct HubBeamScene {
  model::HubBeamDesc hub;
  model::DynamicsDesc dynamics;
};
inline HubBeamScene hubBeamScene(const std::string& file) {
  const model::SceneDescription sc = io::readScene(sourceDir() + "/meshes/" + file);
  return {sc.hubBeam, sc.dynamics};
}
// the same scene with another discretization
inline model::HubBeamDesc withMethod(model::HubBeamDesc d, model::HubBeamMethod method, int size) {
  d.method = method;
  d.elements = d.nodes = d.axialModes = d.bendingModes = size;
  return d;
}

inline model::DynamicsDesc fixedStep(model::Integrator integrator, double dt, double tEnd) {
  model::DynamicsDesc d;
  d.integrator = integrator;
  d.dt = dt;
  d.tEnd = tEnd;
  return d;
}

inline TipSeries runHubBeam(const model::HubBeamDesc& desc, const model::DynamicsDesc& dyn, int every = 1,
                            bool keepSteps = false) {
  const ffr::HubBeam hb(desc);
  ffr::HubBeamDynamics solver(hb, dyn);
  PetscCallAbort(PETSC_COMM_SELF, solver.setFromOptions());
  TipSeries s;
  auto cb = [&](const ffr::HubBeamStep& st, const Eigen::VectorXd&, const Eigen::VectorXd&) {
    if (keepSteps) s.history.push_back(st);
    s.steps = st.step;
    if (st.step % every != 0 && st.time < dyn.tEnd * (1 - 1e-12)) return;
    s.t.push_back(st.time);
    s.ux.push_back(st.obs.tipUx);
    s.uy.push_back(st.obs.tipUy);
  };
  PetscLogDouble t0, t1;
  PetscTime(&t0);
  PetscCallAbort(PETSC_COMM_SELF, solver.run(cb, &s.failure));
  PetscTime(&t1);
  s.wallTime = t1 - t0;
  return s;
}

// The same spin-up with 2D ANCF cables clamped to the hub (generalized-alpha rho_inf 0.9), the tip
// seen from the hub: the geometrically exact reference of the floating-frame models.
inline TipSeries runAncfSpinUp(double E, double omega0, int elements, double dt, double tEnd, int every = 1) {
  const model::SceneDescription sc = seed001Beam(E, elements, omega0, 15.0);
  const model::TimeFunction angle = sc.supports[0].hub.angle;
  MPI_Comm comm = PETSC_COMM_WORLD;
  solvers::Problem p(comm, sc);
  model::DynamicsDesc d = fixedStep(model::Integrator::GeneralizedAlpha, dt, tEnd);
  d.rhoInf = 0.9;
  Vec X, V;
  PetscCallAbort(comm, p.createInitialState(&X, &V));
  solvers::Dynamics dyn(p.assembler(), d);
  PetscCallAbort(comm, dyn.setFromOptions());
  TipSeries s;
  std::vector<double> q;
  solvers::Dynamics::StepCallback cb = [&](const solvers::DynamicsStep& st, Vec Xs, Vec) -> PetscErrorCode {
    PetscFunctionBeginUser;
    if (st.step % every != 0 && st.time < tEnd * (1 - 1e-12)) PetscFunctionReturn(0);
    PetscCall(p.assembler().gatherToRoot(Xs, q));
    double r[2] = {0.0, 0.0};
    if (!q.empty()) {  // the last node
      const model::Vec3 tip = nodePosition(p, q, 0, -1);
      r[0] = tip[0], r[1] = tip[1];
    }
    PetscCallMPI(MPI_Bcast(r, 2, MPI_DOUBLE, 0, comm));
    const double psi = angle.at(st.time).f, c = std::cos(psi), sn = std::sin(psi);
    s.t.push_back(st.time);
    s.ux.push_back(c * r[0] + sn * r[1] - 10.0);
    s.uy.push_back(-sn * r[0] + c * r[1]);
    PetscFunctionReturn(0);
  };
  PetscCallAbort(comm, dyn.run(X, V, cb, &s.failure));
  VecDestroy(&X);
  VecDestroy(&V);
  return s;
}

}  // namespace strand::testing
