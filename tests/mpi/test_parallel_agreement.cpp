// requirement: everything that assembles or solves gives the same answer on 1 and 2 ranks
// (design section 5). Under mpirun -n 2 each rank also solves the same scene serially on
// PETSC_COMM_SELF; the distributed solution must agree with it to solver tolerance.
// Tolerance: the static solves converge to ||R|| / ||R0|| < 1e-10 with LU (serial) vs MUMPS
// (parallel); for these well-conditioned scenes (EA/EI = 1e4, <= 64 elements, docs/validation.md
// "Conditioning") the position error of the solve is below 1e-9 L, so 1e-8 L is asserted.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "strand/elements/ElementRegistry.hpp"
#include "strand/io/SceneReader.hpp"
#include "strand/solvers/Dynamics.hpp"
#include "strand/solvers/ModalSolver.hpp"
#include "strand/solvers/Sweep.hpp"
#include "support/Rotating.hpp"
#include "support/Scenes.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

std::vector<double> solveOn(MPI_Comm comm, const model::SceneDescription& sc, int steps) {
  solvers::Problem p(comm, sc);
  std::string failure;
  auto q = solveStatic(p, steps, &failure);
  EXPECT_TRUE(failure.empty()) << failure;
  return q;
}

void expectAgreement(const model::SceneDescription& sc, int steps, double length) {
  const auto par = solveOn(PETSC_COMM_WORLD, sc, steps);
  const auto ser = solveOn(PETSC_COMM_SELF, sc, steps);
  ASSERT_EQ(par.size(), ser.size());
  double diff = 0.0;
  for (size_t k = 0; k < par.size(); ++k) diff = std::max(diff, std::fabs(par[k] - ser[k]));
  EXPECT_LT(diff, 1e-8 * length);
}

// Runs the dynamics d of scene sc on comm and returns what sample(problem, step, X, V, out) appends
// at each step (on every rank alike).
using Sampler = std::function<PetscErrorCode(solvers::Problem&, const solvers::DynamicsStep&, Vec, Vec,
                                             std::vector<double>&)>;
std::vector<double> sampledRun(MPI_Comm comm, const model::SceneDescription& sc, const model::DynamicsDesc& d,
                               const Sampler& sample) {
  solvers::Problem p(comm, sc);
  Vec X, V;
  PetscCallAbort(comm, p.createInitialState(&X, &V));
  std::vector<double> out;
  solvers::Dynamics dyn(p.assembler(), d);
  solvers::Dynamics::StepCallback cb = [&](const solvers::DynamicsStep& st, Vec Xs, Vec Vs) -> PetscErrorCode {
    return sample(p, st, Xs, Vs, out);
  };
  std::string failure;
  PetscCallAbort(comm, dyn.run(X, V, cb, &failure));
  EXPECT_EQ(failure, "");
  VecDestroy(&X);
  VecDestroy(&V);
  return out;
}

// Three cables from the corners of a triangle meet at a hub node, which carries a load.
model::SceneDescription network(int dim) {
  model::SceneDescription sc;
  sc.file = "(test)";
  sc.dimension = dim;
  const model::Vec3 hub{0.0, 0.0, 0.0};
  const model::Vec3 corners[3] = {{1.0, 0.0, 0.0}, {-0.5, 0.8, 0.0}, {-0.5, -0.8, 0.3 * (dim == 3)}};
  const char* names[3] = {"a", "b", "c"};
  model::JunctionDesc j;
  for (int k = 0; k < 3; ++k) {
    sc.bodies.push_back(straightBody(names[k], dim, 12, corners[k], hub));
    model::SupportDesc s;
    s.at.body = names[k];
    s.at.node = 0;
    s.type = model::SupportType::Clamped;
    sc.supports.push_back(s);
    model::NodeRef r;
    r.body = names[k];
    r.node = -1;
    j.nodes.push_back(r);
  }
  sc.junctions.push_back(j);
  model::NodalLoadDesc l;
  l.at.body = "a";
  l.at.node = -1;
  l.force = {30.0, -50.0, dim == 3 ? 20.0 : 0.0};
  sc.loads.nodal.push_back(l);
  sc.loads.gravity = dim == 3 ? model::Vec3{0, 0, -9.81} : model::Vec3{0, -9.81, 0};
  return sc;
}

}  // namespace

TEST(ParallelAgreement, SingleChainLargeDeflection) {
  for (int dim : {2, 3}) {
    auto sc = cantilever(dim, 64, 1.0);
    const Section s;
    addTipLoad(sc, dim == 2 ? model::Vec3{0, -3 * s.E * s.I, 0} : model::Vec3{0, -2 * s.E * s.I, -2 * s.E * s.I});
    expectAgreement(sc, 8, 1.0);
  }
}

