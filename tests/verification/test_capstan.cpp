// Belt-pulley contact: the capstan (docs/validation.md, "Capstan"; issue 34).
//
// A rope over a drum that turns under it, one end pinned, the other loaded with T2. The drum's
// surface slides under the resting rope, so friction is mu p everywhere on the wrap, and the rope's
// equilibrium is the Euler-Eytelwein (capstan) equation dT/dphi = +-mu T: the pinned end holds
//   T1 = T2 exp(-+ mu theta)
// (the sign: friction drags the rope the way the drum's surface moves), and the contact pressure
// on the wrap is p = T / r (per unit length of the deformed rope). Exact for an extensible rope;
// here with bending stiffness EI / (T r^2) < 1e-4 and the penalty's sinking p / k < 1e-5 r.
//
// requirement: the pinned end's tension is T2 exp(-+ mu theta) within 1 % for theta = pi/2, pi,
//   2 pi and mu = 0.2, 0.5, both senses of the drum (issue 34), and converges with the elements;
// requirement: the contact pressure along the wrap is T(phi) / r with T(phi) = T1 exp(mu phi)
//   (and, frictionless, T2 / r uniformly);
// requirement: in time (generalized-alpha), a suddenly loaded rope with axial damping settles to
//   the same T1; a rope sliding over a frictionless fixed drum with end masses conserves energy,
//   the contact's work counted as load work (docs/user-guide.md, "Energy balance");
// requirement: the bristle law (elastic stick) gives the same capstan tension while the drum slides,
//   and, over a free pulley, moves as the Atwood machine with the energy balance closed;
// requirement: a rope pinned on a fixed drum falls onto it, its pinned element touching after the
//   Newton matrix's first assembly, with the energy balance closed (the held-block rule, decision 29);
// requirement: -n 1 and -n 2 give the same tension (this test runs on both).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "strand/solvers/Dynamics.hpp"
#include "support/DynamicRun.hpp"
#include "support/Scenes.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

constexpr double kR = 0.5, kT2 = 100.0, kEA = 1e5, kSpan = 2.0;

// The rope goes up from the pinned end at (-r, -span), turns clockwise over the drum by theta
// (pi/2, pi or 2 pi), and leaves along a tangent to its loaded end.
struct Capstan {
  model::SceneDescription scene;
  model::Vec3 pull;  // unit direction of the load at the free end
};

Capstan capstan(double theta, double mu, double omega, double elementLength, double stiffness = 1e7) {
  Capstan c;
  model::SceneDescription& sc = c.scene;
  sc.file = "(test)";
  sc.dimension = 2;
  model::PulleyDesc drum;
  drum.name = "drum";
  drum.radius = kR;
  drum.speed.value = omega;
  sc.pulleys.push_back(drum);

  Section s;
  s.E = 1e9;
  s.A = kEA / s.E;
  s.I = 1e-12;  // EI = 1e-3 N m^2
  s.rho = 1000.0;
  model::BodyDesc rope = straightBody("rope", 2, 1, {0, 0, 0}, {1, 0, 0}, s);
  model::GeometryDesc& g = rope.geometry;
  g.kind = model::GeometryKind::Wrap;
  g.start = {-kR, -kSpan, 0};
  model::WrapTurn turn;
  turn.radius = kR;
  turn.sense = -1;
  const double pi = std::acos(-1.0);
  if (std::abs(theta - pi / 2) < 1e-12) {
    g.end = {kSpan, kR, 0};
    c.pull = {1, 0, 0};
  } else if (std::abs(theta - pi) < 1e-12) {
    g.end = {kR, -kSpan, 0};
    c.pull = {0, -1, 0};
  } else {
    turn.turns = 1;
    g.end = {-kR, kSpan, 0};
    c.pull = {0, 1, 0};
  }
  g.wrap.push_back(turn);
  const double length = 2.0 * kSpan + kR * theta;
  rope.elements = static_cast<int>(std::lround(length / elementLength));
  sc.bodies.push_back(rope);

  model::SupportDesc pin;
  pin.at.body = "rope";
  pin.at.node = 0;
  pin.type = model::SupportType::Pinned;
  sc.supports.push_back(pin);
  addTipLoad(sc, {kT2 * c.pull[0], kT2 * c.pull[1], 0});

  model::ContactDesc contact;
  contact.body = "rope";
  contact.pulleys = {"drum"};
  contact.law.stiffness = stiffness;  // sinking p / k = T / (r k): 1e-4 m at 500 N and 1e7 N/m^2
  contact.law.friction = mu > 0.0 ? contact::FrictionLaw::RegularizedCoulomb : contact::FrictionLaw::None;
  contact.law.mu = mu;
  contact.law.slipVelocity = 1e-3;  // the drum's surface slides at |omega| r = 0.5 m/s: tanh(500) = 1
  contact.points = 4;
  sc.contacts.push_back(contact);
  return c;
}

