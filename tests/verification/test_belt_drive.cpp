// Closed belts around pulleys (docs/validation.md, "Belt at rest"; issue 34).
//
// requirement: a closed belt (a loop: its last node is its first) wrapped around two pulleys with
//   a pretension (initial_stretch lambda0, i.e. the reference strain 1/lambda0 - 1) holds a
//   uniform tension equal to the prescribed one, T = EA (lambda^2 - 1) lambda / 2 at the stretch
//   lambda = (path length) / (reference length), the path shortened by the penalty's sinking; and
//   presses on each wrap with p = T / r (per unit deformed length);
// requirement: -n 1 and -n 2 give the same tensions (this test runs on both).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "support/Belts.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

// k = 1e8 N/m^2: the belt sinks delta = p / k = 2e-5 m into the pulleys, and the onset of contact
// spreads over sqrt(T / k) = 3 mm (a string on an elastic foundation)
constexpr double kR = 0.5, kD = 1.0, kEA = 1e5, kStiffness = 1e8;

model::SceneDescription beltAtRest(double stretch, int elements) {
  BeltLoop spec;
  spec.radius = kR;
  spec.distance = kD;
  spec.elements = elements;
  spec.EA = kEA;
  spec.stretch = stretch;
  spec.stiffness = kStiffness;
  return closedBelt(spec);
}

double tensionOfStretch(double lambda) { return cableTension(kEA, lambda); }

}  // namespace

TEST(BeltAtRest, PretensionIsUniformAndPressesWithTOverR) {
  const double pi = std::acos(-1.0), path = 2.0 * kD + 2.0 * pi * kR, stretch = 1.01;
  const int N = 320;
  model::SceneDescription sc = beltAtRest(stretch, N);
  solvers::Problem p(PETSC_COMM_WORLD, sc);
  ASSERT_TRUE(p.model().bodies()[0].closed);
  ASSERT_NEAR(p.model().bodies()[0].length, path, 1e-12);
  // the expected state: the belt sinks delta = p_ref / k = T lambda / (rho k) into both pulleys, so
  // it lies at radius rho = R - delta and its path is 2 D + 2 pi rho
  const double reference = path / stretch;
  double rho = kR, T = 0.0, lambda = stretch;
  for (int it = 0; it < 50; ++it) {
    lambda = (2.0 * kD + 2.0 * pi * rho) / reference;
    T = tensionOfStretch(lambda);
    rho = kR - T * lambda / (rho * kStiffness);
  }
  MPI_Comm comm = PETSC_COMM_WORLD;
  Vec X;
  PetscCallAbort(comm, p.dofs().createVector(&X));
  PetscCallAbort(comm, p.assembler().initialState(X));
  std::string failure;
  {
    solvers::StaticSolver solver(p.assembler(), 1);
    PetscCallAbort(comm, solver.setFromOptions());
    PetscCallAbort(comm, solver.solve(X, nullptr, &failure));
  }
  ASSERT_TRUE(failure.empty()) << failure;
  std::vector<assembly::Assembler::ContactPointOut> points;
  PetscCallAbort(comm, p.assembler().contactPoints(X, nullptr, 0.0, points));
  std::vector<double> q;
  PetscCallAbort(comm, p.assembler().gatherToRoot(X, q));
  q.resize(p.model().numDofs());
  MPI_Bcast(q.data(), static_cast<int>(q.size()), MPI_DOUBLE, 0, comm);
  VecDestroy(&X);

  // Nodal tension: uniform, and the expected one, along the spans and the wraps. Next to where the
  // belt meets a pulley (within two elements of the tangent points (0, +-rho), (D, +-rho)) the
  // nodes deviate by up to 3e-4 T, for 160 .. 640 elements and 2 .. 8 contact points alike
  // (measured); not explained yet (docs/validation.md), so held to 1e-3 there.
  const model::Body& b = p.model().bodies()[0];
  double interior = 0.0, onset = 0.0;
  for (int n = 0; n < b.elements; ++n) {
    const int pos = b.posBlock[n];
    const double t = tensionOfStretch(nodeStretch(b, q, n));
    const double x = q[2 * pos], y = q[2 * pos + 1];
    double near = 1e300;
    for (double cx : {0.0, kD})
      for (double cy : {-rho, rho}) near = std::min(near, std::hypot(x - cx, y - cy));
    double& worst = near < 2.0 * b.elementLength * stretch ? onset : interior;
    worst = std::max(worst, std::abs(t / T - 1.0));
  }
  int rank;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0)
    std::printf("belt at rest: expected T = %.6f N (unsunk %.6f N); nodal tension off by %.2e (spans, wraps), %.2e "
                "(next to the contact onset)\n", T, tensionOfStretch(stretch), interior, onset);
  EXPECT_LT(interior, 1e-4);
  EXPECT_LT(onset, 1e-3);
  // pressure on the wraps, away from where the belt meets them. Its error is the arc's cubic
  // interpolation, (h / rho)^4 rho / 384 = 1.4e-9 m at h = 1.6 cm, against the sinking 2e-5 m
  // pressure on the wraps, away from where the belt meets them
  double worst = 0.0;
  int checked = 0;
  for (const auto& pt : points) {
    const model::Vec3& c = sc.pulleys[pt.pulley].center;
    const double dx = pt.r[0] - c[0], dy = pt.r[1] - c[1];
    const bool outside = pt.pulley == 0 ? dx < -0.1 : dx > 0.1;  // the half of the pulley the belt wraps
    if (!outside) continue;
    ASSERT_TRUE(pt.state.touching);
    worst = std::max(worst, std::abs(pt.state.pressure / (T * lambda / std::hypot(dx, dy)) - 1.0));
    ++checked;
  }
  int total = 0;
  MPI_Allreduce(&checked, &total, 1, MPI_INT, MPI_SUM, comm);
  EXPECT_GT(total, 200);
  EXPECT_LT(worst, 1e-3);
}
