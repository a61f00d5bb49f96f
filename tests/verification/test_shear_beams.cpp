// Verification of the 2D shear-deformable ANCF beams, AncfBeam2dShear (Omar & Shabana 2001) and
// AncfBeam2dLinear (Kerkkanen, Sopanen & Mikkola 2005), seed 004 ch. 2 (docs/elements/ancf-beam-2d.md).
//
// requirement: a linear cantilever under a tip force F against Timoshenko beam theory,
//   w = F L^3 / (3 E I) + F L / (k G A), for L/h = 4, 10, 100, 1000. Both elements bend with a
//   constant curvature per element (the cross-section vector r_y is linear; seed 004 p. 29: "the
//   element of Omar and Shabana exhibits linear bending behavior"), and their mean shear is exact,
//   so the nodal rotations are exact and the deflection integrates the rotation by the trapezoidal
//   rule: w_h = w - F L^3 / (12 E I N^2) exactly (rate 2 in N, any L/h) for every rule that does
//   not lock. The linear element with full integration locks (seed 004 sec. 2.2.1, Fig. 2.2).
// requirement: the patch tests of seed 004 sec. 2 (pure bending, axial stretch; the linearly
//   varying moment is the tip force above) are exact for every element and rule that does not lock;
//   with plane-stress / plane-strain elasticity pure bending is too stiff by the Poisson factors
//   1 - nu^2 and (1 + nu)(1 - 2 nu)/(1 - nu) (Poisson locking), with the decoupled form of
//   seed 004 Eq. 2.18 it is exact.
// requirement: large deflection (P L^2 / E I = 2, L/h = 20) converges at rate 2 to the exact
//   solution of the elements' continuum model (tests/support/DirectorBeam.hpp, Chebyshev collocation).
// requirement: the natural frequencies of a thick cantilever (L/h = 5) converge to Timoshenko's,
//   first bending mode and the first mode of the second ("shear") spectrum, with rate 2; the axial
//   modes are those of the rod, (2n - 1) pi / (2 L) sqrt(E / rho).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "strand/solvers/ModalSolver.hpp"
#include "support/DirectorBeam.hpp"
#include "support/ShearBeams.hpp"
#include "support/Timoshenko.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

const char* const kKinds[] = {"AncfBeam2dShear", "AncfBeam2dLinear"};
const char* const kRules[] = {"full", "reduced", "selective"};

bool locks(const std::string& kind, const std::string& rule) { return kind == "AncfBeam2dLinear" && rule == "full"; }

RectangleSection slenderness(double Lh) {
  RectangleSection s;
  s.height = 1.0 / Lh;
  return s;
}

// The tip of a cantilever of length 1 (node positions), solved in `steps` load steps.
model::Vec3 tipUnder(const model::SceneDescription& sc, int steps = 1) {
  solvers::Problem p(PETSC_COMM_WORLD, sc);
  std::string failure;
  const auto q = solveStatic(p, steps, &failure);
  EXPECT_TRUE(failure.empty()) << failure;
  return nodePosition(p, q, 0, -1);
}

}  // namespace

TEST(ShearBeams, TipForceGivesTimoshenkoWithTheTrapezoidalRotationError) {
  for (const char* kind : kKinds)
    for (const char* rule : kRules)
      for (double Lh : {4.0, 10.0, 100.0, 1000.0})
        for (int n : {1, 2, 4, 16}) {
          const RectangleSection s = slenderness(Lh);
          auto sc = shearCantilever(kind, n, 1.0, s, rule);
          const double F = 1e-7 * s.E * s.inertia();  // w/L ~ 3e-8: geometric nonlinearity ~1e-15
          addTipLoad(sc, {0, -F, 0});
          const double w = -tipUnder(sc)[1];
          const double timoshenko = timoshenkoTipDeflection(F, 1.0, s);
          const double discrete = timoshenko - F / (12.0 * s.E * s.inertia() * n * n);
          const std::string where = std::string(kind) + " " + rule + " L/h " + std::to_string(Lh) + " N " + std::to_string(n);
          if (locks(kind, rule)) {
            EXPECT_LT(w / timoshenko, 1.0 - 0.9 / (4.0 * n * n)) << where;  // stiffer than the discrete solution
            continue;
          }
          EXPECT_NEAR(w / discrete, 1.0, 1e-7) << where;
        }
}