TEST(ParallelAgreement, NetworkOfThreeCablesAtOneNode) {
  for (int dim : {2, 3}) expectAgreement(network(dim), 4, 1.0);
}

TEST(ParallelAgreement, JunctionSharesPositionButNotSlope) {
  solvers::Problem p(PETSC_COMM_WORLD, network(3));
  const auto& b = p.model().bodies();
  EXPECT_EQ(b[0].posBlock.back(), b[1].posBlock.back());
  EXPECT_EQ(b[0].posBlock.back(), b[2].posBlock.back());
  EXPECT_NE(b[0].block(b[0].elements, 1), b[1].block(b[1].elements, 1));
  // 3 bodies x 13 nodes x (r, r'), two positions merged, and one multiplier block for each clamp
  // whose slope is not along an axis (b and c: its direction held by r'.n = 0)
  EXPECT_EQ(p.model().numBlocks(), 3 * 2 * 13 - 2 + 2);
}

TEST(ParallelAgreement, ModalFrequencies) {
  for (int dim : {2, 3}) {
    auto sc = cantilever(dim, 24, 1.0);
    double w[2][4] = {};
    MPI_Comm comms[2] = {PETSC_COMM_WORLD, PETSC_COMM_SELF};
    for (int c = 0; c < 2; ++c) {
      solvers::Problem p(comms[c], sc);
      Vec X;
      PetscCallAbort(comms[c], p.dofs().createVector(&X));
      PetscCallAbort(comms[c], p.assembler().initialState(X));
      solvers::ModalResult r;
      PetscCallAbort(comms[c], solvers::solveModes(p.assembler(), X, 4, &r));
      ASSERT_GE(r.omega.size(), 4u);
      for (int k = 0; k < 4; ++k) w[c][k] = r.omega[k];
      solvers::destroyModes(&r);
      VecDestroy(&X);
    }
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(w[0][k] / w[1][k], 1.0, 1e-10) << "dim " << dim << " mode " << k;
  }
}

// requirement (issue 4): -n 1 and -n 2 give the same frequencies. A mass-location sweep of the
// rotating chordwise beam with Coriolis (PEP, complex shapes, MAC tracking, veering detection,
// local refinement): frequencies to 1e-9, the same events at the same parameter.
TEST(ParallelAgreement, RotatingSweepWithCoriolis) {
  auto sc = rotatingCantilever(2, 16, 10.0, 0.0, 70.0);
  model::PointMassDesc pm;
  pm.at = 0.5;
  pm.mass = 2.0 * 1000.0 * 1e-2;
  sc.bodies[0].pointMasses.push_back(pm);
  sc.sweep.present = true;
  sc.sweep.parameter = model::SweepParameter::MassLocation;
  sc.sweep.from = 0.3;
  sc.sweep.to = 0.6;
  sc.sweep.points = 16;
  sc.sweep.refine = 10;
  sc.modes.count = 5;
  sc.modes.coriolis = true;
  solvers::SweepResult r[2];
  MPI_Comm comms[2] = {PETSC_COMM_WORLD, PETSC_COMM_SELF};
  for (int c = 0; c < 2; ++c) PetscCallAbort(comms[c], solvers::runSweep(comms[c], sc, &r[c]));
  ASSERT_EQ(r[0].omegaBar.size(), r[1].omegaBar.size());
  double dev = 0.0;
  for (size_t i = 0; i < r[0].omegaBar.size(); ++i)
    for (size_t k = 0; k < r[0].omegaBar[i].size(); ++k)
      dev = std::max(dev, std::fabs(r[0].omegaBar[i][k] / r[1].omegaBar[i][k] - 1.0));
  std::printf("max relative frequency difference, distributed vs serial: %.1e\n", dev);
  EXPECT_LT(dev, 1e-9);
  for (const auto& e : r[0].events)
    std::printf("%s loci %d-%d at %.4f: gap %.4f, exchange %.2f, mixing %.2f, refined %d\n", e.kind.c_str(), e.lower + 1,
                e.lower + 2, e.parameter, e.gap, e.exchange, e.mixing, e.refined);
  ASSERT_EQ(r[0].events.size(), 1u);  // loci 3-4 near beta = 0.43
  ASSERT_EQ(r[1].events.size(), 1u);
  // the gap Coriolis opens (0.61 at omega_bar 68.8); its label rests on the shapes' mixing at the
  // minimum, 0.91 against the 0.9 threshold here, so only its agreement is asserted
  EXPECT_GT(r[0].events[0].gap / r[0].events[0].frequency, 3e-3);
  EXPECT_EQ(r[0].events[0].kind, r[1].events[0].kind);
  EXPECT_NEAR(r[0].events[0].parameter, r[1].events[0].parameter, 1e-6);
  EXPECT_NEAR(r[0].events[0].gap / r[1].events[0].gap, 1.0, 1e-6);
  EXPECT_EQ(r[0].label, r[1].label);
}

