// Virtual captive tests from the MMG model: the captive force model against
// the simulator's motion equations, the generated runs, and the repository's
// KVLCC2 campaign file run with solver: mmg. Ship: KVLCC2 L7 of Yasukawa &
// Yoshimura (2015), J. Mar. Sci. Technol. 20:37-52.
#include "identification/virtual_captive.h"

#include <gtest/gtest.h>

#include <cmath>

#include "data/schema/campaign_file.h"
#include "identification/captive_force_model.h"
#include "tests/data/schema/captive_test_fixtures.h"
#include "tests/simulator/simulator_test_utilities.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::ident {
namespace {

using sim::testing::Kvlcc2;


// A ship moving freely under its hull forces alone accelerates as
// MmgModel::Accelerations says; then the rigid-body inertia force equals the
// captive hydrodynamic force (hull + added-mass reactions). This ties the
// captive force model and M_RB a to the simulator's motion equations.
TEST(VirtualCaptiveTest, CaptiveForceModelMatchesMotionEquations) {
  const sim::ShipParameters ship = Kvlcc2();
  const sim::MmgModel<double> model(ship);
  const data::CaptiveShip cs = CaptiveShipFrom(ship);
  for (auto [u, v, r] :
       std::vector<std::array<double, 3>>{{1.1, -0.2, 0.05}, {0.9, 0.1, -0.08}, {1.2, 0.0, 0.0}}) {
    const sim::PlanarForce<double> hull = model.HullForces(u, v, r);
    const std::array<double, 3> acc = model.Accelerations(u, v, r, hull);
    const data::BodyKinematics k{u, v, r, acc[0], acc[1], acc[2]};
    const std::array<double, 3> f = CaptiveHydrodynamicForce(model, k);
    const std::array<double, 3> rb = data::RigidBodyInertia(cs, k);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(f[c], rb[c], 1e-9 * (1 + std::abs(rb[c]))) << "channel " << c;
  }
}

TEST(VirtualCaptiveTest, CircularMotionRunIsSteadyAndAnalysed) {
  const sim::ShipParameters ship = Kvlcc2();
  data::MotionParameters m = data::fixtures::SampleMotion(data::MotionKind::kCircularMotion);
  const data::CaptiveRun run = GenerateRun(sim::MmgModel<double>(ship), "arm", m, {});
  const std::array<double, 3> f0 = {run.force[0].back(), run.force[1].back(), run.force[2].back()};
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(run.force[c][run.force[c].size() / 2], f0[c], 1e-9 * std::abs(f0[c]));
  EXPECT_NO_THROW(data::SelectWindow(run, "arm"));
}

TEST(VirtualCaptiveTest, RepositoryCampaignRuns) {
  const data::CampaignFile f = data::LoadCampaignFile(kelvin::testing::SourceDir() /
                                                      "data/cases/kvlcc2_virtual_captive.yaml");
  EXPECT_EQ(f.name, "kvlcc2_virtual_captive");
  EXPECT_EQ(f.design.drift_angles.size(), 7u);
  EXPECT_NEAR(f.design.drift_angles[1], 2.5 * M_PI / 180, 1e-15);
  EXPECT_EQ(f.design.sway_amplitudes, (std::vector<double>{0.1, 0.2}));
  const data::CaptiveCampaign c = RunCampaign(f);
  EXPECT_EQ(c.runs.size(), 13u);  // 7 drift + 2 sway + 2 yaw + 2 yaw with drift
  EXPECT_EQ(c.ship.name, "KVLCC2");
}

}  // namespace
}  // namespace kelvin::ident
