// Sweeps of the rotating-beam modes (docs/validation.md, "Veering and mode shift"): the phenomena of
// seed 003 (Zhang et al., Nonlinear Dyn. 88 (2017)) as assertions.
#include <gtest/gtest.h>

#include <cstdio>

#include "strand/solvers/Sweep.hpp"
#include "support/Rotating.hpp"

using namespace strand;
using namespace strand::testing;

namespace {
solvers::SweepResult sweep(model::SceneDescription sc, model::SweepParameter par, double from, double to, int points,
                           int count, bool coriolis) {
  sc.sweep.present = true;
  sc.sweep.parameter = par;
  sc.sweep.from = from;
  sc.sweep.to = to;
  sc.sweep.points = points;
  sc.modes.count = count;
  sc.modes.coriolis = coriolis;
  sc.statics.loadSteps = 4;
  solvers::SweepResult r;
  PetscCallAbort(PETSC_COMM_WORLD, solvers::runSweep(PETSC_COMM_WORLD, sc, &r));
  EXPECT_EQ(r.failure, "");
  return r;
}

void print(const solvers::SweepResult& r) {
  for (const auto& e : r.events)
    std::printf("%s loci %d-%d at %s = %.4f: gap %.4f at omega_bar %.3f, exchange %.2f, mixing %.2f, mode shift %d\n",
                e.kind.c_str(), e.lower + 1, e.lower + 2, r.parameterName.c_str(), e.parameter, e.gap, e.frequency,
                e.exchange, e.mixing, int(e.modeShift));
}
}  // namespace

// requirement: loci veer instead of crossing as gamma grows, with a mode shift detected by MAC
// (seed 003 abstract; Yoo & Shin 1998). Chordwise 2D beam, slenderness mu = 70, delta = 0:
// the 3rd bending locus meets the 1st stretching locus. Without the Coriolis matrix the two
// families are uncoupled about the straight steady state (K_T and M are block-diagonal in axial and
// transverse motion), so the loci cross: pure shapes, tracked identities swap. With it they veer:
// minimum gap, mixed shapes at the closest point, shapes exchanged across (mode shift).
// Measured (N = 16, 61 points): crossing at gamma = 25.5 (gap 0.13 = sampling), veering at
// gamma = 31.0 (gap 0.74, mixing 0.71, exchange 0.90). A linear-prestress model (independent
// Frobenius solution, docs/validation.md) veers at gamma ~ 25.5: the ANCF steady state is
// stretched by up to gamma^2 / (2 mu^2) = 10 % there, which stiffens the stretching mode.
TEST(RotatingSweep, CoriolisMakesLociVeerWhereTheyCrossWithout) {
  const auto sc = rotatingCantilever(2, 16, 0.0, 0.0, 70.0);
  const auto with = sweep(sc, model::SweepParameter::Gamma, 10, 40, 61, 5, true);
  const auto without = sweep(sc, model::SweepParameter::Gamma, 10, 40, 61, 5, false);
  std::printf("with Coriolis (%s, max |Re lambda|/|lambda| %.1e):\n", with.method.c_str(), with.maxRealPart);
  print(with);
  std::printf("without Coriolis (%s):\n", without.method.c_str());
  print(without);
  ASSERT_EQ(with.events.size(), 1u);
  const auto& v = with.events[0];
  EXPECT_EQ(v.kind, "veering");
  EXPECT_TRUE(v.modeShift);
  EXPECT_EQ(v.lower, 2);  // loci 3 and 4
  EXPECT_GT(v.parameter, 25.0);
  EXPECT_LT(v.parameter, 35.0);
  EXPECT_GT(v.gap / v.frequency, 3e-3);  // repelled: 5x the crossing's sampled gap
  EXPECT_LT(with.maxRealPart, 1e-8);
  ASSERT_EQ(without.events.size(), 1u);
  const auto& c = without.events[0];
  EXPECT_EQ(c.kind, "crossing");
  EXPECT_EQ(c.lower, 2);
  EXPECT_GT(c.mixing, 0.99);
  // tracking by MAC follows each shape through the crossing: the identities of loci 3 and 4 swap
  EXPECT_EQ(without.label.back()[2], 3);
  EXPECT_EQ(without.label.back()[3], 2);
  EXPECT_EQ(with.label.back()[2], 2);
}

