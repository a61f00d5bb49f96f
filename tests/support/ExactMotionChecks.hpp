// The common check of the driven-hub cases with an exact solution (tests/support/CarriedLink.hpp):
// test_multibody.cpp (2D) and test_rigid_body_3d.cpp (3D).
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include "strand/solvers/Schemes.hpp"
#include "support/CarriedLink.hpp"

namespace strand::testing {

// Generalized-alpha (rho_inf 0.9, index 3) and BDF2-GGL at h = 2 and 1 ms to tEnd: the start is
// consistent to round-off (|G v|, torque and force < 1e-12), the joint holds (< 1e-9 m), and the
// drive torque, the ground force and the energy balance converge at rate 2 +- 0.2.
inline void expectSecondOrderAgainstExactMotion(const char* label, double tEnd,
                                                const std::function<CarriedLink(const model::DynamicsDesc&)>& run) {
  for (model::Integrator integrator : {model::Integrator::GeneralizedAlpha, model::Integrator::Bdf}) {
    CarriedLink r[2];
    for (int k = 0; k < 2; ++k) {
      model::DynamicsDesc d;  // rho_inf 0.9, BDF order 2: the defaults
      d.integrator = integrator;
      d.dt = 2e-3 / (1 << k);
      d.tEnd = tEnd;
      r[k] = run(d);
      ASSERT_EQ(r[k].failure, "") << label;
      std::printf("%s, %-17s h %.0e: start |G v| %.1e, torque %.1e, force %.1e; max |x - R p| %.1e m, torque error "
                  "%.2e, force error %.2e, energy balance %.2e\n",
                  label, solvers::schemeName(d).c_str(), d.dt, r[k].startVelocity, r[k].startTorque, r[k].startForce,
                  r[k].position, r[k].torque, r[k].force, r[k].energy);
      EXPECT_LT(r[k].startVelocity, 1e-12) << label;
      EXPECT_LT(r[k].startTorque, 1e-12) << label;
      EXPECT_LT(r[k].startForce, 1e-12) << label;
      EXPECT_LT(r[k].position, 1e-9) << label;
    }
    const double torqueRate = std::log2(r[0].torque / r[1].torque), forceRate = std::log2(r[0].force / r[1].force),
                 energyRate = std::log2(r[0].energy / r[1].energy);
    std::printf("%s rates: torque %.3f, force %.3f, energy %.3f\n", label, torqueRate, forceRate, energyRate);
    EXPECT_NEAR(torqueRate, 2.0, 0.2) << label;
    EXPECT_NEAR(forceRate, 2.0, 0.2) << label;
    EXPECT_NEAR(energyRate, 2.0, 0.2) << label;
  }
}

}  // namespace strand::testing
