// requirement: the consistent mass matrix reproduces the exact mass, center of mass and polar
// inertia of straight cables (exactly: the integrands are polynomials the cubic interpolation
// holds) and of circular arcs (converging like h^4: Hermite interpolation of the arc);
// point masses add m N^T N (seed 003 Eq. 53).
// requirement: a curved 2D cable whose initial shape is stress free (stress_free: initial) has zero
// internal force after any rigid rotation and translation (Gerstmayr & Shabana 2006, objectivity).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/Scenes.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

struct MassProps {
  double mass, com[3], polar;  // m, (1/m) int r dm, int |r|^2 dm
};

// Fill X with q0 + (R q0 + t - q0)-style values: X_i = f(model block, component, q0 block) for owned blocks.
template <class F>
void setFromModel(const solvers::Problem& p, Vec X, F&& value) {
  const int d = p.model().dim();
  for (int b = 0; b < p.model().numBlocks(); ++b) {
    const PetscInt g = p.dofs().globalBlock()[b];
    if (g < p.dofs().ownedBegin() || g >= p.dofs().ownedEnd()) continue;
    for (int i = 0; i < d; ++i)
      PetscCallAbort(PETSC_COMM_WORLD, VecSetValue(X, g * d + i, value(b, i, &p.model().initialCoordinates()[b * d]), INSERT_VALUES));
  }
  PetscCallAbort(PETSC_COMM_WORLD, VecAssemblyBegin(X));
  PetscCallAbort(PETSC_COMM_WORLD, VecAssemblyEnd(X));
}

MassProps massProperties(const model::SceneDescription& sc) {
  solvers::Problem p(PETSC_COMM_WORLD, sc);
  Mat M;
  Vec X, u, Mv;
  PetscCallAbort(PETSC_COMM_WORLD, p.dofs().createMatrix(&M, nullptr));
  PetscCallAbort(PETSC_COMM_WORLD, p.assembler().massMatrix(M));
  PetscCallAbort(PETSC_COMM_WORLD, p.dofs().createVector(&X));
  setFromModel(p, X, [](int, int i, const double* q0) { return q0[i]; });  // X = q0 (coordinates)
  PetscCallAbort(PETSC_COMM_WORLD, VecDuplicate(X, &u));
  PetscCallAbort(PETSC_COMM_WORLD, VecDuplicate(X, &Mv));
  const int d = sc.dimension;
  MassProps out{};
  PetscCallAbort(PETSC_COMM_WORLD, MatMult(M, X, Mv));
  PetscCallAbort(PETSC_COMM_WORLD, VecDot(X, Mv, &out.polar));
  for (int i = 0; i < d; ++i) {
    // unit translation along i: 1 on the position coordinates i, 0 on slopes
    PetscCallAbort(PETSC_COMM_WORLD, VecSet(u, 0.0));
    for (const model::Body& b : p.model().bodies())
      for (int blk : b.posBlock) {
        const PetscInt row = p.dofs().globalBlock()[blk] * d + i;
        if (p.dofs().globalBlock()[blk] >= p.dofs().ownedBegin() && p.dofs().globalBlock()[blk] < p.dofs().ownedEnd())
          PetscCallAbort(PETSC_COMM_WORLD, VecSetValue(u, row, 1.0, INSERT_VALUES));
      }
    PetscCallAbort(PETSC_COMM_WORLD, VecAssemblyBegin(u));
    PetscCallAbort(PETSC_COMM_WORLD, VecAssemblyEnd(u));
    double mu;
    PetscCallAbort(PETSC_COMM_WORLD, MatMult(M, u, Mv));
    PetscCallAbort(PETSC_COMM_WORLD, VecDot(u, Mv, &mu));
    if (i == 0) out.mass = mu;
    PetscCallAbort(PETSC_COMM_WORLD, VecDot(X, Mv, &out.com[i]));
  }
  for (int i = 0; i < d; ++i) out.com[i] /= out.mass;
  MatDestroy(&M);
  VecDestroy(&X);
  VecDestroy(&u);
  VecDestroy(&Mv);
  return out;
}

model::SceneDescription arc(int dim, int n, double R, double theta) {
  model::SceneDescription sc;
  sc.file = "(test)";
  sc.dimension = dim;
  model::BodyDesc b = straightBody("arc", dim, n, {0, 0, 0}, {1, 0, 0});
  b.geometry.kind = model::GeometryKind::Arc;
  b.geometry.center = {0, 0, 0};
  b.geometry.radius = R;
  b.geometry.startAngle = 0.0;
  b.geometry.endAngle = theta;
  sc.bodies.push_back(b);
  return sc;
}

}  // namespace

TEST(MassProperties, StraightCableIsExact) {
  for (int dim : {2, 3}) {
    auto sc = cantilever(dim, 7, 2.5);
    sc.supports.clear();
    const Section s;
    const double rhoA = s.rho * s.A, L = 2.5;
    const MassProps mp = massProperties(sc);
    EXPECT_NEAR(mp.mass / (rhoA * L), 1.0, 1e-14);
    EXPECT_NEAR(mp.com[0], L / 2, 1e-14);
    EXPECT_NEAR(mp.com[1], 0.0, 1e-14);
    EXPECT_NEAR(mp.polar / (rhoA * L * L * L / 3.0), 1.0, 1e-14);
  }
}

