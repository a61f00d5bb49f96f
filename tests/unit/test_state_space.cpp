// The first-order form y = (u, v) (solvers/StateSpace.hpp) on a damped beam clamped to a turning
// hub (seed 001's spin-up at t = 3 s, so the prescribed motion has velocity and acceleration):
//  1. Taylor test of the Newton operator: for a direction d that leaves the supported entries alone
//     (the operator drops the supported columns of free rows; StateSpace.hpp),
//     |F(y + e d, y' + sigma e d) - F(y, y') - e J d| falls as e^2 (ratio 4 per halving).
//  2. The PCShell is the exact inverse of the MatShell: |P^{-1} J x - x| / |x| ~ round-off.
//  3. The explicit form agrees with the implicit one: F(t, y, f(t, y)) = 0 when y holds the
//     prescribed motion on supported entries.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include "strand/solvers/ConstrainedStateSpace.hpp"
#include "strand/solvers/StateSpace.hpp"
#include "support/Pendulum.hpp"
#include "support/Scenes.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

// A state with entries uniform in [-1/2, 1/2], the displacement half scaled by scaleU.
Vec randomState(const solvers::StateSpace& space, MPI_Comm comm, unsigned seed, double scaleU) {
  Vec Y;
  PetscCallAbort(comm, space.createState(&Y));
  PetscRandom r;
  PetscCallAbort(comm, PetscRandomCreate(comm, &r));
  PetscCallAbort(comm, PetscRandomSetSeed(r, seed));
  PetscCallAbort(comm, PetscRandomSeed(r));
  PetscCallAbort(comm, VecSetRandom(Y, r));
  PetscCallAbort(comm, PetscRandomDestroy(&r));
  PetscCallAbort(comm, VecShift(Y, -0.5));
  PetscScalar* y;
  PetscInt n;
  PetscCallAbort(comm, VecGetLocalSize(Y, &n));
  PetscCallAbort(comm, VecGetArray(Y, &y));
  for (PetscInt i = 0; i < n / 2; ++i) y[i] *= scaleU;
  PetscCallAbort(comm, VecRestoreArray(Y, &y));
  return Y;
}

// Taylor test of a Newton matrix: with F0 = F(Y, Yd) and JD = J D, the remainder
// |F(Y + e D, Yd + sigma e D) - F0 - e JD| must fall as e^2 (ratio 4 per halving, asserted).
void expectTaylorRatios(MPI_Comm comm, const std::function<void(Vec, Vec, Vec)>& residual, Vec Y, Vec Yd, Vec D,
                        double sigma, Vec F0, Vec JD, const std::string& label) {
  Vec F1, Ye, Yde;
  PetscCallAbort(comm, VecDuplicate(Y, &F1));
  PetscCallAbort(comm, VecDuplicate(Y, &Ye));
  PetscCallAbort(comm, VecDuplicate(Y, &Yde));
  double prev = 0.0;
  for (int k = 0; k < 5; ++k) {
    const double e = 1e-3 / (1 << k);
    PetscCallAbort(comm, VecWAXPY(Ye, e, D, Y));
    PetscCallAbort(comm, VecWAXPY(Yde, sigma * e, D, Yd));
    residual(Ye, Yde, F1);
    PetscCallAbort(comm, VecAXPY(F1, -1.0, F0));
    PetscCallAbort(comm, VecAXPY(F1, -e, JD));
    PetscReal r;
    PetscCallAbort(comm, VecNorm(F1, NORM_2, &r));
    if (k > 0) {
      std::printf("%se = %.3e  remainder %.4e  ratio %.3f\n", label.c_str(), e, r, prev / r);
      EXPECT_NEAR(prev / r, 4.0, 0.2) << label;
    }
    prev = r;
  }
  for (Vec* v : {&F1, &Ye, &Yde}) VecDestroy(v);
}