// A long flexible chain (issue 3): 12 cables of 0.25 m (2 elements each, EA = 1e4 N, EI = 1 N m^2)
// joined end to end by pin joints (Lagrange multipliers), the first pinned to the ground, released
// horizontally under gravity; generalized-alpha rho_inf = 0.9, h = 1 ms, 0.3 s. The tip trajectory
// on all ranks must match the serial one at every step. Tolerance: the two runs solve with
// different factorizations (one banded LU against the interface Schur solve), so their Newton
// iterates differ by round-off, and at worst a stopping decision flips and one run stops with the
// error left, |du| < 1e-12 |q0| (|q0| = 12.0 here: 36 nodes' positions and unit slopes), in a
// step where the other takes one more iteration. Steps where that happens are few (measured: none,
// 6e-14 m); 1e-9 m, 80 such steps' worth, is asserted, against a tip travel of 0.4 m.
TEST(ParallelAgreement, LongFlexibleChainTrajectory) {
  const int links = 12;
  const double l = 0.25;
  model::SceneDescription sc;
  sc.file = "(test)";
  sc.dimension = 2;
  sc.analysis = model::Analysis::Dynamic;
  sc.loads.gravity = {0, -9.81, 0};
  Section s;
  s.E = 1e8;
  for (int k = 0; k < links; ++k) {
    sc.bodies.push_back(straightBody("c" + std::to_string(k), 2, 2, {k * l, 0, 0}, {(k + 1) * l, 0, 0}, s));
    model::JointDesc j;
    j.type = model::JointType::Pin;
    j.a.kind = model::JointEndDesc::Kind::CableNode;
    j.a.body = "c" + std::to_string(k);
    j.a.node = 0;
    if (k == 0) {
      j.b.kind = model::JointEndDesc::Kind::Ground;
    } else {
      j.b.kind = model::JointEndDesc::Kind::CableNode;
      j.b.body = "c" + std::to_string(k - 1);
      j.b.node = -1;
    }
    sc.joints.push_back(j);
  }
  model::DynamicsDesc d;
  d.integrator = model::Integrator::GeneralizedAlpha;
  d.rhoInf = 0.9;
  d.dt = 1e-3;
  d.tEnd = 0.3;
  auto tipOf = [&](solvers::Problem& p, const solvers::DynamicsStep&, Vec Xs, Vec, std::vector<double>& tip) -> PetscErrorCode {
    std::vector<double> q;
    PetscCall(p.assembler().gatherToRoot(Xs, q));
    double xy[2] = {0, 0};
    if (!q.empty()) {
      const model::Vec3 r = nodePosition(p, q, links - 1, -1);
      xy[0] = r[0];
      xy[1] = r[1];
    }
    MPI_Bcast(xy, 2, MPI_DOUBLE, 0, p.assembler().dofs().comm());
    tip.push_back(xy[0]);
    tip.push_back(xy[1]);
    return 0;
  };
  const auto par = sampledRun(PETSC_COMM_WORLD, sc, d, tipOf);
  const auto ser = sampledRun(PETSC_COMM_SELF, sc, d, tipOf);
  ASSERT_EQ(par.size(), ser.size());
  double diff = 0.0;
  for (size_t k = 0; k < par.size(); ++k) diff = std::max(diff, std::fabs(par[k] - ser[k]));
  std::printf("chain tip at t = 0.3 s: (%.9f, %.9f); max difference distributed vs serial over %zu steps: %.2e m\n",
              par[par.size() - 2], par.back(), par.size() / 2, diff);
  EXPECT_LT(diff, 1e-9);
  EXPECT_GT(std::hypot(par[par.size() - 2] - links * l, par.back()), 0.1);  // it did swing
}

