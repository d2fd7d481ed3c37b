// Acceptance 4 of issue 9: a 35 deg turning circle simulated with the
// identified derivative set matches the one with the true set within 1% in
// advance and tactical diameter. Truth: KVLCC2 L7 model, Yasukawa & Yoshimura
// (2015), J. Mar. Sci. Technol. 20:37-52 (data/ships/kvlcc2.yaml), whose
// propeller and rudder models are kept; only the hull coefficients change.
#include <gtest/gtest.h>

#include <cmath>

#include "identification/joint_fit.h"
#include "identification/virtual_captive.h"
#include "simulator/maneuvers/runner.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::ident {
namespace {

sim::TurningMetrics Turn(const sim::ShipParameters& ship) {
  const sim::ManeuverResult r = sim::RunManeuver(
      sim::MmgModel<double>(ship), sim::ManeuverSpec::Parse("turning:35:stbd"), sim::RunOptions{});
  EXPECT_TRUE(r.turning.has_value());
  return r.turning.value_or(sim::TurningMetrics{});
}

void CompareTurn(double noise, std::uint64_t seed) {
  const sim::ShipParameters truth = sim::LoadShip(testing::SourceDir() / "data/ships/kvlcc2.yaml");
  data::CaptiveCampaign c = GenerateCampaign(sim::MmgModel<double>(truth),
                                             data::StandardDesign(truth.approach_speed, true), {});
  if (noise > 0) AddForceNoise(c, noise, seed);
  const JointFitResult fit = FitCampaign(c, {}, "virtual");
  ASSERT_TRUE(fit.converged);
  sim::ShipParameters identified = truth;
  identified.hull = fit.coefficients;
  const sim::TurningMetrics a = Turn(truth);
  const sim::TurningMetrics b = Turn(identified);
  const double advance = b.advance / a.advance - 1,
               tactical = b.tactical_diameter / a.tactical_diameter - 1;
  std::printf(
      "noise %.0f%%: advance %.4f / %.4f m (%+.3f%%), tactical diameter %.4f / %.4f m (%+.3f%%)\n",
      100 * noise, b.advance, a.advance, 100 * advance, b.tactical_diameter, a.tactical_diameter,
      100 * tactical);
  EXPECT_LT(std::abs(advance), 0.01);
  EXPECT_LT(std::abs(tactical), 0.01);
}

TEST(TurningCircleTest, IdentifiedSetWithoutNoise) { CompareTurn(0.0, 0); }

// The flagged coefficients (X_vr, Y_rrr at this noise) are dropped, the rest
// carry the noise of the campaign; five independent campaigns.
TEST(TurningCircleTest, IdentifiedSetWithFivePercentNoise) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) CompareTurn(0.05, seed);
}

}  // namespace
}  // namespace kelvin::ident