struct Fixture {
  MPI_Comm comm = PETSC_COMM_WORLD;
  model::SceneDescription scene;
  std::unique_ptr<solvers::Problem> problem;
  Mat M = nullptr, Mmasked = nullptr;
  Vec supported = nullptr;
  KSP mass = nullptr;
  std::unique_ptr<solvers::StateSpace> space;
  TS ts = nullptr, tsExplicit = nullptr;  // an implicit TS (IFunction) and an explicit one (RHSFunction)

  Fixture() {
    scene = seed001Beam(7e10, 4, 4.0, 15.0);
    // the whole root slope eliminated: no multipliers (this is the unconstrained state space; a
    // `clamped` hub support holds the slope's direction by a joint)
    scene.supports[0].type = model::SupportType::ClampedUnstretched;
    scene.bodies[0].section.set("damping_axial", 2e-3);
    scene.bodies[0].section.set("damping_bending", 2e-3);
    problem = std::make_unique<solvers::Problem>(comm, scene);
    assembly::Assembler& a = problem->assembler();
    PetscCallAbort(comm, problem->dofs().createMatrix(&M, nullptr));
    PetscCallAbort(comm, problem->dofs().createMatrix(&Mmasked, nullptr));
    PetscCallAbort(comm, a.massMatrix(M, false));
    PetscCallAbort(comm, a.massMatrix(Mmasked, true));
    PetscCallAbort(comm, MatCreateVecs(M, nullptr, &supported));
    PetscCallAbort(comm, a.supportMask(supported));
    PetscCallAbort(comm, MatDiagonalSet(Mmasked, supported, ADD_VALUES));
    PetscCallAbort(comm, KSPCreate(comm, &mass));
    PetscCallAbort(comm, KSPSetOperators(mass, Mmasked, Mmasked));
    PetscCallAbort(comm, solvers::setDirectSolverDefaults(mass, false));
    space = std::make_unique<solvers::StateSpace>(a, M, supported, mass, true);
    PetscCallAbort(comm, TSCreate(comm, &ts));
    PetscCallAbort(comm, TSSetType(ts, TSBDF));
    PetscCallAbort(comm, space->setImplicit(ts));
    PetscCallAbort(comm, TSCreate(comm, &tsExplicit));
    PetscCallAbort(comm, TSSetType(tsExplicit, TSRK));
    PetscCallAbort(comm, space->setExplicit(tsExplicit));
    Vec Y;
    PetscCallAbort(comm, space->createState(&Y));
    PetscCallAbort(comm, TSSetSolution(ts, Y));
    PetscCallAbort(comm, TSSetSolution(tsExplicit, Y));
    PetscCallAbort(comm, VecDestroy(&Y));
  }
  ~Fixture() {
    TSDestroy(&ts);
    TSDestroy(&tsExplicit);
    space.reset();
    KSPDestroy(&mass);
    MatDestroy(&M);
    MatDestroy(&Mmasked);
    VecDestroy(&supported);
  }
  // a state with displacements ~1e-2 m and velocities ~1 m/s, prescribed entries at time t
  Vec state(double t, unsigned seed) {
    Vec Y = randomState(*space, comm, seed, 2e-2);
    PetscCallAbort(comm, space->prescribe(t, Y));
    return Y;
  }
  // zero on the supported entries of both halves
  void maskSupported(Vec D) {
    Vec Xc, Vc;
    PetscCallAbort(comm, VecDuplicate(supported, &Xc));
    PetscCallAbort(comm, VecDuplicate(supported, &Vc));
    PetscCallAbort(comm, space->unpack(D, Xc, Vc));
    PetscCallAbort(comm, problem->assembler().zeroSupportedRows(Xc));
    PetscCallAbort(comm, problem->assembler().zeroSupportedRows(Vc));
    PetscCallAbort(comm, space->pack(Xc, Vc, D));
    VecDestroy(&Xc);
    VecDestroy(&Vc);
  }
};

}  // namespace