// Shear locking of the linear element with full integration: the error grows with L/h (seed 004
// sec. 2.2.1); selective integration removes it.
TEST(ShearBeams, FullIntegrationLocksTheLinearElementAndSelectiveDoesNot) {
  std::vector<double> locked;
  for (double Lh : {10.0, 100.0, 1000.0}) {
    const RectangleSection s = slenderness(Lh);
    const double F = 1e-7 * s.E * s.inertia();
    for (const char* rule : {"full", "selective"}) {
      auto sc = shearCantilever("AncfBeam2dLinear", 16, 1.0, s, rule);
      addTipLoad(sc, {0, -F, 0});
      const double ratio = -tipUnder(sc)[1] / timoshenkoTipDeflection(F, 1.0, s);
      std::printf("L/h %6g %-9s w / w_Timoshenko = %.6f\n", Lh, rule, ratio);
      if (std::string(rule) == "full") locked.push_back(ratio);
      else EXPECT_NEAR(ratio, 1.0, 1.0 / (4.0 * 16 * 16) + 1e-6);
    }
  }
  EXPECT_LT(locked[0], 0.9);   // L/h = 10: 11 % too stiff at N = 16
  EXPECT_LT(locked[1], 0.1);   // L/h = 100
  EXPECT_LT(locked[2], 0.01);  // L/h = 1000: locked
}

TEST(ShearBeams, PatchTestsPureBendingAndAxialStretchAreExact) {
  for (const char* kind : kKinds)
    for (const char* rule : kRules) {
      if (locks(kind, rule)) continue;
      for (int n : {1, 3}) {
        const RectangleSection s = slenderness(50.0);
        const std::string where = std::string(kind) + " " + rule + " N " + std::to_string(n);
        {  // pure bending: w = M L^2 / (2 E I), no shear
          auto sc = shearCantilever(kind, n, 1.0, s, rule);
          const double M = 1e-8 * s.E * s.inertia();
          addTipLoad(sc, {0, 0, 0}, {0, 0, -M});
          EXPECT_NEAR(-tipUnder(sc)[1] / (M / (2.0 * s.E * s.inertia())), 1.0, 1e-9) << where;
        }
        {  // axial stretch: the Green strain e0 = (lambda^2 - 1)/2 carries P = E A e0 lambda
          auto sc = shearCantilever(kind, n, 1.0, s, rule);
          const double EA = s.E * s.area(), P = 1e-4 * EA;
          double lambda = 1.0;
          for (int it = 0; it < 20; ++it)
            lambda -= (0.5 * EA * lambda * (lambda * lambda - 1.0) - P) / (0.5 * EA * (3.0 * lambda * lambda - 1.0));
          addTipLoad(sc, {P, 0, 0});
          EXPECT_NEAR((tipUnder(sc)[0] - 1.0) / (lambda - 1.0), 1.0, 1e-9) << where;
        }
      }
    }
}

TEST(ShearBeams, PoissonLockingFactorsOfThePlaneElasticityForms) {
  const RectangleSection s = slenderness(100.0);
  const double nu = s.nu;
  struct Form {
    const char* name;
    double factor;  // bending deflection over the exact E I one
  } forms[] = {{"decoupled", 1.0}, {"plane_stress", 1.0 - nu * nu}, {"plane_strain", (1.0 + nu) * (1.0 - 2.0 * nu) / (1.0 - nu)}};
  for (const char* kind : kKinds)
    for (const Form& f : forms) {
      auto sc = shearCantilever(kind, 4, 1.0, s, "selective", f.name);
      const double M = 1e-8 * s.E * s.inertia();
      addTipLoad(sc, {0, 0, 0}, {0, 0, -M});
      EXPECT_NEAR(-tipUnder(sc)[1] / (M / (2.0 * s.E * s.inertia())), f.factor, 1e-8) << kind << " " << f.name;
    }
}

TEST(ShearBeams, LargeDeflectionConvergesAtRateTwoToTheContinuumSolution) {
  RectangleSection s = slenderness(20.0);
  const double P = 2.0 * s.E * s.inertia();  // P L^2 / E I = 2, L = 1
  const DirectorBeam model{s.E, s.shearModulus(), s.shearFactor(), s.area(), s.inertia(),
                           s.width * std::pow(s.height, 5) / 80.0, 1.0};
  const double F[2] = {0.0, -P};
  const auto reference = model.cantilever(F, 64).tip();
  const auto finer = model.cantilever(F, 80).tip();
  std::printf("continuum tip (%.12f, %.12f), 80 points: %.2e apart\n", reference[0], reference[1],
              std::hypot(finer[0] - reference[0], finer[1] - reference[1]));
  ASSERT_LT(std::hypot(finer[0] - reference[0], finer[1] - reference[1]), 1e-9);
  for (const char* kind : kKinds)
    for (const char* rule : kRules) {
      if (locks(kind, rule)) continue;
      std::vector<double> err;
      for (int n : {8, 16, 32, 64}) {
        auto sc = shearCantilever(kind, n, 1.0, s, rule);
        addTipLoad(sc, {0, -P, 0});
        const model::Vec3 tip = tipUnder(sc, 10);
        err.push_back(std::hypot(tip[0] - reference[0], tip[1] - reference[1]));
        std::printf("%s %-9s N %2d tip error %.3e\n", kind, rule, n, err.back());
      }
      const double rate = std::log2(err[2] / err[3]);
      EXPECT_NEAR(rate, 2.0, 0.15) << kind << " " << rule;
      EXPECT_LT(err[3], 1e-4) << kind << " " << rule;
    }
}