struct Solved {
  std::vector<double> q;
  std::vector<assembly::Assembler::ContactPointOut> points;  // this rank's
  std::string failure;
};

Solved solve(solvers::Problem& p, int loadSteps) {
  MPI_Comm comm = p.dofs().comm();
  Vec X;
  PetscCallAbort(comm, p.dofs().createVector(&X));
  PetscCallAbort(comm, p.assembler().initialState(X));
  Solved out;
  {
    solvers::StaticSolver solver(p.assembler(), loadSteps);
    PetscCallAbort(comm, solver.setFromOptions());
    PetscCallAbort(comm, solver.solve(X, nullptr, &out.failure));
  }
  PetscCallAbort(comm, p.assembler().contactPoints(X, nullptr, 0.0, out.points));
  PetscCallAbort(comm, p.assembler().gatherToRoot(X, out.q));
  const int n = p.model().numDofs();
  out.q.resize(n);
  MPI_Bcast(out.q.data(), n, MPI_DOUBLE, 0, comm);
  VecDestroy(&X);
  return out;
}

// The cable's tension at stretch lambda = |r'|: EA times the Green strain (lambda^2 - 1) / 2 is
// the force per reference area, the tension vector EA eps_G r' has the length EA eps_G lambda.
double tensionOfStretch(double lambda) { return kEA * 0.5 * (lambda * lambda - 1.0) * lambda; }

double stretchOfTension(double T) {
  double lambda = 1.0 + T / kEA;
  for (int it = 0; it < 20; ++it)
    lambda -= (tensionOfStretch(lambda) - T) / (kEA * (1.5 * lambda * lambda - 0.5));
  return lambda;
}

// The tension at a node of the rope (straight spans: uniform).
double tensionAt(const solvers::Problem& p, const std::vector<double>& q, int node) {
  const model::Body& b = p.model().bodies()[0];
  const int blk = b.block(node, 1);
  const double scale = b.blockScale(1);
  return tensionOfStretch(std::hypot(q[blk * 2], q[blk * 2 + 1]) / scale);
}

}  // namespace

TEST(Capstan, PinnedEndHoldsT2TimesExpOfMuTheta) {
  const double pi = std::acos(-1.0);
  for (double theta : {pi / 2, pi, 2 * pi})
    for (double mu : {0.2, 0.5})
      for (double omega : {1.0, -1.0}) {
        Capstan c = capstan(theta, mu, omega, 0.05);
        solvers::Problem p(PETSC_COMM_WORLD, c.scene);
        const Solved s = solve(p, 4);
        ASSERT_TRUE(s.failure.empty()) << s.failure;
        // the path turns clockwise: a counterclockwise drum drags the rope back towards the pin
        const double exact = kT2 * std::exp(-(omega > 0 ? 1.0 : -1.0) * mu * theta);
        const double T1 = tensionAt(p, s.q, 0);
        int rank;
        MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
        if (rank == 0)
          std::printf("capstan theta %.4f mu %.1f omega %+.0f: T1 = %.4f N, T2 exp(-+mu theta) = %.4f N, error %.2e\n", theta,
                      mu, omega, T1, exact, T1 / exact - 1.0);
        EXPECT_NEAR(T1 / exact, 1.0, 0.01) << "theta " << theta << " mu " << mu << " omega " << omega;
        EXPECT_NEAR(tensionAt(p, s.q, p.model().bodies()[0].elements), kT2, 1e-3 * kT2);
      }
}