TEST(StateSpace, NewtonOperatorPassesTheTaylorTestAndItsPreconditionerIsItsInverse) {
  Fixture f;
  MPI_Comm comm = f.comm;
  const double t = 3.0, sigma = 1500.0;  // sigma ~ 3 / (2 h), BDF2 at h = 1 ms
  Vec Y = f.state(t, 7), Yd = f.state(t, 11), D = f.state(t, 13), F0, F1, JD, W;
  f.maskSupported(D);
  PetscCallAbort(comm, VecDuplicate(Y, &F0));
  PetscCallAbort(comm, VecDuplicate(Y, &F1));
  PetscCallAbort(comm, VecDuplicate(Y, &JD));
  PetscCallAbort(comm, VecDuplicate(Y, &W));
  Mat J;
  PetscCallAbort(comm, TSGetIJacobian(f.ts, &J, nullptr, nullptr, nullptr));
  PetscCallAbort(comm, TSComputeIFunction(f.ts, t, Y, Yd, F0, PETSC_FALSE));
  PetscCallAbort(comm, TSComputeIJacobian(f.ts, t, Y, Yd, sigma, J, J, PETSC_FALSE));
  PetscCallAbort(comm, MatMult(J, D, JD));
  expectTaylorRatios(
      comm, [&](Vec Ye, Vec Yde, Vec F) { PetscCallAbort(comm, TSComputeIFunction(f.ts, t, Ye, Yde, F, PETSC_FALSE)); },
      Y, Yd, D, sigma, F0, JD, "");
  // P^{-1} J x = x for any x (supported entries included)
  SNES snes;
  KSP ksp;
  PC pc;
  PetscCallAbort(comm, TSGetSNES(f.ts, &snes));
  PetscCallAbort(comm, SNESGetKSP(snes, &ksp));
  PetscCallAbort(comm, KSPGetPC(ksp, &pc));
  PetscCallAbort(comm, PCSetOperators(pc, J, J));  // as the SNES would before its first solve
  Vec x = f.state(t, 17);
  PetscCallAbort(comm, MatMult(J, x, W));
  PetscCallAbort(comm, PCApply(pc, W, F1));
  PetscCallAbort(comm, VecAXPY(F1, -1.0, x));
  PetscReal err, nx;
  PetscCallAbort(comm, VecNorm(F1, NORM_2, &err));
  PetscCallAbort(comm, VecNorm(x, NORM_2, &nx));
  std::printf("|P^-1 J x - x| / |x| = %.3e\n", err / nx);
  EXPECT_LT(err / nx, 1e-10);
  for (Vec* v : {&Y, &Yd, &D, &F0, &F1, &JD, &W, &x}) VecDestroy(v);
}

TEST(StateSpace, ExplicitRateSolvesTheImplicitResidual) {
  Fixture f;
  MPI_Comm comm = f.comm;
  const double t = 3.0;
  Vec Y = f.state(t, 5), G, F;
  PetscCallAbort(comm, VecDuplicate(Y, &G));
  PetscCallAbort(comm, VecDuplicate(Y, &F));
  PetscCallAbort(comm, TSComputeRHSFunction(f.tsExplicit, t, Y, G));
  PetscCallAbort(comm, TSComputeIFunction(f.ts, t, Y, G, F, PETSC_FALSE));
  PetscReal r, g;
  PetscCallAbort(comm, VecNorm(F, NORM_INFINITY, &r));
  PetscCallAbort(comm, VecNorm(G, NORM_INFINITY, &g));
  std::printf("|F(t, y, f(t, y))| = %.3e  (|f| = %.3e)\n", r, g);
  EXPECT_LT(r, 1e-9 * g);
  VecDestroy(&Y);
  VecDestroy(&G);
  VecDestroy(&F);
}


