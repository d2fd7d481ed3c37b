// Ship files: loading, every bad-input path, and Froude scaling.
#include "simulator/mmg/ship_parameters.h"

#include <gmock/gmock.h>

#include "data/schema/errors.h"
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "data/reference/friction_lines.h"
#include "simulator/maneuvers/runner.h"
#include "tests/simulator/simulator_test_utilities.h"

namespace kelvin::sim {
namespace {

using kelvin::testing::ScopedTempDir;
using ::testing::HasSubstr;

std::string Kvlcc2Text() {
  std::ifstream in(kelvin::testing::SourceDir() / "data/ships/kvlcc2.yaml");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Writes the KVLCC2 file with one line's value replaced.
std::filesystem::path Modified(const ScopedTempDir& dir, const std::string& pattern, const std::string& repl) {
  const std::string text = std::regex_replace(Kvlcc2Text(), std::regex(pattern), repl);
  const auto path = dir / "ship.yaml";
  std::ofstream(path) << text;
  return path;
}

TEST(ShipParametersTest, LoadsKvlcc2) {
  // Yasukawa & Yoshimura (2015), Tables 1-3.
  const ShipParameters s = testing::Kvlcc2();
  EXPECT_EQ(s.name, "KVLCC2");
  EXPECT_DOUBLE_EQ(s.principal.Lpp, 7.0);
  EXPECT_DOUBLE_EQ(s.hull.Y_v, -0.315);
  EXPECT_DOUBLE_EQ(s.hull.N_rrr, -0.013);
  EXPECT_DOUBLE_EQ(s.hull.J_z, 0.011);
  EXPECT_DOUBLE_EQ(s.propeller.x_P_prime, -0.48);
  EXPECT_DOUBLE_EQ(s.rudder.gamma_R_plus, 0.640);
  EXPECT_NEAR(s.limits.rudder_rate, 15.8 * M_PI / 180, 1e-15);
  EXPECT_NEAR(s.mass(), 1025.0 * 3.27, 1e-9);
  EXPECT_NEAR(s.I_zG(), s.mass() * 1.75 * 1.75, 1e-9);
}

struct BadShip {
  const char* pattern;
  const char* replacement;
  const char* message;
};

class BadShipTest : public ::testing::TestWithParam<BadShip> {};

TEST_P(BadShipTest, GivesOneClearError) {
  ScopedTempDir dir;
  const auto path = Modified(dir, GetParam().pattern, GetParam().replacement);
  try {
    LoadShip(path);
    FAIL() << "accepted " << GetParam().replacement;
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path.string()));
    EXPECT_THAT(e.what(), HasSubstr(GetParam().message));
  }
}

INSTANTIATE_TEST_SUITE_P(
    Files, BadShipTest,
    ::testing::Values(
        BadShip{"displacement: 3.27", "displacement: -3.27",
                "parameter 'principal.displacement' = -3.27: expected a positive finite value"},
        BadShip{"A_R: 0.0539", "A_R: 0", "parameter 'rudder.A_R' = 0: expected a positive finite value"},
        BadShip{"t_P: 0.220", "t_P: 1.5", "parameter 'propeller.t_P' = 1.5: expected a value in [0, 1)"},
        BadShip{"x_G: 0.25", "x_G: 4.0", "parameter 'principal.x_G' = 4: expected |x_G| < Lpp/2"},
        BadShip{"m_y_prime: 0.223", "m_y_prime: -0.2", "'hull.m_y_prime' = -0.2: expected a non-negative added mass"},
        BadShip{"  Y_vvr: 0.379", "  Y_vvrr: 0.379", "unknown key 'hull.Y_vvrr'"},
        BadShip{"  Y_v: -0.315\n", "", "missing required key 'hull.Y_v'"},
        BadShip{"Lpp: 7.00 ", "Lpp: seven ", "key 'principal.Lpp' = 'seven': expected a number"}));

// A hull for CFD only (the DTC: principal, geometry, the propeller of the
// body-force disk and an assumed rudder, no hull derivatives): loads, gives
// the CFD its open-water table, and the MMG model refuses it by name until
// derivatives come; without its rudder section the refusal names that too.
TEST(ShipParametersTest, ACfdOnlyShipLoadsAndTheManeuveringModelRefusesIt) {
  const auto file = kelvin::testing::SourceDir() / "data/ships/dtc.yaml";
  const ShipParameters dtc = LoadShip(file);
  EXPECT_FALSE(dtc.has_hull);
  EXPECT_TRUE(dtc.has_rudder);
  EXPECT_TRUE(dtc.propeller.mmg);
  EXPECT_DOUBLE_EQ(*dtc.propeller.hub_ratio, 0.176);
  EXPECT_DOUBLE_EQ(*dtc.propeller.z_P, 0.1598);
  const OpenWaterCurve curve = CfdOpenWater(dtc, file.string());
  EXPECT_EQ(curve.J.size(), 21u);
  EXPECT_DOUBLE_EQ(curve.KT(0.6), 0.2250);  // a node of the tutorial's table
  auto expect_refusal = [](const ShipParameters& ship, const std::string& path, bool names_rudder) {
    try {
      RequireManeuveringModel(ship, path);
      FAIL() << "the MMG model accepted a ship without hull derivatives";
    } catch (const ConfigError& e) {
      EXPECT_THAT(e.what(), HasSubstr("hull derivatives"));
      EXPECT_THAT(e.what(), HasSubstr(path));
      EXPECT_EQ(std::string(e.what()).find("a rudder section") != std::string::npos, names_rudder) << e.what();
    }
  };
  expect_refusal(dtc, file.string(), false);
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  const std::string t = text.str();
  const std::size_t rudder = t.find("\nrudder:"), next = t.find("\nactuators:");
  ASSERT_NE(rudder, std::string::npos);
  ASSERT_NE(next, std::string::npos);
  const ScopedTempDir dir;
  const auto bare = dir / "dtc_without_rudder.yaml";
  std::ofstream(bare) << t.substr(0, rudder) << t.substr(next);
  const ShipParameters no_rudder = LoadShip(bare);
  EXPECT_FALSE(no_rudder.has_rudder);
  expect_refusal(no_rudder, bare.string(), true);
  EXPECT_NO_THROW(RequireManeuveringModel(testing::Kvlcc2(), "kvlcc2.yaml"));
}

// Without a table the CFD tabulates the MMG quadratic K_T with the ship
// file's K_Q quadratic up to K_T = 0; without K_Q it says what is missing.
TEST(ShipParametersTest, TheCfdOpenWaterCurveComesFromTheQuadratics) {
  const auto file = kelvin::testing::SourceDir() / "data/ships/wigley.yaml";
  const ShipParameters wigley = LoadShip(file);
  const OpenWaterCurve curve = CfdOpenWater(wigley, file.string());
  const auto& pp = wigley.propeller;
  for (double J : {0.0, 0.2, 0.4, 0.6}) {
    EXPECT_NEAR(curve.KT(J), pp.k0 + pp.k1 * J + pp.k2 * J * J, 1e-6) << J;
    EXPECT_NEAR(curve.KQ(J), (*pp.kq)[0] + (*pp.kq)[1] * J + (*pp.kq)[2] * J * J, 1e-6) << J;
  }
  EXPECT_NEAR(curve.KT(curve.J_max()), 0.0, 1e-9);
  ScopedTempDir tmp;
  try {
    CfdOpenWater(LoadShip(Modified(tmp, "x_P_prime: -0.48", "x_P_prime: -0.48")), "kvlcc2.yaml");
    FAIL() << "a propeller without K_Q was accepted";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("K_Q_coefficients"));
  }
}

