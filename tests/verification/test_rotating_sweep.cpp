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