TEST(ShearBeams, ThickCantileverFrequenciesConvergeToTimoshenkosBothSpectra) {
  RectangleSection s = slenderness(5.0);
  s.width = 0.1;
  const TimoshenkoBeam beam{s.E * s.inertia(), s.shearFactor() * s.shearModulus() * s.area(), s.rho * s.area(),
                            s.rho * s.inertia(), 1.0};
  const double cutoff = std::sqrt(beam.kGA / beam.rhoI);
  std::vector<double> bending = beam.frequencies(8, 1.2 * cutoff);
  ASSERT_EQ(bending.size(), 8u);
  ASSERT_GT(bending.back(), cutoff);  // the eighth is the first of the second spectrum
  std::vector<double> reference = bending;
  for (int n = 1; n <= 4; ++n) reference.push_back((2 * n - 1) * M_PI / 2.0 * std::sqrt(s.E / s.rho));
  std::sort(reference.begin(), reference.end());
  const auto first = std::find(reference.begin(), reference.end(), bending[0]) - reference.begin();
  const auto shear = std::find(reference.begin(), reference.end(), bending[7]) - reference.begin();
  for (const char* kind : kKinds) {
    std::vector<double> errFirst, errShear;
    for (int n : {16, 32, 64}) {
      auto sc = shearCantilever(kind, n, 1.0, s, "selective");
      solvers::Problem p(PETSC_COMM_WORLD, sc);
      Vec X;
      PetscCallAbort(PETSC_COMM_WORLD, p.dofs().createVector(&X));
      PetscCallAbort(PETSC_COMM_WORLD, p.assembler().initialState(X));
      solvers::ModalResult r;
      PetscCallAbort(PETSC_COMM_WORLD, solvers::solveModes(p.assembler(), X, static_cast<int>(reference.size()), &r));
      ASSERT_EQ(r.omega.size(), reference.size());
      for (double res : r.relativeResidual) EXPECT_LT(res, 1e-8);
      for (size_t k = 0; k < reference.size() && n == 64; ++k)  // every mode identified
        EXPECT_NEAR(r.omega[k] / reference[k], 1.0, 0.01) << kind << " N " << n << " mode " << k + 1;
      errFirst.push_back(std::fabs(r.omega[first] / reference[first] - 1.0));
      errShear.push_back(std::fabs(r.omega[shear] / reference[shear] - 1.0));
      std::printf("%s N %2d: bending 1 %.6g (Timoshenko %.6g), second spectrum 1 %.6g (%.6g)\n", kind, n,
                  r.omega[first], reference[first], r.omega[shear], reference[shear]);
      solvers::destroyModes(&r);
      VecDestroy(&X);
    }
    EXPECT_NEAR(std::log2(errFirst[1] / errFirst[2]), 2.0, 0.2) << kind;
    EXPECT_NEAR(std::log2(errShear[1] / errShear[2]), 2.0, 0.3) << kind;
    EXPECT_LT(errFirst[2], 1e-4) << kind;
    EXPECT_LT(errShear[2], 2e-3) << kind;  // 2.6e-4 (Shear), 1.3e-3 (Linear) at N = 64
  }
}

// requirement: gravity (rho A g), a distributed load p and the weight of a point mass m_p at the tip
// load the shear beams consistently (KernelFamily: consistent loads from the centerline
// interpolation): the tip deflection converges at rate 2 to Timoshenko's
// (q L^4 / (8 E I) + q L^2 / (2 k G A)) + (m_p g L^3 / (3 E I) + m_p g L / (k G A)), q = rho A g + p.
TEST(ShearBeams, SelfWeightDistributedLoadAndPointMassConvergeToTimoshenko) {
  const RectangleSection s = slenderness(10.0);
  const double g = 9.81, p = 2e3, mp = 50.0, q = s.rho * s.area() * g + p;
  const double kGA = s.shearFactor() * s.shearModulus() * s.area(), EI = s.E * s.inertia();
  const double exact = q / (8.0 * EI) + q / (2.0 * kGA) + mp * g / (3.0 * EI) + mp * g / kGA;
  for (const char* kind : kKinds) {
    std::vector<double> err;
    for (int n : {8, 16, 32}) {
      auto sc = shearCantilever(kind, n, 1.0, s, "selective");
      sc.loads.gravity = {0, -g, 0};
      model::DistributedLoadDesc d;
      d.body = "beam";
      d.forcePerLength = {0, -p, 0};
      sc.loads.distributed.push_back(d);
      sc.bodies[0].pointMasses.push_back({1.0, mp, {}});
      err.push_back(std::fabs(-tipUnder(sc)[1] / exact - 1.0));
    }
    std::printf("%s: tip error %.3e %.3e %.3e\n", kind, err[0], err[1], err[2]);
    EXPECT_NEAR(std::log2(err[0] / err[1]), 2.0, 0.1) << kind;
    EXPECT_NEAR(std::log2(err[1] / err[2]), 2.0, 0.1) << kind;
  }
}