// The tri-linear creep-rate law of Leamy & Wasfy (2002): sliding (|s| = omega r = 0.5 m/s beyond
// v_s = 1e-3 m/s) it is Coulomb's, T2 e^{mu theta}; creeping (v_s = 1, 2 m/s: the rope at rest, the
// drum's surface moving under it at s = omega rho everywhere) its friction mu p s / v_s is Coulomb's
// with mu_eff = mu omega rho / v_s, so T1 = T2 e^{mu_eff theta} (rho = r less the rope's sinking,
// 1e-4 of r).
TEST(Capstan, CreepRateLawHoldsEulerEytelweinWithItsCreepFriction) {
  const double pi = std::acos(-1.0), mu = 0.5;
  for (double vs : {1e-3, 1.0, 2.0}) {
    Capstan c = capstan(pi, mu, -1.0, 0.05);
    c.scene.contacts[0].law.friction = contact::FrictionLaw::CreepRate;
    c.scene.contacts[0].law.slipVelocity = vs;
    solvers::Problem p(PETSC_COMM_WORLD, c.scene);
    const Solved s = solve(p, 4);
    ASSERT_TRUE(s.failure.empty()) << s.failure;
    const double muEff = mu * std::min(1.0, 1.0 * kR / vs), exact = kT2 * std::exp(muEff * pi);
    const double T1 = tensionAt(p, s.q, 0);
    int rank;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    if (rank == 0)
      std::printf("capstan, creep-rate law, v_s = %g m/s: T1 = %.4f N, T2 exp(mu_eff pi) = %.4f N (mu_eff %.3f), error %.2e\n",
                  vs, T1, exact, muEff, T1 / exact - 1.0);
    EXPECT_NEAR(T1 / exact, 1.0, 1e-3) << "v_s " << vs;
  }
}

// Two errors: the elements' (h) and the penalty's (the rope sinks T / (r k) into the drum and lies
// on a spiral whose radius falls as T grows, so the pressure has a share along the rope: O(1/k)).
// Measured (theta = pi, mu = 0.5): at k = 1e6 N/m^2 the error is 7.3e-4 .. 8.1e-4 for h = 0.2 ..
// 0.0125 m (the penalty's), at 1e7 1.1e-3, 1.6e-4, 7.9e-5, 8.2e-5, 6.2e-5: first the elements',
// then the penalty's floor. A stiffer penalty needs elements whose arc error (h/r)^4 r / 384 stays
// below the sinking (k = 1e8 with h = 0.2 m does not converge: docs/contact.md).
TEST(Capstan, TensionConvergesWithElementsAndPenalty) {
  const double pi = std::acos(-1.0), exact = kT2 * std::exp(0.5 * pi);
  auto error = [&](double h, double k) {
    Capstan c = capstan(pi, 0.5, -1.0, h, k);
    solvers::Problem p(PETSC_COMM_WORLD, c.scene);
    const Solved s = solve(p, 4);
    EXPECT_TRUE(s.failure.empty()) << s.failure;
    const double e = std::abs(tensionAt(p, s.q, 0) / exact - 1.0);
    int rank;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    if (rank == 0) std::printf("capstan theta = pi, mu = 0.5: k = %.0e N/m^2, h = %.4f m: relative error %.3e\n", k, h, e);
    return e;
  };
  // elements, at k = 1e7: the error falls to the penalty's floor
  const double e1 = error(0.2, 1e7), e2 = error(0.1, 1e7), e3 = error(0.05, 1e7);
  EXPECT_LT(e2, e1 / 4.0);
  EXPECT_LT(e3, e2);
  EXPECT_LT(e3, 1e-4);
  // penalty, at h = 0.025 m: the floor falls as 1/k
  const double p6 = error(0.025, 1e6), p7 = error(0.025, 1e7), p8 = error(0.025, 1e8);
  EXPECT_GT(p6 / p7, 5.0);
  EXPECT_GT(p7 / p8, 5.0);
  EXPECT_LT(p8, 2e-5);
}