// BDF with joints (solvers/ConstrainedStateSpace.hpp): a damped cable pinned to the ground at one
// end and to a rigid bob at the other (no supports but the bob's unused slot), a rigid 3-link
// chain (only joint terms are nonlinear there, so the GGL terms H(mu~) and (H_k v)^T dominate the
// remainder), and a 3D cable with two rigid bodies (support/Scenes.hpp). Taylor test of the assembled 2n x 2n Newton matrix, both
// forms, with every unknown perturbed (multipliers of both halves included): the remainder falls
// as e^2.
TEST(ConstrainedStateSpace, NewtonMatrixPassesTheTaylorTestOnBothForms) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  model::SceneDescription sc = flexiblePendulum(2e-3, 1e8, 4);
  sc.supports.clear();
  model::RigidBodyDesc bob;
  bob.name = "bob";
  bob.mass = 0.5;
  bob.inertia = 2e-3;
  bob.position = {1.1, 0, 0};
  sc.rigidBodies.push_back(bob);
  model::JointDesc root, tip;
  root.a.kind = model::JointEndDesc::Kind::CableNode;
  root.a.body = sc.bodies[0].name;
  root.a.node = 0;
  tip.a = root.a;
  tip.a.node = -1;
  tip.b.kind = model::JointEndDesc::Kind::RigidPoint;
  tip.b.body = "bob";
  tip.b.point = {-0.1, 0, 0};
  sc.joints = {root, tip};
  // the cable of the 3D scene is soft (E A = 0.1 N) so that its curvature leaves the loads' terms
  // visible in the remainder: a wrong torque or moment tangent turns the ratio to 2
  for (const model::SceneDescription& scene : {sc, rigidChain(3, 0.4, 0.3), cableWithTwoBodies3d(1e3)})
  for (auto form : {model::DynamicsDesc::ConstraintForm::Ggl, model::DynamicsDesc::ConstraintForm::Index3}) {
    solvers::Problem p(comm, scene);
    assembly::Assembler& a = p.assembler();
    a.setConstraintScale(250.0);
    Mat M;
    Vec supported, multipliers;
    PetscCallAbort(comm, p.dofs().createMatrix(&M, nullptr));
    PetscCallAbort(comm, a.massMatrix(M, false));
    PetscCallAbort(comm, MatCreateVecs(M, nullptr, &supported));
    PetscCallAbort(comm, VecDuplicate(supported, &multipliers));
    PetscCallAbort(comm, a.multiplierMask(multipliers));
    PetscCallAbort(comm, a.supportMask(supported));
    solvers::StateSpace space(a, M, supported, nullptr, true);
    solvers::ConstrainedStateSpace cs(a, space, supported, multipliers, true, form);
    auto random = [&](unsigned seed, double scaleU) { return randomState(space, comm, seed, scaleU); };
    const double t = 0.1, sigma = 1500.0;
    Vec Y = random(7, 5e-2), Yd = random(11, 1.0), D = random(13, 1.0), F0, JD;
    {  // the supported entries are linear rows; leave them alone
      Vec Xc, Vc;
      PetscCallAbort(comm, VecDuplicate(supported, &Xc));
      PetscCallAbort(comm, VecDuplicate(supported, &Vc));
      PetscCallAbort(comm, space.unpack(D, Xc, Vc));
      PetscCallAbort(comm, a.zeroSupportedRows(Xc));
      PetscCallAbort(comm, a.zeroSupportedRows(Vc));
      PetscCallAbort(comm, space.pack(Xc, Vc, D));
      VecDestroy(&Xc);
      VecDestroy(&Vc);
    }
    PetscCallAbort(comm, VecDuplicate(Y, &F0));
    PetscCallAbort(comm, VecDuplicate(Y, &JD));
    Mat J;
    PetscCallAbort(comm, cs.residual(t, Y, Yd, F0));
    PetscCallAbort(comm, cs.jacobian(t, Y, sigma, &J));
    PetscCallAbort(comm, MatMult(J, D, JD));
    expectTaylorRatios(
        comm, [&](Vec Ye, Vec Yde, Vec F) { PetscCallAbort(comm, cs.residual(t, Ye, Yde, F)); }, Y, Yd, D, sigma, F0, JD,
        std::string(scene.bodies.empty() ? "chain " : scene.dimension == 3 ? "3D    " : "cable ") +
            (form == model::DynamicsDesc::ConstraintForm::Ggl ? "GGL    " : "index3 "));
    for (Vec* v : {&Y, &Yd, &D, &F0, &JD, &supported, &multipliers}) VecDestroy(v);
    MatDestroy(&M);
  }
}