TEST(MassProperties, CircularArcConvergesAtRateFour) {
  const double R = 0.8, theta = 2.0, rhoA = Section{}.rho * Section{}.A;
  const double exactMass = rhoA * R * theta, exactPolar = exactMass * R * R;
  const double exactCom[2] = {R * std::sin(theta) / theta, R * (1.0 - std::cos(theta)) / theta};
  for (int dim : {2, 3}) {
    std::vector<double> errCom, errPolar;
    for (int n : {2, 4, 8, 16}) {
      const MassProps mp = massProperties(arc(dim, n, R, theta));
      EXPECT_NEAR(mp.mass / exactMass, 1.0, 1e-14);  // arc length is exact by construction
      errCom.push_back(std::hypot(mp.com[0] - exactCom[0], mp.com[1] - exactCom[1]) / R);
      errPolar.push_back(std::fabs(mp.polar / exactPolar - 1.0));
    }
    const double rateCom = std::log2(errCom[1] / errCom[3]) / 2.0, ratePolar = std::log2(errPolar[1] / errPolar[3]) / 2.0;
    std::printf("arc dim=%d: COM error %.2e -> %.2e (rate %.2f), inertia error %.2e -> %.2e (rate %.2f)\n", dim,
                errCom[0], errCom[3], rateCom, errPolar[0], errPolar[3], ratePolar);
    EXPECT_GT(rateCom, 3.7);
    EXPECT_GT(ratePolar, 3.7);
    EXPECT_LT(errCom[3], 1e-6);
    EXPECT_LT(errPolar[3], 1e-6);
  }
}

TEST(MassProperties, PointMassAddsItsMassAndMoment) {
  auto sc = cantilever(2, 5, 1.0);
  sc.supports.clear();
  model::PointMassDesc pm;
  pm.at = 0.37;  // inside element 1, not at a node
  pm.mass = 2.0;
  sc.bodies[0].pointMasses.push_back(pm);
  const Section s;
  const double m0 = s.rho * s.A;
  const MassProps mp = massProperties(sc);
  EXPECT_NEAR(mp.mass, m0 + 2.0, 1e-13);
  EXPECT_NEAR(mp.com[0], (m0 * 0.5 + 2.0 * 0.37) / (m0 + 2.0), 1e-13);
  EXPECT_NEAR(mp.polar, m0 / 3.0 + 2.0 * 0.37 * 0.37, 1e-13);
}

TEST(RigidMotion, StressFreeCurvedCableStaysForceFree) {
  auto sc = arc(2, 10, 0.5, 2.5);
  sc.bodies[0].stressFreeInitial = true;
  solvers::Problem p(PETSC_COMM_WORLD, sc);
  Vec X, R;
  PetscCallAbort(PETSC_COMM_WORLD, p.dofs().createVector(&X));
  PetscCallAbort(PETSC_COMM_WORLD, VecDuplicate(X, &R));
  for (double angle : {0.0, 0.7, -2.9, 3.1}) {
    // rotate and translate the reference shape: q = R q0 (+ t for positions), u = q - q0
    const double c = std::cos(angle), s = std::sin(angle);
    std::vector<char> isPos(p.model().numBlocks(), 0);
    for (int blk : p.model().bodies()[0].posBlock) isPos[blk] = 1;
    setFromModel(p, X, [&](int b, int i, const double* q0) {
      const double rot = i == 0 ? c * q0[0] - s * q0[1] : s * q0[0] + c * q0[1];
      const double t = isPos[b] ? (i == 0 ? 3.0 : -7.0) : 0.0;
      return rot + t - q0[i];
    });
    PetscCallAbort(PETSC_COMM_WORLD, p.assembler().staticResidual(X, 1.0, R));
    PetscReal norm, U;
    PetscCallAbort(PETSC_COMM_WORLD, VecNorm(R, NORM_INFINITY, &norm));
    PetscCallAbort(PETSC_COMM_WORLD, p.assembler().strainEnergy(X, &U));
    const Section sec;
    // Round-off bound (positions enter relative to each element's first node, so the translation
    // cancels exactly): a rotation by ~pi gives |u'| <= 2, and eps = r0'.u' + u'.u'/2 cancels terms
    // of size |u'|^2 <= 4, so |eps| <= 2 * 4 eps_mach; the force EA eps r' is scattered with
    // |B1| l <= 1.5 at 5 Gauss points from 2 elements per node: |f| <= 2 * 5 * 1.5 * 8 EA eps_mach.
    const double bound = 120.0 * sec.E * sec.A * 2.2e-16;
    std::printf("rigid motion angle %.1f: max residual %.3e (bound %.3e)\n", angle, norm, bound);
    EXPECT_LT(norm, bound) << "angle " << angle;
    EXPECT_LT(U, 1e-20 * sec.E * sec.A) << "angle " << angle;
  }
  VecDestroy(&X);
  VecDestroy(&R);
}