TEST(Capstan, ContactPressureIsTensionOverRadius) {
  const double pi = std::acos(-1.0);
  for (double mu : {0.0, 0.3}) {
    Capstan c = capstan(pi, mu, 1.0, 0.025);
    solvers::Problem p(PETSC_COMM_WORLD, c.scene);
    const Solved s = solve(p, 4);
    ASSERT_TRUE(s.failure.empty()) << s.failure;
    const double T1 = tensionAt(p, s.q, 0);
    double worst = 0.0;
    int checked = 0;
    for (const auto& pt : s.points) {
      // the angle turned from the entry point (-r, 0), clockwise over the top: phi = pi - atan2(y, x)
      const double angle = std::atan2(pt.r[1], pt.r[0]);
      if (angle < 0.0) continue;  // below the centre: not on the wrap
      const double phi = pi - angle;
      if (phi < 0.2 || phi > pi - 0.2) continue;  // away from where the rope meets the drum
      const double T = T1 * std::exp(mu * phi), rho = std::hypot(pt.r[0], pt.r[1]);
      // per unit reference length: p_ref = p lambda, p = T / rho on the deformed rope
      const double expected = T / rho * stretchOfTension(T);
      ASSERT_TRUE(pt.state.touching);
      worst = std::max(worst, std::abs(pt.state.pressure / expected - 1.0));
      ++checked;
    }
    int total = 0;
    MPI_Allreduce(&checked, &total, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
    EXPECT_GT(total, 100);
    EXPECT_LT(worst, 2e-3) << "mu " << mu;
  }
}


// The capstan of the static test in time: T2 applied at t = 0, the rope overdamped axially
// (damping_axial 0.02 s: zeta about 3 for its first axial mode, 280 rad/s), the drum sliding under it;
// with regularized Coulomb friction and with the bristle law (k_t = 1e7 N/m^2), whose friction is
// mu p exactly where the rope slides.
TEST(Capstan, SuddenlyLoadedRopeSettlesToTheCapstanTension) {
  const double pi = std::acos(-1.0);
  for (contact::FrictionLaw law : {contact::FrictionLaw::RegularizedCoulomb, contact::FrictionLaw::Bristle}) {
    Capstan c = capstan(pi, 0.5, -1.0, 0.05);
    c.scene.analysis = model::Analysis::Dynamic;
    c.scene.bodies[0].section.set("damping_axial", 0.02);
    c.scene.bodies[0].section.set("damping_bending", 0.02);
    c.scene.contacts[0].law.friction = law;
    c.scene.contacts[0].law.tangentialStiffness = 1e7;
    const DynamicRun r = runDynamics(c.scene, 2e-3, 0.6, 0.8);
    ASSERT_TRUE(r.failure.empty()) << r.failure;
    solvers::Problem p(PETSC_COMM_WORLD, c.scene);
    const double T1 = tensionAt(p, r.q, 0), exact = kT2 * std::exp(0.5 * pi);
    int rank;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    if (rank == 0)
      std::printf("dynamic capstan at t = 0.6 s, %s: T1 = %.4f N (T2 exp(mu pi) = %.4f N)\n",
                  law == contact::FrictionLaw::Bristle ? "bristle law" : "regularized Coulomb", T1, exact);
    EXPECT_NEAR(T1 / exact, 1.0, 2e-3);
  }
}

// The Atwood machines below: 2 kg and 1 kg at the ends of the rope of the capstan scene, hanging
// 1 m below the drum's centre, released at rest under gravity, generalized-alpha at rho_inf = 1
// (no numerical dissipation), dt 0.5 ms, 0.3 s. A softer penalty (1e5 N/m^2): the contact's own
// frequency sqrt(k / rho A) = 1000 rad/s stays resolved (omega dt = 0.5) without dissipation.
// With x the 2 kg mass's drop the hanging spans differ by 2x, so (rope inextensible)
//   M x'' = (m1 - m2) g + 2 rho A g x,   x' = (m1 - m2) / (2 rho A) k sinh(k t),  k = sqrt(2 rho A g / M),
// with M = m1 + m2 + rho A L, plus J / rho^2 over a free pulley (rho: the rope's centerline radius).
namespace {

constexpr double kRhoA = 1000.0 * kEA / 1e9;

double atwoodLength() { return 2.0 * 1.0 + kR * std::acos(-1.0); }

model::SceneDescription atwood(double mu, double slipVelocity) {
  Capstan c = capstan(std::acos(-1.0), mu, 0.0, 0.05);
  model::SceneDescription& sc = c.scene;
  sc.analysis = model::Analysis::Dynamic;
  sc.supports.clear();
  sc.loads.nodal.clear();
  sc.loads.gravity = {0, -9.81, 0};
  model::PointMassDesc a, b;
  a.at = 0.0;
  a.mass = 2.0;
  b.at = atwoodLength();
  b.mass = 1.0;
  sc.bodies[0].pointMasses = {a, b};
  sc.bodies[0].geometry.start = {-kR, -1.0, 0};  // spans of 1 m: the rope slides 0.2 m in 0.3 s
  sc.bodies[0].geometry.end = {kR, -1.0, 0};
  sc.bodies[0].elements = static_cast<int>(std::lround(atwoodLength() / 0.05));
  sc.contacts[0].law.stiffness = 1e5;
  sc.contacts[0].law.slipVelocity = slipVelocity;
  return sc;
}

double atwoodSpeed(double M, double t) {
  const double k = std::sqrt(2.0 * kRhoA * 9.81 / M);
  return 1.0 / (2.0 * kRhoA) * k * std::sinh(k * t);
}



// A free-pulley Atwood run (pulley 0 with its inertia J) against the closed form: the pulley's
// speed omega and the rope's x'/rho, the kinetic energy and M x'^2/2 with M = m1 + m2 + rho A L +
// J/rho^2, the balance's drift and the largest kinetic or potential energy. The rope sits on the
// pulley at rho = R - T / (R k) (T about 13 N: 2.6e-4 m).
struct FreeAtwood {
  double omega = 0, ropeOmega = 0, kinetic = 0, exactKinetic = 0, drift = 0, scale = 0;
};
FreeAtwood freeAtwood(const model::SceneDescription& sc, const DynamicRun& r) {
  solvers::Problem p(PETSC_COMM_WORLD, sc);
  const double J = sc.pulleys[0].inertia, rho = kR - 13.0 / (kR * 1e5);
  const solvers::DynamicsStep& last = r.steps.back();
  const double M = 3.0 + kRhoA * atwoodLength() + J / (rho * rho), xdot = atwoodSpeed(M, last.time);
  FreeAtwood a;
  a.omega = r.v[2 * p.model().pulleyBlock(0)];
  a.ropeOmega = xdot / rho;
  a.kinetic = last.kinetic;
  a.exactKinetic = 0.5 * M * xdot * xdot;
  a.drift = energyDrift(r);
  for (const solvers::DynamicsStep& st : r.steps) a.scale = std::max({a.scale, st.kinetic, std::abs(st.potential)});
  return a;
}

}  // namespace

// Over a frictionless fixed drum: the rope slides; nothing dissipates, so kinetic + strain +
// potential energy minus the contact's work stays at its start to the scheme's error, and the rope
// moves as the heavy-rope Atwood machine.
TEST(Capstan, RopeSlidingOverAFrictionlessDrumConservesEnergy) {
  const DynamicRun r = runDynamics(atwood(0.0, 1e-3), 5e-4, 0.3, 1.0);
  ASSERT_TRUE(r.failure.empty()) << r.failure;
  double scale = 0.0;
  for (const solvers::DynamicsStep& st : r.steps)
    scale = std::max({scale, st.kinetic, std::abs(st.potential), std::abs(st.loadWork)});
  const double drift = energyDrift(r);
  const solvers::DynamicsStep& last = r.steps.back();
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0)
    std::printf("Atwood over a frictionless drum: T = %.4f J, P = %.4f J, contact work %.4f J, drift %.2e J of %.3f J\n",
                last.kinetic, last.potential, last.loadWork, drift, scale);
  EXPECT_LT(drift, 1e-3 * scale);
  const double M = 3.0 + kRhoA * atwoodLength(), xdot = atwoodSpeed(M, last.time);
  EXPECT_NEAR(last.kinetic / (0.5 * M * xdot * xdot), 1.0, 1e-2);
}

