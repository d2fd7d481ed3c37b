// kelvin identify end to end: campaign HDF5 or CSV runs in, derivative YAML
// (loadable into a ship file) and HDF5 with covariance out; argument errors
// exit 2, file errors exit 1, each with one clear message. Truth: KVLCC2 L7,
// Yasukawa & Yoshimura (2015), J. Mar. Sci. Technol. 20:37-52.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "data/schema/captive_io.h"
#include "data/schema/h5_file.h"
#include "identification/derivative_set_io.h"
#include "identification/virtual_captive.h"
#include "simulator/mmg/derivative_set.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::ident {
namespace {

std::string Kelvin() { return (testing::ToolsDir() / "kelvin").string(); }
std::filesystem::path ShipFile() { return testing::SourceDir() / "data/ships/kvlcc2.yaml"; }

data::CaptiveCampaign Campaign() {
  const sim::ShipParameters ship = sim::LoadShip(ShipFile());
  return GenerateCampaign(sim::MmgModel<double>(ship),
                          data::StandardDesign(ship.approach_speed, true), {});
}

TEST(IdentifyCliTest, CampaignToDerivativeSetLoadableAsShip) {
  testing::ScopedTempDir dir;
  data::WriteCampaignH5(Campaign(), dir / "campaign.h5");
  const auto r = testing::RunCommand(Kelvin() + " identify " + (dir / "campaign.h5").string() +
                                     " -o " + (dir / "kvlcc2_derivatives.yaml").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("Y_v"), std::string::npos);
  // The hull: section replaces a ship file's hull: section as is.
  const YAML::Node out = YAML::LoadFile((dir / "kvlcc2_derivatives.yaml").string());
  YAML::Node ship_yaml = YAML::LoadFile(ShipFile().string());
  ship_yaml["hull"] = out["hull"];
  {
    std::ofstream f(dir / "identified_ship.yaml");
    f << ship_yaml;
  }
  const sim::ShipParameters truth = sim::LoadShip(ShipFile());
  const sim::ShipParameters identified = sim::LoadShip(dir / "identified_ship.yaml");
  for (int i = 0; i < sim::HullCoefficients<double>::kCount; ++i) {
    EXPECT_NEAR(identified.hull[i], truth.hull[i], 0.005 * std::abs(truth.hull[i]))
        << sim::HullCoefficients<double>::kNames[i];
    EXPECT_TRUE(
        out["standard_errors"][std::string(sim::HullCoefficients<double>::kNames[i])].IsDefined());
  }
  // The bridge streams it as a derivative set (unchecked against CFD so far).
  const sim::DerivativeSet set = sim::LoadDerivativeSet(dir / "kvlcc2_derivatives.yaml");
  for (int i = 0; i < sim::HullCoefficients<double>::kCount; ++i) {
    EXPECT_EQ(set.hull[i], identified.hull[i]) << sim::HullCoefficients<double>::kNames[i];
  }
  EXPECT_FALSE(set.check.has_value());
  // Its range: what the campaign's runs reached, to the 6 digits written.
  ASSERT_TRUE(set.range.has_value());
  const sim::MotionRange range = CampaignRange(Campaign());
  EXPECT_NEAR(set.range->drift, range.drift, 1e-5 * range.drift);
  EXPECT_NEAR(set.range->r_prime, range.r_prime, 1e-5 * range.r_prime);
  // HDF5 beside it: the full covariance and per-run measured/fitted forces.
  const data::H5Reader h5(dir / "kvlcc2_derivatives.h5");
  const data::Series cov = h5.Read("/covariance");
  EXPECT_EQ(cov.values.size(), 400u);
  EXPECT_TRUE(h5.Has("/runs/sway_v0.100/fitted_Y"));
  EXPECT_TRUE(h5.Has("/runs/sway_v0.100/measured_Y"));
  // The plot script draws measured against fitted forces, one PNG per run.
  if (!testing::HaveProgram("/usr/bin/python3")) GTEST_SKIP() << "no /usr/bin/python3";
  const auto plot = testing::RunCommand(
      "/usr/bin/python3 " + (testing::SourceDir() / "tools/plot_identification.py").string() + " " +
      (dir / "kvlcc2_derivatives.h5").string() + " -o " + (dir / "plots").string());
  ASSERT_EQ(plot.exit_code, 0) << plot.output;
  for (const char* run :
       {"drift_+20.0deg", "sway_v0.200", "yaw_r0.600", "yaw_drift_+12.0deg_r0.400"}) {
    EXPECT_GT(std::filesystem::file_size(dir / "plots" / (std::string(run) + ".png")), 10000u)
        << run;
  }
}

// The range a campaign spans: a static drift at 12 deg and a circular run at
// r' 0.6 with 4 deg drift give drift 12 deg and r' 0.6; the speed ramp of
// the drift run (before t_ramp) does not count.
TEST(IdentifyCliTest, CampaignRangeIsTheLargestDriftAndYawRate) {
  data::CaptiveCampaign c;
  c.ship.Lpp = 7.0;
  data::CaptiveRun drift;
  drift.motion.kind = data::MotionKind::kStaticDrift;
  drift.motion.U = 1.2;
  drift.motion.beta = 12.0 * M_PI / 180.0;
  drift.motion.t_ramp = 2.0;
  drift.time = {0.5, 1.0, 2.0, 3.0};
  data::CaptiveRun circle;
  circle.motion.kind = data::MotionKind::kCircularMotion;
  circle.motion.U = 1.2;
  circle.motion.beta = -4.0 * M_PI / 180.0;
  circle.motion.r_prime = -0.6;
  circle.time = {0.0, 1.0};
  c.runs = {drift, circle};
  const sim::MotionRange r = CampaignRange(c);
  EXPECT_NEAR(r.drift, 12.0 * M_PI / 180.0, 1e-12);
  EXPECT_NEAR(r.r_prime, 0.6, 1e-12);
}

TEST(IdentifyCliTest, CsvRunsWithShipFile) {
  testing::ScopedTempDir dir;
  std::string files;
  for (const data::CaptiveRun& run : Campaign().runs) {
    data::WriteRunCsv(run, dir / (run.name + ".csv"));
    files.append(" ").append((dir / (run.name + ".csv")).string());
  }
  const auto r = testing::RunCommand(Kelvin() + " identify" + files + " --ship " +
                                     ShipFile().string() + " -o " + (dir / "d.yaml").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const YAML::Node out = YAML::LoadFile((dir / "d.yaml").string());
  EXPECT_NEAR(out["hull"]["N_r"].as<double>(), -0.049, 0.005 * 0.049);
  // Without the ship file the CSV runs lack the ship data: argument error.
  const auto bad =
      testing::RunCommand(Kelvin() + " identify" + files + " -o " + (dir / "e.yaml").string());
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("--ship is required with .csv runs"), std::string::npos) << bad.output;
}

TEST(IdentifyCliTest, BadArgumentsExitTwo) {
  testing::ScopedTempDir dir;
  data::WriteCampaignH5(Campaign(), dir / "c.h5");
  const std::string base =
      Kelvin() + " identify " + (dir / "c.h5").string() + " -o " + (dir / "d.yaml").string();
  auto r = testing::RunCommand(base + " --loss square");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--loss 'square': expected 'none', 'huber' or 'cauchy'"),
            std::string::npos)
      << r.output;
  r = testing::RunCommand(base + " --prior Y_vv=1:0.1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("unknown coefficient 'Y_vv'"), std::string::npos) << r.output;
  r = testing::RunCommand(base + " --prior Y_vvr=0.3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--prior 'Y_vvr=0.3': expected NAME=MEAN:SIGMA"), std::string::npos)
      << r.output;
  r = testing::RunCommand(base + " --bound Y_v=-0.2:-0.4");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("'bounds.Y_v': [-0.2, -0.4]: expected lower < upper"), std::string::npos)
      << r.output;
  r = testing::RunCommand(base + " --bound Y_v=-0.2");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--bound 'Y_v=-0.2': expected NAME=LOWER:UPPER"), std::string::npos)
      << r.output;
  r = testing::RunCommand(base + " --fix m_x_prime=abc");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--fix m_x_prime: 'abc' is not a number"), std::string::npos) << r.output;
  r = testing::RunCommand(Kelvin() + " identify " + (dir / "c.txt").string() + " -o " +
                          (dir / "d.yaml").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("expected a campaign .h5 file or .csv runs"), std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "d.yaml"));
}

TEST(IdentifyCliTest, BadFilesExitOneAndWriteNothing) {
  testing::ScopedTempDir dir;
  auto r = testing::RunCommand(Kelvin() + " identify " + (dir / "none.h5").string() + " -o " +
                               (dir / "d.yaml").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("none.h5: no such file"), std::string::npos) << r.output;
  data::CaptiveCampaign c = Campaign();
  c.runs[7].force[1][300] = std::numeric_limits<double>::quiet_NaN();
  data::WriteCampaignH5(c, dir / "nan.h5");
  r = testing::RunCommand(Kelvin() + " identify " + (dir / "nan.h5").string() + " -o " +
                          (dir / "d.yaml").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("run '" + c.runs[7].name + "': channel 'Y': sample 300"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "d.yaml"));
  EXPECT_FALSE(std::filesystem::exists(dir / "d.h5"));
}

}  // namespace
}  // namespace kelvin::ident
