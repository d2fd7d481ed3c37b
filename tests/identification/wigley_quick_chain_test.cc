// The glue of the quickstart's CFD chain on the Wigley hull (tools/quickstart
// stage 4): the campaign, case and mesh files it runs, and the ship file
// data/ships/wigley.yaml that takes the identified derivatives for the
// maneuvers. The CFD campaign itself (about 1.5 CPU-minutes) is the slow
// test WigleyLfsCampaign/wigley_quick (wigley_lfs_campaign_test.cc); here
// the same test matrix is run as a virtual (MMG) campaign of the Wigley ship
// file through the same commands (kelvin captive -> kelvin identify ->
// kelvin simulate --derivatives), so every file format and option between
// the stages is exercised in seconds.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "data/schema/campaign_file.h"
#include "data/schema/h5_file.h"
#include "simulator/mmg/derivative_set.h"
#include "simulator/mmg/ship_parameters.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::ident {
namespace {

namespace fs = std::filesystem;

fs::path Data() { return testing::SourceDir() / "data"; }
std::string Kelvin() { return (testing::ToolsDir() / "kelvin").string(); }

// The quickstart campaign loads, names the coarse case and the campaign ship,
// discards two ramp periods (the start-up disturbance leaves the grid during
// the second period, see wigley_lfs_campaign.yaml) and has the runs the linear
// derivatives need; the simulation ship file describes the same hull.
TEST(WigleyQuickChain, CampaignAndShipFilesDescribeTheSameHull) {
  const data::CampaignFile f =
      data::LoadCampaignFile(Data() / "cases/captive_cfd/wigley_quick_campaign.yaml");
  EXPECT_EQ(f.solver, data::CampaignFile::Solver::kCfd);
  EXPECT_EQ(f.cfd.case_file.filename(), "wigley_quick_case.yaml");
  EXPECT_TRUE(fs::exists(f.cfd.case_file));
  EXPECT_GE(f.sampling.ramp_periods, 2);
  EXPECT_GE(f.design.drift_angles.size(), 2u);
  EXPECT_GE(f.design.sway_amplitudes.size(), 1u);
  EXPECT_GE(f.design.yaw_amplitudes.size(), 1u);
  const data::CaptiveShip campaign_ship = data::LoadCaptiveShip(f.ship_file);
  const sim::ShipParameters ship = sim::LoadShip(Data() / "ships/wigley.yaml");
  EXPECT_DOUBLE_EQ(ship.principal.Lpp, campaign_ship.Lpp);
  EXPECT_DOUBLE_EQ(ship.principal.d, campaign_ship.d);
  EXPECT_DOUBLE_EQ(ship.principal.rho, campaign_ship.rho);
  EXPECT_NEAR(ship.principal.displacement * ship.principal.rho, campaign_ship.mass, 1e-9);
  EXPECT_DOUBLE_EQ(ship.approach_speed, f.speed);
  // The hull section holds CFD-identified linear derivatives with the signs
  // of a stable, conventional hull (Y'v < 0, Y'r > 0, N'v < 0, N'r < 0).
  EXPECT_LT(ship.hull.Y_v, 0);
  EXPECT_GT(ship.hull.Y_r, 0);
  EXPECT_LT(ship.hull.N_v, 0);
  EXPECT_LT(ship.hull.N_r, 0);
}

TEST(WigleyQuickChain, CaptiveIdentifySimulateCommandsChainOnTheWigleyShip) {
  testing::ScopedTempDir dir;
  // The quickstart campaign's test matrix as a virtual campaign of the ship
  // file's own model (solver mmg), 2% force noise.
  {
    std::ofstream f(dir / "campaign.yaml");
    f << "campaign: {name: wigley_virtual, ship: " << (Data() / "ships/wigley.yaml").string()
      << ", solver: mmg, speed: 1.0, noise: 0.02, seed: 3}\n"
         "tests:\n"
         "  static_drift_deg: [0, 4, 8, 12]\n"
         "  pure_sway_v_prime: [0.1, 0.2]\n"
         "  pure_yaw_r_prime: [0.1, 0.2]\n"
         "  omega_prime: 1.2\n"
         "sampling: {samples_per_period: 100, periods: 2, ramp_periods: 2}\n";
  }
  const auto captive = testing::RunCommand(Kelvin() + " captive " + (dir / "campaign.yaml").string() +
                                           " -o " + (dir / "campaign.h5").string());
  ASSERT_EQ(captive.exit_code, 0) << captive.output;
  const auto identify = testing::RunCommand(Kelvin() + " identify " + (dir / "campaign.h5").string() +
                                            " -o " + (dir / "wigley_derivatives.yaml").string());
  ASSERT_EQ(identify.exit_code, 0) << identify.output;
  // The cross terms are flagged (no combined runs) and the linear terms come
  // back: the set round-trips through the ship file's model.
  const sim::DerivativeSet set = sim::LoadDerivativeSet(dir / "wigley_derivatives.yaml");
  const sim::ShipParameters ship = sim::LoadShip(Data() / "ships/wigley.yaml");
  EXPECT_EQ(set.hull.Y_vrr, 0.0);
  EXPECT_EQ(set.hull.N_vvr, 0.0);
  for (const char* name : {"Y_v", "Y_r", "N_v", "N_r"}) {
    int i = 0;
    while (sim::HullCoefficients<double>::kNames[i] != name) ++i;
    EXPECT_NEAR(set.hull[i], ship.hull[i], 0.1 * std::abs(ship.hull[i])) << name;
  }
  const auto simulate = testing::RunCommand(
      Kelvin() + " simulate " + (Data() / "ships/wigley.yaml").string() + " --derivatives " +
      (dir / "wigley_derivatives.yaml").string() + " -m turning:35:stbd -m zigzag:10/10:stbd -o " +
      (dir / "sim").string());
  ASSERT_EQ(simulate.exit_code, 0) << simulate.output;
  // The turning circle turns to starboard (positive steady yaw rate) on a
  // finite diameter; the zig-zag has a first overshoot.
  const data::H5Reader turning(dir / "sim/Wigley_turning_35_stbd.h5");
  const double rate = turning.Read("metrics/steady_rate").values.at(0);
  const double diameter = turning.Read("metrics/tactical_diameter_over_L").values.at(0);
  std::printf("Wigley (assumed rudder): steady rate %.3g deg/s, tactical diameter %.3g L\n", rate,
              diameter);
  EXPECT_GT(rate, 0);
  EXPECT_TRUE(std::isfinite(diameter) && diameter > 0);
  const data::H5Reader zigzag(dir / "sim/Wigley_zigzag_10_10_stbd.h5");
  EXPECT_TRUE(std::isfinite(zigzag.Read("metrics/first_overshoot").values.at(0)));
}

}  // namespace
}  // namespace kelvin::ident