// Over a pulley free to turn (J = 0.5 kg m^2) with friction (mu = 0.5): the rope grips it (the
// capstan allows T1/T2 up to e^{mu pi} = 4.8, the pulley's inertia needs far less), so the pulley
// turns with the rope, omega = x' / rho, and adds J / rho^2 to the moving mass. Regularized
// friction grips by creeping, |s| < v_s: omega lags x' / rho by O(v_s) (measured 5.4e-3, 1.9e-3,
// 7.5e-4 at v_s = 0.03, 0.01, 0.003 m/s). At v_s = 1e-3 m/s (dt 0.5 ms, rho_inf 1) Newton stalls:
// it converges linearly at about 0.9 per iteration and gives up after step 49 (docs/contact.md).
// Energy: the pulley's kinetic energy is in T, the friction's creep work in the contact's.
TEST(Capstan, RopeTurnsAFreePulleyAsTheAtwoodMachineWithThePulleysInertia) {
  const double J = 0.5;
  std::vector<double> lag;
  for (double vs : {0.03, 0.01, 0.003}) {
    model::SceneDescription sc = atwood(0.5, vs);
    sc.pulleys[0].inertia = J;
    const DynamicRun r = runDynamics(sc, 5e-4, 0.3, 1.0);
    ASSERT_TRUE(r.failure.empty()) << r.failure;
    const FreeAtwood a = freeAtwood(sc, r);
    lag.push_back(1.0 - a.omega / a.ropeOmega);
    int rank;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    if (rank == 0)
      std::printf("Atwood over a free pulley, v_s = %g m/s: omega = %.5f rad/s (x'/rho = %.5f), T = %.5f J "
                  "(M x'^2/2 = %.5f J), drift %.2e J of %.3f J\n",
                  vs, a.omega, a.ropeOmega, a.kinetic, a.exactKinetic, a.drift, a.scale);
    EXPECT_NEAR(a.kinetic / a.exactKinetic, 1.0, 1e-3);
    EXPECT_LT(a.drift, 1e-4 * a.scale);
  }
  EXPECT_GT(lag[0], lag[1]);
  EXPECT_GT(lag[1], lag[2]);
  EXPECT_LT(lag[2], 1e-3);
  EXPECT_GT(lag[2], 0.0);
}

