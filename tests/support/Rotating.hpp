// Rotating-beam scenes and modal solves for tests: steady state in the rotating frame, then the
// linearized modes (solvers::ModalSolver), with each mode's share of motion per direction.
#pragma once
#include <array>

#include "strand/solvers/ModalSolver.hpp"
#include "support/Scenes.hpp"

namespace strand::testing {

// Uniform cantilever along +x from the origin, L = 1, rotating about z (axis) with
// gamma = Omega sqrt(rho A L^4 / EI), hub radius ratio delta (axis at x = -delta L) and
// slenderness mu = sqrt(A L^2 / I).
inline model::SceneDescription rotatingCantilever(int dim, int elements, double gamma, double delta = 0.0,
                                                  double mu = 1e4, model::Vec3 axis = {0, 0, 1}) {
  Section s{1e9, 1e-2, 1e-2 / (mu * mu), 1000.0};
  auto sc = cantilever(dim, elements, 1.0, s);
  sc.rotation.present = true;
  sc.rotation.axis = axis;
  sc.rotation.center = {-delta, 0, 0};
  sc.rotation.omega = gamma * std::sqrt(s.E * s.I / (s.rho * s.A));
  return sc;
}

struct RotatingModes {
  std::vector<double> omegaBar;                   // omega sqrt(rho A L^4 / EI) of the first body
  std::vector<std::array<double, 3>> direction;   // share of sum |u_i|^2 over position DOFs, per axis
  std::vector<double> residual;
  double maxRealPart = 0.0;
  std::string method;
};

inline RotatingModes rotatingModes(const model::SceneDescription& sc, const solvers::ModalOptions& opt,
                                   MPI_Comm comm = PETSC_COMM_WORLD, int loadSteps = 4) {
  solvers::Problem p(comm, sc);
  Vec X;
  PetscCallAbort(comm, p.dofs().createVector(&X));
  PetscCallAbort(comm, p.assembler().initialState(X));
  std::string why;
  {
    solvers::StaticSolver steady(p.assembler(), loadSteps);
    PetscCallAbort(comm, steady.solve(X, nullptr, &why));
  }
  RotatingModes out;
  solvers::ModalResult r;
  {
    solvers::ModalSolver modal(p.assembler(), opt);
    PetscCallAbort(comm, modal.solve(X, &r));
  }
  const double T = p.model().scales().time();
  const int d = p.model().dim();
  const auto& q0 = p.model().initialCoordinates();
  for (size_t k = 0; k < r.omega.size(); ++k) {
    out.omegaBar.push_back(r.omega[k] * T);
    out.residual.push_back(r.relativeResidual[k]);
    std::array<double, 3> e{};
    for (int part = 0; part < (r.shapesImag.empty() ? 1 : 2); ++part) {
      std::vector<double> q;
      PetscCallAbort(comm, p.assembler().gatherToRoot(part == 0 ? r.shapes[k] : r.shapesImag[k], q));
      q.resize(p.model().numDofs());
      MPI_Bcast(q.data(), static_cast<int>(q.size()), MPI_DOUBLE, 0, comm);
      for (int pb : p.model().bodies()[0].posBlock)
        for (int i = 0; i < d; ++i) e[i] += std::pow(q[pb * d + i] - q0[pb * d + i], 2);
    }
    const double sum = e[0] + e[1] + e[2];
    for (double& v : e) v /= sum;
    out.direction.push_back(e);
  }
  out.maxRealPart = r.maxRealPart;
  out.method = r.method;
  solvers::destroyModes(&r);
  VecDestroy(&X);
  if (!why.empty()) ADD_FAILURE() << why;
  return out;
}

// The modes whose motion is mostly along axis i (share > 0.5), in ascending order.
inline std::vector<double> family(const RotatingModes& m, int axis) {
  std::vector<double> w;
  for (size_t k = 0; k < m.omegaBar.size(); ++k)
    if (m.direction[k][axis] > 0.5) w.push_back(m.omegaBar[k]);
  return w;
}

}  // namespace strand::testing