// requirement: the point mass enters the steady state (its centrifugal load adds tension inboard)
// and the mass matrix (seed 003 Eq. 53, 57): flapwise and chordwise frequencies with a tip mass of
// ratio alpha = 1 at gamma = 10 against an independent Hermite FEM of the linear model with
// T = gamma^2 ((1 - xi^2)/2 + alpha beta H(beta - xi)) (80 elements, 6 digits; checked against the
// exact tip-mass roots 1.557298, 16.25009, 50.89584 at gamma = 0, Math. Probl. Eng. 2017, 1568019).
TEST(RotatingSweep, TipMassFrequencies) {
  // N = 64: chord_1^2 = flap_1^2 - gamma^2 amplifies the relative error by (flap_1/chord_1)^2 = 11
  // (N = 32: flap 6e-6, chord 6.7e-5, measured)
  auto sc = rotatingCantilever(3, 64, 10.0);
  model::PointMassDesc pm;
  pm.at = 1.0;
  pm.mass = 1.0 * 1000.0 * 1e-2;  // alpha = m / (rho A L) = 1
  sc.bodies[0].pointMasses.push_back(pm);
  const auto m = rotatingModes(sc, [] { solvers::ModalOptions o; o.count = 6; return o; }());
  const auto flap = family(m, 2), chord = family(m, 1);
  const double refFlap[3] = {10.486436, 43.451724, 91.284958}, refChord[3] = {3.156793, 42.285368, 90.735570};
  for (int k = 0; k < 3; ++k) {
    std::printf("tip mass alpha 1 gamma 10 mode %d: flap %.6f (ref %.6f) chord %.6f (ref %.6f)\n", k + 1, flap[k],
                refFlap[k], chord[k], refChord[k]);
    EXPECT_NEAR(flap[k] / refFlap[k], 1.0, 2e-5);
    EXPECT_NEAR(chord[k] / refChord[k], 1.0, 2e-5);
  }
}

namespace {
// The chordwise beam of seed 003's mass studies in our units: mu = 70, gamma = 10, one point mass.
model::SceneDescription beamWithMass(double location, double massRatio) {
  auto sc = rotatingCantilever(2, 16, 10.0, 0.0, 70.0);
  model::PointMassDesc pm;
  pm.at = location;
  pm.mass = massRatio * 1000.0 * 1e-2;  // alpha = m / (rho A L)
  sc.bodies[0].pointMasses.push_back(pm);
  return sc;
}

int countKind(const solvers::SweepResult& r, const std::string& kind) {
  int n = 0;
  for (const auto& e : r.events) n += e.kind == kind;
  return n;
}
}  // namespace

// requirement: veering caused by the mass ratio, and multiple veering (seed 003 abstract: "veering
// rather than crossing ... due to the changing of the magnitude of the concentrated mass"; "the
// loci will veer more than once due to different types of mode coupling between the bending and
// stretching vibrations"). A tip mass (beta = 1) of growing alpha lowers the stretching frequency
// (about mu / sqrt(alpha) for large alpha) and raises the bending ones (more tension), so the
// stretching locus passes the 3rd and then the 2nd bending locus. With Coriolis both approaches
// veer with a mode shift; without it the families are uncoupled and the loci cross (gap 0).
// Measured (100 points, alpha 0.05..5, refined by 21-point local sweeps): veering of loci 3-4 at
// alpha = 0.5325 (gap 0.39, mixing 0.75) and of loci 2-3 at alpha = 1.974 (gap 0.51, mixing
// 0.58); without Coriolis crossings at alpha = 0.491 and 1.767 with fitted gap 0.
TEST(RotatingSweep, MassRatioMakesTheStretchingLocusVeerTwice) {
  const auto sc = beamWithMass(1.0, 0.1);
  const auto with = sweep(sc, model::SweepParameter::MassRatio, 0.05, 5.0, 100, 6, true);
  const auto without = sweep(sc, model::SweepParameter::MassRatio, 0.05, 5.0, 100, 6, false);
  std::printf("mass ratio, with Coriolis:\n");
  print(with);
  std::printf("mass ratio, without Coriolis:\n");
  print(without);
  ASSERT_EQ(with.events.size(), 2u);
  EXPECT_EQ(countKind(with, "veering"), 2);
  // one locus veers twice: first with the locus above it (3-4), then with the next one down (2-3)
  EXPECT_EQ(with.events[0].lower, 2);
  EXPECT_EQ(with.events[1].lower, 1);
  for (const auto& e : with.events) {
    EXPECT_TRUE(e.modeShift);
    EXPECT_TRUE(e.refined);
    EXPECT_GT(e.gap / e.frequency, 3e-3);
  }
  EXPECT_NEAR(with.events[0].parameter, 0.53, 0.05);
  EXPECT_NEAR(with.events[1].parameter, 1.97, 0.1);
  ASSERT_EQ(without.events.size(), 2u);
  EXPECT_EQ(countKind(without, "crossing"), 2);
  for (const auto& e : without.events) EXPECT_LT(e.gap / e.frequency, 1e-3);
}