// The same machine (v_s = 0.01 m/s) under the first-order schemes: BDF2 (dt 0.25 ms) and explicit
// RK4 (dt 20 us: the contact's frequency, 1.3e5 rad/s, bounds its step). The same closed form.
TEST(Capstan, FreePulleyAtwoodMachineUnderTheFirstOrderSchemes) {
  const double J = 0.5;
  model::SceneDescription sc = atwood(0.5, 0.01);
  sc.pulleys[0].inertia = J;
  for (const auto& [integrator, dt, name] : {std::tuple{model::Integrator::Bdf, 2.5e-4, "BDF2"},
                                             std::tuple{model::Integrator::Rk4, 2e-5, "RK4"}}) {
    const DynamicRun r = runDynamics(sc, dt, 0.3, 1.0, integrator, 2);
    ASSERT_TRUE(r.failure.empty()) << name << ": " << r.failure;
    const FreeAtwood a = freeAtwood(sc, r);
    int rank;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    if (rank == 0)
      std::printf("Atwood over a free pulley, %s: omega = %.5f rad/s (x'/rho = %.5f), T = %.5f J (M x'^2/2 = %.5f J), "
                  "drift %.2e J of %.3f J\n",
                  name, a.omega, a.ropeOmega, a.kinetic, a.exactKinetic, a.drift, a.scale);
    EXPECT_NEAR(a.kinetic / a.exactKinetic, 1.0, 1e-3) << name;
    EXPECT_NEAR(a.omega / a.ropeOmega, 1.0, 5e-3) << name;
    EXPECT_LT(a.drift, 1e-3 * a.scale) << name;
  }
}

