// The free body's equations and its coupling schemes (cfd/motion/free_body.h)
// against exact solutions, with model water forces in place of the flow:
// - a constant force: the velocity grows linearly (both time schemes are exact);
// - no force: the earth-frame velocity is constant (momentum) and the kinetic
//   energy too, however the body yaws;
// - a model of the water's added mass and damping, F = -m_a dv/dt - c v, on a
//   hull lighter than its added mass: the stabilised coupling converges to the
//   exact decay of (m + m_a) dv/dt = -c v; the plain fixed point (no added
//   mass in the Jacobian) and the explicit staggered scheme both blow up, as
//   the contraction factor m_a / m > 1 says they must.
#include "cfd/motion/free_body.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

using ::testing::HasSubstr;

FreeBodyOptions Options() {
  FreeBodyOptions o;
  o.mass = 2.7778;  // the 1 m Wigley
  o.I_zG = o.mass * 0.0625;
  o.initial = {1.0, 0.0, 0.0};
  return o;
}

TEST(FreeBody, ConstantForceGivesALinearSpeedOnBothSchemes) {
  for (bool bdf2 : {false, true}) {
    FreeBodyOptions o = Options();
    o.free = {true, false, false};
    o.bdf2 = bdf2;
    FreeBody body(o);
    const double F = -0.5, dt = 0.01;
    for (int n = 1; n <= 200; ++n) {
      body.BeginStep(n * dt, dt);
      for (int k = 0; k < 3; ++k) body.Correct({F, 0.0, 0.0}, 1.0);
    }
    EXPECT_NEAR(body.velocities()[0], 1.0 + F / o.mass * 2.0, 1e-12) << "bdf2 " << bdf2;
    // x0 = t + F t^2 / (2 m): exact for BDF2 on a quadratic after its Euler
    // start (O(dt^2) there), first order for Euler.
    const double x_exact = 2.0 + 0.5 * F / o.mass * 4.0;
    EXPECT_NEAR(body.Trajectory().x0, x_exact, bdf2 ? 2e-5 : 2e-3) << "bdf2 " << bdf2;
  }
}

TEST(FreeBody, WithoutForcesTheEarthVelocityAndTheEnergyAreConstant) {
  FreeBodyOptions o = Options();
  o.initial = {1.0, 0.2, 0.5};  // yawing at 0.5 rad/s
  o.x_G = 0.0;
  FreeBody body(o);
  const Pose p0 = body.Trajectory();
  const double dt = 0.005;
  for (int n = 1; n <= 1000; ++n) {  // 5 s, 143 degrees of heading
    body.BeginStep(n * dt, dt);
    for (int k = 0; k < 4; ++k) body.Correct({}, 1.0);
  }
  const Pose p = body.Trajectory();
  EXPECT_NEAR(p.psi, 2.5, 1e-9);  // r is constant: no moment, x_G = 0
  // The body-axis velocity turns against the heading so that the earth one
  // stays: (dx0, dy0) = (1.0, 0.2) within the BDF2 error.
  EXPECT_NEAR(p.dx0, p0.dx0, 2e-4);
  EXPECT_NEAR(p.dy0, p0.dy0, 2e-4);
  const auto& nu = body.velocities();
  EXPECT_NEAR(nu[0] * nu[0] + nu[1] * nu[1], 1.04, 2e-4);
}

// The water's added-mass and damping force on a swaying hull, computed with
// the body's own discrete acceleration (as the flow's BDF2 sees the wall).
struct ModelWater {
  double m_a, c;
  PlanarLoad Force(const FreeBodyState& before, const FreeBody& body, double dt, bool bdf2) const {
    const double v = body.velocities()[1];
    const double a = bdf2 && before.steps >= 1 ? (1.5 * v - 2.0 * before.nu[1] + 0.5 * before.nu_old[1]) / dt
                                               : (v - before.nu[1]) / dt;
    return {0.0, -m_a * a - c * v, 0.0};
  }
};

// Runs a sway release of `steps` steps with `outer` outer iterations; returns
// the sway velocity (NaN or huge when the scheme blew up).
double SwayRelease(BodyCoupling scheme, double added_mass_estimate, int steps, int outer, double* exact) {
  FreeBodyOptions o = Options();
  o.free = {false, true, false};
  o.initial = {1.0, 0.1, 0.0};
  o.coupling = scheme;
  o.added_mass = {0.0, added_mass_estimate, 0.0};
  o.divergence_factor = 1e300;
  FreeBody body(o);
  const ModelWater water{2.13 * o.mass, 9.8};  // the Wigley's m_y / m and Y_v damping (kg/s)
  const double dt = 0.04;                      // the captive campaign's steady time step
  for (int n = 1; n <= steps; ++n) {
    const FreeBodyState before = body.state();
    body.BeginStep(n * dt, dt);
    for (int k = 0; k < outer; ++k) body.Correct(water.Force(before, body, dt, true), 1.0);
    if (scheme == BodyCoupling::kExplicit) body.Correct(water.Force(before, body, dt, true), 1.0);
  }
  *exact = 0.1 * std::exp(-water.c / (o.mass + water.m_a) * steps * dt);
  return body.velocities()[1];
}

