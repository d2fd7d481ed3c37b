// Virtual captive tests from the MMG model: the captive force model against
// the simulator's motion equations, and the generated runs. Ship: KVLCC2 L7
// of Yasukawa & Yoshimura (2015), J. Mar. Sci. Technol. 20:37-52.
#include "identification/virtual_captive.h"

#include <gtest/gtest.h>

#include <cmath>

#include "data/schema/errors.h"
#include "identification/captive_force_model.h"
#include "tests/simulator/simulator_test_utilities.h"

namespace kelvin::ident {
namespace {

using data::BodyKinematics;
using data::CaptiveRun;
using data::CaptiveShip;
using data::MotionKind;
using data::MotionParameters;
using sim::testing::Kvlcc2;

MotionParameters Motion(MotionKind kind) {
  MotionParameters m;
  m.kind = kind;
  m.U = 1.2;
  m.beta = 0.15;
  m.y_a = 0.3;
  m.psi_a = 0.2;
  m.omega = 0.6;
  m.r_prime = 0.4;
  m.t_ramp = 4.0;
  return m;
}

// A ship moving freely under its hull forces alone accelerates as
// MmgModel::Accelerations says; then the rigid-body inertia force equals the
// captive hydrodynamic force (hull + added-mass reactions). This ties the
// captive force model and M_RB a to the simulator's motion equations.
TEST(VirtualCaptiveTest, CaptiveForceModelMatchesMotionEquations) {
  const sim::ShipParameters ship = Kvlcc2();
  const sim::MmgModel<double> model(ship);
  const CaptiveShip cs = CaptiveShipFrom(ship);
  for (auto [u, v, r] :
       std::vector<std::array<double, 3>>{{1.1, -0.2, 0.05}, {0.9, 0.1, -0.08}, {1.2, 0.0, 0.0}}) {
    const sim::PlanarForce<double> hull = model.HullForces(u, v, r);
    const std::array<double, 3> acc = model.Accelerations(u, v, r, hull);
    const BodyKinematics k{u, v, r, acc[0], acc[1], acc[2]};
    const std::array<double, 3> f = CaptiveHydrodynamicForce(model, k);
    const std::array<double, 3> rb = data::RigidBodyInertia(cs, k);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(f[c], rb[c], 1e-9 * (1 + std::abs(rb[c]))) << "channel " << c;
  }
}

TEST(VirtualCaptiveTest, CircularMotionRunIsSteadyAndAnalysed) {
  const sim::ShipParameters ship = Kvlcc2();
  MotionParameters m = Motion(MotionKind::kCircularMotion);
  const CaptiveRun run = GenerateRun(sim::MmgModel<double>(ship), "arm", m, {});
  const std::array<double, 3> f0 = {run.force[0].back(), run.force[1].back(), run.force[2].back()};
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(run.force[c][run.force[c].size() / 2], f0[c], 1e-9 * std::abs(f0[c]));
  EXPECT_NO_THROW(data::SelectWindow(run, "arm"));
}

TEST(VirtualCaptiveTest, BadGeneratorOptionsNameTheOption) {
  VirtualCaptiveOptions o;
  o.samples_per_period = 4;
  try {
    o.Validate();
    FAIL();
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("'samples_per_period' = 4: expected at least 8"),
              std::string::npos);
  }
  CampaignDesign d = StandardDesign(1.0, true);
  d.sway_amplitudes = {0.1, -0.2};
  try {
    d.Validate();
    FAIL();
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("'sway_amplitudes' = -0.2"), std::string::npos)
        << e.what();
  }
  d = StandardDesign(0.0, true);
  try {
    d.Validate();
    FAIL();
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("'U' = 0"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace kelvin::ident