// A free pulley's own terms: inertia J, rotational damping c and a load torque tau, under a rope
// that slides on it without friction (no torque from the rope): J omega' = tau - c omega, so
// omega(t) = tau / c (1 - exp(-c t / J)).
TEST(Capstan, FreePulleySpinsUpUnderItsTorqueAgainstItsDamping) {
  const double pi = std::acos(-1.0), J = 0.5, c = 2.0, tau = 3.0;
  Capstan cap = capstan(pi, 0.0, 0.0, 0.05);
  model::SceneDescription& sc = cap.scene;
  sc.analysis = model::Analysis::Dynamic;
  sc.pulleys[0].inertia = J;
  sc.pulleys[0].damping = c;
  sc.pulleys[0].torque.value = tau;
  sc.bodies[0].section.set("damping_axial", 0.02);
  const DynamicRun r = runDynamics(sc, 1e-3, 0.5, 0.9);
  ASSERT_TRUE(r.failure.empty()) << r.failure;
  solvers::Problem p(PETSC_COMM_WORLD, sc);
  const double omega = r.v[2 * p.model().pulleyBlock(0)];
  const double exact = tau / c * (1.0 - std::exp(-c * 0.5 / J));
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0) std::printf("free pulley at t = 0.5 s: omega = %.7f rad/s (exact %.7f)\n", omega, exact);
  EXPECT_NEAR(omega / exact, 1.0, 1e-4);
}

// The free-pulley Atwood machine with the bristle law: the rope sticks to the pulley (|T1 - T2| r
// is far below the capstan's limit) and moves as the Atwood machine with the pulley's inertia; the
// bristle's elastic energy is part of the contact's work, so the balance closes.
TEST(Capstan, BristleLawTurnsAFreePulleyAsTheAtwoodMachine) {
  const double J = 0.5;
  model::SceneDescription sc = atwood(0.5, 1e-2);
  sc.pulleys[0].inertia = J;
  sc.contacts[0].law.friction = contact::FrictionLaw::Bristle;
  sc.contacts[0].law.tangentialStiffness = 1e6;
  const DynamicRun r = runDynamics(sc, 5e-4, 0.3, 1.0);
  ASSERT_TRUE(r.failure.empty()) << r.failure;
  solvers::Problem p(PETSC_COMM_WORLD, sc);
  const int blk = p.model().pulleyBlock(0);
  ASSERT_GE(blk, 0);
  const solvers::DynamicsStep& last = r.steps.back();
  double scale = 0.0;
  for (const solvers::DynamicsStep& st : r.steps) scale = std::max({scale, st.kinetic, std::abs(st.potential)});
  const double rho = kR - 13.0 / (kR * 1e5);
  const double M = 3.0 + kRhoA * atwoodLength() + J / (rho * rho), xdot = atwoodSpeed(M, last.time);
  const double drift = energyDrift(r);
  const double drop = -1.0 - r.q[p.model().bodies()[0].posBlock[0] * 2 + 1], turned = r.q[2 * blk] * rho;
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0)
    std::printf("Atwood over a free pulley, bristle law: T = %.5f J (M x'^2/2 = %.5f J), drift %.2e J of %.3f J; "
                "drop %.5e m, pulley surface %.5e m\n",
                last.kinetic, 0.5 * M * xdot * xdot, drift, scale, drop, turned);
  EXPECT_NEAR(last.kinetic / (0.5 * M * xdot * xdot), 1.0, 1e-3);
  EXPECT_LT(drift, 1e-4 * scale);
  EXPECT_NEAR(turned / drop, 1.0, 2e-2);  // the rope's stretch and sinking: 1e-2
}