TEST(FreeBody, StabilisedCouplingConvergesWhereTheNaiveSchemesBlowUp) {
  double exact = 0.0;
  const double m = Options().mass;
  // Added mass 2.13 m: the stabilised scheme with the true estimate, and
  // with an estimate 30% low, follows the exact decay (BDF2 error at
  // dt / tau = 0.045: below 0.5% over 2 s).
  for (double estimate : {2.13 * m, 0.7 * 2.13 * m}) {
    const double v = SwayRelease(BodyCoupling::kStabilised, estimate, 50, 4, &exact);
    EXPECT_NEAR(v, exact, 5e-3 * exact) << "estimate " << estimate;
  }
  // The plain fixed point (no estimate): the iterations amplify by m_a / m = 2.13.
  const double plain = SwayRelease(BodyCoupling::kStabilised, 0.0, 10, 4, &exact);
  EXPECT_FALSE(std::abs(plain) < 1.0) << plain;
  // The explicit staggered scheme: the steps amplify.
  const double expl = SwayRelease(BodyCoupling::kExplicit, 0.0, 50, 0, &exact);
  EXPECT_FALSE(std::abs(expl) < 1.0) << expl;
}

TEST(FreeBody, HeldDegreesOfFreedomFollowTheStartUpAndReportTheirLoad) {
  FreeBodyOptions o = Options();
  o.free = {true, false, false};
  o.ramp_time = 1.0;
  o.release_time = 2.0;
  FreeBody body(o);
  const double dt = 0.01;
  for (int n = 1; n <= 150; ++n) {
    body.BeginStep(n * dt, dt);
    body.Correct({-0.3, 0.0, 0.0}, 1.0);
  }
  EXPECT_DOUBLE_EQ(body.velocities()[0], 1.0);  // towed until 2 s
  EXPECT_FALSE(body.released());
  EXPECT_NEAR(body.constraint_load().X, 0.3, 1e-12);  // the carriage holds the drag
  for (int n = 151; n <= 300; ++n) {
    body.BeginStep(n * dt, dt);
    for (int k = 0; k < 3; ++k) body.Correct({-0.3, 0.0, 0.0}, 1.0);
  }
  EXPECT_TRUE(body.released());
  // Released at a step of the acceleration: BDF2 places the release within
  // the first free step, so the speed is exact up to a * dt.
  EXPECT_NEAR(body.velocities()[0], 1.0 - 0.3 / o.mass * 1.0, 0.3 / o.mass * dt);
  EXPECT_DOUBLE_EQ(body.constraint_load().X, 0.0);
}

TEST(FreeBody, StateRoundTripsAndARestartContinuesBitForBit) {
  FreeBodyOptions o = Options();
  o.initial = {1.0, 0.05, 0.1};
  auto run = [&](FreeBody& b, int from, int to) {
    for (int n = from; n <= to; ++n) {
      b.BeginStep(n * 0.02, 0.02);
      for (int k = 0; k < 3; ++k) b.Correct({-0.2 * b.velocities()[0], -3.0 * b.velocities()[1], -0.1 * b.velocities()[2]}, 1.0);
    }
  };
  FreeBody a(o), b(o);
  run(a, 1, 40);
  run(b, 1, 17);
  FreeBody c(o);
  c.SetState(FreeBodyState::Unpack(b.state().Pack()));
  run(c, 18, 40);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(a.velocities()[i], c.velocities()[i]);
  EXPECT_EQ(a.Trajectory().x0, c.Trajectory().x0);
  EXPECT_EQ(a.Trajectory().psi, c.Trajectory().psi);
  EXPECT_THROW(FreeBodyState::Unpack({1.0, 2.0}), DataFileError);
}

TEST(FreeBody, BadOptionsAndARunawaySpeedAreNamed) {
  FreeBodyOptions o = Options();
  o.mass = 0.0;
  try {
    FreeBody b(o);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("motion.mass = 0"));
  }
  o = Options();
  o.release_time = -1.0;
  EXPECT_THROW(FreeBody{o}, ConfigError);
  o = Options();
  o.free = {true, false, false};
  FreeBody b(o);
  b.BeginStep(0.1, 0.1);
  b.Correct({1e6, 0.0, 0.0}, 1.0);
  std::string why;
  EXPECT_TRUE(b.Diverged(&why));
  EXPECT_THAT(why, HasSubstr("exceeds 10 times the initial speed"));
}

}  // namespace
}  // namespace kelvin::cfd