// requirement: veering caused by the mass location, multiple veering. alpha = 2, beta from the
// clamp to the tip: the stretching locus falls through loci 5, 4 and 3 in turn. Measured (100
// points, the clamp holding the slope's direction, the root stretch free): loci 4-5 at beta =
// 0.162, 3-4 at 0.433, 2-3 at 0.812 (gaps 1.04, 0.59, 0.78); without Coriolis crossings at 0.154,
// 0.419, 0.790 (gaps <= 0.033). The first two veer (shapes mixed at the minimum, mixing 0.60);
// at the third the gap is as open (0.78, 1.4 % of the frequency) but the shapes at the minimum stay
// 91 % pure with half an exchange (0.53): the stretching locus meets loci 2 and 3 at once there, and
// the two-mode mixing test labels it a crossing (with the stretch held at the root, clamped_unstretched,
// it had mixed). Asserted: three events with a mode shift at the crossings' places, every gap
// opened by Coriolis to over 5x the crossings' sampled gaps, the first two labelled veering.
TEST(RotatingSweep, MassLocationMakesTheStretchingLocusVeerThreeTimes) {
  const auto sc = beamWithMass(0.5, 2.0);
  const auto with = sweep(sc, model::SweepParameter::MassLocation, 0.0, 1.0, 100, 6, true);
  const auto without = sweep(sc, model::SweepParameter::MassLocation, 0.0, 1.0, 100, 6, false);
  std::printf("mass location, with Coriolis:\n");
  print(with);
  std::printf("mass location, without Coriolis:\n");
  print(without);
  ASSERT_EQ(with.events.size(), 3u);
  ASSERT_EQ(without.events.size(), 3u);
  EXPECT_EQ(countKind(without, "crossing"), 3);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(with.events[k].lower, 3 - k);
    EXPECT_TRUE(with.events[k].modeShift);
    EXPECT_NEAR(with.events[k].parameter, without.events[k].parameter, 0.03);
    EXPECT_GT(with.events[k].gap / with.events[k].frequency, 5.0 * 0.033 / 52.0);
    EXPECT_LT(without.events[k].gap / without.events[k].frequency, 1e-3);
    if (k < 2) {
      EXPECT_EQ(with.events[k].kind, "veering");
    }
  }
}

// requirement: vibration nodes of each mode shape against the parameter. At gamma = 0 they are
// the zeros of the Euler-Bernoulli cantilever modes, cosh bx - cos bx - s (sinh bx - sin bx)
// (Blevins, Formulas for Natural Frequency and Mode Shape, Table 8-1: 0.783; 0.504, 0.868;
// 0.358, 0.644, 0.906; 12 digits computed with mpmath). The nodes are the zeros of the cubic
// Hermite interpolant, so their error falls like h^4 (faster at gamma = 0). At gamma = 10 the reference is an
// independent Hermite FEM of the linear rotating beam, w'''' - (T w')' = omega^2 w with
// T = gamma^2 (1 - x^2) / 2 (100 and 200 elements agree to 1e-9; the chordwise shapes equal the
// flapwise ones). Rotation moves the node of mode 2 inboard (0.7834 -> 0.7748) and those of
// modes 3 and 4 outboard; mode k keeps k - 1 nodes along the sweep.
TEST(RotatingSweep, VibrationNodes) {
  const double ref0[3][3] = {{0.783444550501, 0, 0}, {0.503547873377, 0.867677591603, 0},
                             {0.358337517757, 0.644087938166, 0.905564006955}};
  const double ref10[3][3] = {{0.7748473877, 0, 0}, {0.5070810432, 0.8719374721, 0},
                              {0.3610819032, 0.6508680877, 0.9083149430}};
  std::vector<double> err0, err10;
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  for (int n : {16, 32, 64}) {
    auto sc = rotatingCantilever(2, n, 0.0, 0.0, 1e6);
    const auto r = sweep(sc, model::SweepParameter::Gamma, 0.0, 10.0, 6, 4, false);
    if (rank != 0) continue;  // shapes and nodes live on rank 0
    double e0 = 0.0, e10 = 0.0;
    for (int k = 1; k < 4; ++k) {
      for (size_t i = 0; i < r.parameter.size(); ++i)
        ASSERT_EQ(r.nodes[i][k].size(), static_cast<size_t>(k)) << "mode " << k + 1 << " point " << i;
      for (int j = 0; j < k; ++j) {
        e0 = std::max(e0, std::fabs(r.nodes[0][k][j] - ref0[k - 1][j]));
        e10 = std::max(e10, std::fabs(r.nodes.back()[k][j] - ref10[k - 1][j]));
      }
    }
    EXPECT_LT(r.nodes.back()[1][0], r.nodes[0][1][0]);  // inboard
    EXPECT_GT(r.nodes.back()[2][0], r.nodes[0][2][0]);  // outboard
    std::printf("N = %d: max node error at gamma = 0: %.2e, at gamma = 10: %.2e\n", n, e0, e10);
    err0.push_back(e0);
    err10.push_back(e10);
  }
  if (rank != 0) return;
  // measured: gamma 0: 4.7e-6, 8.1e-8, 3.9e-9 (rates 58, 21); gamma 10: 2.1e-5, 2.1e-6, 1.7e-7
  // (rates 10, 12.6; 15.1 at N = 128: pre-asymptotic, approaching h^4 from below)
  EXPECT_LT(err0[2], 1e-8);
  EXPECT_LT(err10[2], 1e-6);
  EXPECT_GT(err0[0] / err0[1], 16.0);
  EXPECT_GT(err0[1] / err0[2], 16.0);
  EXPECT_GT(err10[1] / err10[2], 12.0);
}