TEST(ShipParametersTest, FroudeScalingKeepsNondimensionalManeuvers) {
  // The same nondimensional model at full scale: distances scale with
  // lambda, times with sqrt(lambda); advance / L is unchanged.
  const ShipParameters model = testing::Kvlcc2();
  const ShipParameters full = ScaleShip(model, model.scale, false);
  EXPECT_NEAR(full.principal.Lpp, 320.0, 0.01);
  EXPECT_NEAR(full.approach_speed, 1.179 * std::sqrt(45.714), 1e-9);
  const auto spec = ManeuverSpec::Parse("turning:35:stbd");
  const auto a = RunManeuver(MmgModel<double>(model), spec, {});
  const auto b = RunManeuver(MmgModel<double>(full), spec, {});
  EXPECT_NEAR(a.turning->advance / a.Lpp, b.turning->advance / b.Lpp, 1e-6);
  EXPECT_NEAR(a.turning->tactical_diameter / a.Lpp, b.turning->tactical_diameter / b.Lpp, 1e-6);
  EXPECT_NEAR(a.turning->time_to_90 * std::sqrt(model.scale), b.turning->time_to_90, 1e-4 * b.turning->time_to_90);
}

TEST(ShipParametersTest, RpsMaxIsAbsentUnlessGivenAndScalesWithFroude) {
  const ScopedTempDir dir;
  const ShipParameters plain = testing::Kvlcc2();
  EXPECT_FALSE(plain.limits.rps_max.has_value());
  EXPECT_FALSE(ScaleShip(plain, 4.0, false).limits.rps_max.has_value());
  const ShipParameters limited =
      LoadShip(Modified(dir, "  rudder_rate_deg_s: 15.8", "  rudder_rate_deg_s: 15.8\n  rps_max: 20.0"));
  ASSERT_TRUE(limited.limits.rps_max.has_value());
  EXPECT_EQ(*limited.limits.rps_max, 20.0);
  EXPECT_DOUBLE_EQ(*ScaleShip(limited, 4.0, false).limits.rps_max, 10.0);  // n / sqrt(lambda)
}

TEST(ShipParametersTest, FrictionCorrectionNeedsWettedAreaAndLowersR0) {
  ShipParameters model = testing::Kvlcc2();
  try {
    ScaleShip(model, model.scale, true);
    FAIL();
  } catch (const ModelError& e) {
    EXPECT_THAT(e.what(), HasSubstr("needs principal.wetted_area"));
  }
  model.principal.wetted_area = 9.0;  // m^2, a plausible L7 wetted area
  const ShipParameters full = ScaleShip(model, model.scale, true);
  // C_F falls with Reynolds number, so the full-scale resistance coefficient is lower.
  EXPECT_LT(full.hull.R0, model.hull.R0);
  const double Re_m = 1.179 * 7.0 / model.principal.nu;
  const double Re_s = Re_m * std::pow(model.scale, 1.5);
  const double expected =
      (data::Ittc57FrictionCoefficient(Re_s) - data::Ittc57FrictionCoefficient(Re_m)) * model.principal.wetted_area /
      (7.0 * 0.46);
  EXPECT_NEAR(full.hull.R0 - model.hull.R0, expected, 1e-12);
}

}  // namespace
}  // namespace kelvin::sim