// A rope pinned at the top of a fixed frictionless drum, horizontal, falls onto it. The pinned
// node's position block is held, and held blocks are left out of the Newton matrix, but not on a
// body in contact: the drum's contact writes the whole block of element 0 (the pinned node's) once
// that element touches, which happens steps after the matrix's first assembly (the rope falls
// x^2 / (2 R) = 2.5 mm onto the drum at x = 0.05 m in about 23 ms). With the held blocks left
// out, PETSc stopped there with a new nonzero (docs/architecture.md, decision 29). Nothing
// dissipates (rho_inf 1, no friction): the energy balance with the penalty's stored energy closes.
TEST(Capstan, RopePinnedOnAFixedDrumFallsOntoItAndConservesEnergy) {
  Capstan c = capstan(std::acos(-1.0), 0.0, 0.0, 0.05);
  model::SceneDescription& sc = c.scene;
  sc.analysis = model::Analysis::Dynamic;
  sc.loads.nodal.clear();
  sc.loads.gravity = {0, -9.81, 0};
  model::BodyDesc& rope = sc.bodies[0];
  rope.geometry = model::GeometryDesc{};
  rope.geometry.kind = model::GeometryKind::Line;
  rope.geometry.start = {0, kR, 0};
  rope.geometry.end = {1.0, kR, 0};
  rope.elements = 20;
  sc.contacts[0].law.stiffness = 1e5;
  int firstTouch = -1;  // the first step with element 0 pressed onto the drum
  const StepHook touch = [&](solvers::Problem& p, const solvers::DynamicsStep& st, Vec X, Vec V) -> PetscErrorCode {
    PetscFunctionBeginUser;
    std::vector<assembly::Assembler::ContactPointOut> pts;
    PetscCall(p.assembler().contactPoints(X, V, st.time, pts));
    int mine = 0, any = 0;
    for (const auto& pt : pts) mine |= pt.element == 0 && pt.state.pressure > 0.0;
    MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, p.dofs().comm());
    if (any && firstTouch < 0) firstTouch = static_cast<int>(st.step);
    PetscFunctionReturn(0);
  };
  const DynamicRun r = runDynamics(sc, 5e-4, 0.15, 1.0, model::Integrator::GeneralizedAlpha, 2, touch);
  ASSERT_TRUE(r.failure.empty()) << r.failure;
  double scale = 0.0;
  for (const solvers::DynamicsStep& st : r.steps)
    scale = std::max({scale, st.kinetic, std::abs(st.potential), std::abs(st.loadWork)});
  const double drift = energyDrift(r);
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0)
    std::printf("rope pinned on a fixed drum: element 0 touches at step %d; drift %.2e J of %.4f J\n", firstTouch,
                drift, scale);
  EXPECT_GT(firstTouch, 1);  // after the Newton matrix's first assembly
  EXPECT_LT(drift, 1e-3 * scale);
}
