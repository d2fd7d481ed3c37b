// CFD captive runs with the body-force propeller and rudder (issue 21,
// tests.appendages of a campaign file, cfd/campaign/appendage_run.h) on the
// quickstart's Wigley grid: a campaign stopped part-way and resumed writes
// the same appendage runs bit for bit; with the propeller's swirl off the
// symmetric hull gives mirror loads for the rudder to port and to starboard;
// and the interaction fit of the written file places the rudder's force
// where the rudder is.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "cfd/campaign/appendage_run.h"
#include "cfd/campaign/cfd_campaign.h"
#include "cfd/run/propeller_actuator.h"
#include "cfd/run/rudder_actuator.h"
#include "data/schema/appendage_runs.h"
#include "data/schema/campaign_file.h"
#include "data/schema/captive_io.h"
#include "identification/interaction_fit.h"
#include "simulator/mmg/ship_parameters.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;

class AppendageCampaign : public ::testing::Test {
 public:
  static void SetUpTestSuite() {
    tmp_ = new kelvin::testing::ScopedTempDir();
    const fs::path src = kelvin::testing::SourceDir() / "data";
    const auto r = kelvin::testing::RunCommand((kelvin::testing::ToolsDir() / "kelvin").string() + " mesh " +
                                               (src / "cases/captive_cfd/wigley_quick_mesh.yaml").string() +
                                               " -o " + (tmp_->path() / "grid").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    // The quickstart's case on this grid.
    std::string text = kelvin::testing::ReadText(src / "cases/captive_cfd/wigley_quick_case.yaml");
    const std::string mesh = "../../../build/grids/wigley_captive_quick/constant/polyMesh";
    text.replace(text.find(mesh), mesh.size(), (tmp_->path() / "grid/constant/polyMesh").string());
    std::ofstream(tmp_->path() / "case.yaml") << text;
  }
  static void TearDownTestSuite() {
    delete tmp_;
    tmp_ = nullptr;
  }

  // A campaign of one bare straight run and the appendage runs below, 1.2 s each.
  static data::CampaignFile Campaign(const std::string& name) {
    const fs::path src = kelvin::testing::SourceDir() / "data";
    const fs::path file = tmp_->path() / (name + ".yaml");
    std::ofstream(file) << "campaign: {name: " << name << ", ship: "
                        << (src / "cases/captive_cfd/wigley_ship.yaml").string()
                        << ", solver: cfd, speed: 1.0}\n"
                           "cfd: {case: case.yaml, hull_patches: [hull], centre: [0.5, 0, 0], steady_ramp: 0.4,\n"
                           "      steady_duration: 0.8, settle: false, checkpoint_interval: 7, directory: "
                        << name << "}\n"
                        << "tests:\n  static_drift_deg: [0]\n  appendages:\n    ship: " << (src / "ships/wigley.yaml").string()
                        << "\n    propeller_rate: 59.79\n    swirl: false\n    rudder_deg: [-20, 20]\n";
    return data::LoadCampaignFile(file);
  }
  static kelvin::testing::ScopedTempDir* tmp_;
};
kelvin::testing::ScopedTempDir* AppendageCampaign::tmp_ = nullptr;

CampaignRunOptions Quiet(long stop_after = 0) {
  CampaignRunOptions o;
  o.progress = false;
  o.jobs = 1;
  o.stop_after_steps = stop_after;
  return o;
}

// The design's propeller_thickness and rudder_sample_distance reach each
// run's body-force disk and blade; without them the case loader's defaults
// (0.25 D, one chord).
TEST_F(AppendageCampaign, DiskThicknessAndSampleDistanceReachTheRuns) {
  data::CampaignFile f = Campaign("options");
  const data::AppendageTest test = data::PlanAppendageTests(*f.appendages, f.speed, 1.0).front();
  const auto options_of = [&](const data::CampaignFile& file) {
    CaseOverrides overrides;  // the campaign gives each run its step and end
    overrides.dt = 0.01;
    overrides.end_time = 0.1;
    overrides.output = tmp_->path() / "options_run";
    const Case c = LoadAppendageCase(file, test, overrides);
    double thickness = 0, sample = 0;
    for (const auto& a : c.actuators) {
      if (auto* p = dynamic_cast<const PropellerActuator*>(a.get())) thickness = p->propeller().disk().options().thickness;
      if (auto* r = dynamic_cast<const RudderActuator*>(a.get())) sample = r->rudder().options().sample_distance;
    }
    return std::pair{thickness, sample};
  };
  const double D = 0.0294;  // data/ships/wigley.yaml propeller.D_p
  const auto [t0, s0] = options_of(f);
  EXPECT_NEAR(t0, 0.25 * D, 1e-12);
  EXPECT_EQ(s0, 1.0);
  f.appendages->propeller_thickness = 0.4;
  f.appendages->rudder_sample_distance = 0.75;
  const auto [t1, s1] = options_of(f);
  EXPECT_NEAR(t1, 0.4 * D, 1e-12);
  EXPECT_EQ(s1, 0.75);
}

TEST_F(AppendageCampaign, ResumesBitForBitMirrorsTheRudderAndPlacesItsForce) {
  const data::CampaignFile whole = Campaign("whole");
  const CampaignRunSummary a = RunCfdCampaign(whole, Quiet());
  ASSERT_TRUE(a.complete);
  // Killed every 11 steps (inside runs and between checkpoints), resumed.
  const data::CampaignFile parts = Campaign("parts");
  CampaignRunSummary b;
  for (int call = 0; call < 50 && !b.complete; ++call) b = RunCfdCampaign(parts, Quiet(11));
  ASSERT_TRUE(b.complete);
  const data::AppendageCampaign ra = data::ReadAppendageRuns(a.output), rb = data::ReadAppendageRuns(b.output);
  ASSERT_EQ(ra.runs.size(), 3u);
  ASSERT_EQ(rb.runs.size(), 3u);
  for (std::size_t i = 0; i < ra.runs.size(); ++i) {
    EXPECT_EQ(ra.runs[i].name, rb.runs[i].name);
    for (auto [x, y] : {std::pair{ra.runs[i].Y, rb.runs[i].Y}, {ra.runs[i].N, rb.runs[i].N},
                        {ra.runs[i].F_N, rb.runs[i].F_N}, {ra.runs[i].u_R, rb.runs[i].u_R}, {ra.runs[i].T, rb.runs[i].T}})
      EXPECT_EQ(x, y) << ra.runs[i].name;  // bit for bit
  }
  // prop_straight, prop_rudder_-20.0deg, prop_rudder_+20.0deg. Without swirl
  // the flow is mirror-symmetric: the loads mirror to the solvers' tolerance
  // (1e-6 momentum, 1e-4 pressure relative), the straight run has no side force.
  const data::AppendageRun &s = ra.runs[0], &port = ra.runs[1], &stbd = ra.runs[2];
  ASSERT_GT(stbd.F_N, 0.1);
  EXPECT_NEAR(port.F_N, -stbd.F_N, 1e-3 * stbd.F_N);
  EXPECT_NEAR(port.Y, -stbd.Y, 1e-3 * std::abs(stbd.Y));
  EXPECT_NEAR(port.N, -stbd.N, 1e-3 * std::abs(stbd.N));
  EXPECT_NEAR(port.X, stbd.X, 1e-3 * std::abs(stbd.X));
  EXPECT_LT(std::abs(s.F_N), 1e-3 * stbd.F_N);
  EXPECT_LT(std::abs(s.Y), 1e-3 * std::abs(stbd.Y));
  // The rudder to starboard pushes the stern to port and turns the bow to
  // starboard (Y < 0, N > 0 in ship axes, z down).
  EXPECT_LT(stbd.Y, 0.0);
  EXPECT_GT(stbd.N, 0.0);
  // The fit: the side force's lever N / Y lies between the rudder and the
  // midship (x_R + a_H x_H over 1 + a_H), and the hull adds a positive
  // fraction a_H of the rudder's force (the blade stands behind the hull).
  const sim::ShipParameters ship = sim::LoadShip(kelvin::testing::SourceDir() / "data/ships/wigley.yaml");
  ident::InteractionFitOptions o;
  o.propeller = ship.propeller;
  o.rudder = ship.rudder;
  o.bare_X = ident::BareStraightX(data::ReadCampaignH5(a.output), 1.0);
  ASSERT_TRUE(o.bare_X.has_value());
  const ident::InteractionFitResult fit = ident::FitInteraction(ra, o, a.output.string());
  const double a_H = fit.Get("a_H").value, x_H = fit.Get("x_H_prime").value;
  EXPECT_TRUE(fit.Get("a_H").identified);
  EXPECT_GT(a_H, 0.0);
  EXPECT_LT(a_H, 0.5);
  const double lever = (ship.rudder.x_R_prime + a_H * x_H) / (1.0 + a_H);
  EXPECT_LT(lever, 0.0);
  EXPECT_GT(lever, ship.rudder.x_R_prime - 0.05);
  EXPECT_NEAR(fit.Get("f_alpha").value, 6.13 * (ship.rudder.H_R * ship.rudder.H_R / ship.rudder.A_R) /
                                             (ship.rudder.H_R * ship.rudder.H_R / ship.rudder.A_R + 2.25),
              1e-3);  // the CFD blade's own lift slope (Fujii), measured back
}

}  // namespace
}  // namespace kelvin::cfd