// requirement (issue 33): a scene can mix element kinds. meshes/boom-rope-load.yaml: a boom of
// AncfBeam2dShear elements, a rope of AncfCable2d elements joined to its tip by a junction, a rigid
// block pinned to the rope; 0.2 s of its dynamics (generalized-alpha, index-3 pin), and its static
// equilibrium under gravity with the block clamped to the rope instead (a pinned block has no
// static stiffness against turning at zero load). Distributed and serial runs agree: statics to 1e-8 L as above; the trajectory of
// every coordinate to 1e-9 (different factorizations, the same Newton tolerance as the chain).
TEST(ParallelAgreement, MixedElementKindsBoomRopeAndBlock) {
  const char* source = std::getenv("STRAND_SOURCE_DIR");
  ASSERT_NE(source, nullptr);
  model::SceneDescription sc = io::readScene(std::string(source) + "/meshes/boom-rope-load.yaml");
  ASSERT_EQ(sc.bodies[0].kind, elements::findKind("AncfBeam2dShear"));
  ASSERT_EQ(sc.bodies[1].kind, elements::findKind("AncfCable2d"));
  model::SceneDescription statics = sc;
  statics.analysis = model::Analysis::Static;
  statics.rigidBodies[0].velocity = {0, 0, 0};
  statics.joints[0].type = model::JointType::Clamp;
  expectAgreement(statics, 5, 2.0);
  sc.dynamics.tEnd = 0.2;
  auto finalState = [&](MPI_Comm comm) {
    solvers::Problem p(comm, sc);
    Vec X, V;
    PetscCallAbort(comm, p.createInitialState(&X, &V));
    solvers::Dynamics dyn(p.assembler(), sc.dynamics);
    std::string failure;
    PetscCallAbort(comm, dyn.run(X, V, nullptr, &failure));
    EXPECT_EQ(failure, "");
    std::vector<double> q;
    PetscCallAbort(comm, p.assembler().gatherToRoot(X, q));
    q.resize(p.model().numDofs());
    MPI_Bcast(q.data(), static_cast<int>(q.size()), MPI_DOUBLE, 0, comm);
    VecDestroy(&X);
    VecDestroy(&V);
    return q;
  };
  const auto par = finalState(PETSC_COMM_WORLD);
  const auto ser = finalState(PETSC_COMM_SELF);
  ASSERT_EQ(par.size(), ser.size());
  double diff = 0.0;
  for (size_t k = 0; k < par.size(); ++k) diff = std::max(diff, std::fabs(par[k] - ser[k]));
  std::printf("mixed scene at t = 0.2 s: max difference distributed vs serial %.2e\n", diff);
  EXPECT_LT(diff, 1e-9);
}

// A model smaller than the ranks: one element, whose blocks METIS gives to one rank; the other owns
// none (the parallel direct solve divided by its zero row count: SIGFPE before).
TEST(ParallelAgreement, OneElementLeavesARankWithoutRows) {
  auto sc = cantilever(2, 1, 1.0);
  addTipLoad(sc, {0, -100.0, 0});
  expectAgreement(sc, 1, 1.0);
}

// requirement (issue 34): a belt drive gives the same speeds and tensions on 1 and 2 ranks.
// meshes/serpentine-drive.yaml (crank, three accessories with inertia, damping and load torques, a
// tensioner on a sprung slide; bristle friction) with 1,000 elements instead of 10,000, to 30 ms
// (the crank at 0 -> 80 rad/s from 10 ms, the loads coming on from 30 ms): the free pulleys' speeds,
// torques and the tensioner's slide at every step, distributed against serial. The distributed
// solve takes the pulleys' rows as the interface-Schur's hubs (docs/contact.md), the serial one
// PETSc's LU: they agree to the Newton tolerance (measured 1.1e-13 of the largest value).
TEST(ParallelAgreement, SerpentineBeltDrive) {
  const char* source = std::getenv("STRAND_SOURCE_DIR");
  ASSERT_NE(source, nullptr);
  model::SceneDescription sc = io::readScene(std::string(source) + "/meshes/serpentine-drive.yaml");
  ASSERT_EQ(sc.bodies[0].elements, 10000);
  ASSERT_EQ(sc.pulleys.size(), 5u);
  sc.bodies[0].elements = 1000;
  sc.dynamics.tEnd = 0.03;
  auto pulleys = [](solvers::Problem& p, const solvers::DynamicsStep& st, Vec Xs, Vec Vs,
                    std::vector<double>& out) -> PetscErrorCode {
    std::vector<assembly::Assembler::PulleyLoad> load;
    PetscCall(p.assembler().pulleyLoads(Xs, Vs, st.time, load));
    for (const auto& l : load)
      for (double v : {l.speed, l.torque, l.slide}) out.push_back(v);
    return 0;
  };
  const auto par = sampledRun(PETSC_COMM_WORLD, sc, sc.dynamics, pulleys);
  const auto ser = sampledRun(PETSC_COMM_SELF, sc, sc.dynamics, pulleys);
  ASSERT_EQ(par.size(), ser.size());
  double diff = 0.0, scale = 0.0;
  for (size_t k = 0; k < par.size(); ++k) {
    diff = std::max(diff, std::fabs(par[k] - ser[k]));
    scale = std::max(scale, std::fabs(ser[k]));
  }
  std::printf("serpentine drive, 1,000 elements, %zu steps: crank torque %.4f N m, water pump %.3f rad/s at 30 ms; "
              "pulley speeds, torques and slide, distributed vs serial: %.2e of their largest (%.3g)\n",
              par.size() / 15, ser[ser.size() - 14], ser[ser.size() - 12], diff / scale, scale);
  EXPECT_GT(std::fabs(ser[ser.size() - 12]), 10.0);  // the water pump (free) turns with the crank
  EXPECT_LT(diff, 1e-10 * scale);
}
