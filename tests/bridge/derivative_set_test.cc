// Derivative sets and their check against CFD: loading, the assessment the
// bridge prints, the refusal with --require-checked, and the bad-file paths.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <fstream>

#include "bridge/derivative_set.h"
#include "data/schema/errors.h"
#include "identification/derivative_set_io.h"
#include "simulator/mmg/surrogate.h"
#include "tests/test_utilities/test_utilities.h"
#include "tests/simulator/simulator_test_utilities.h"

namespace kelvin::bridge {
namespace {

using ::testing::HasSubstr;

using sim::testing::Kvlcc2;
using sim::DerivativeSet;
using sim::LoadDerivativeSet;

// A derivative file with the KVLCC2 hull, N_r replaced, and `check` text.
std::filesystem::path WriteSet(const testing::ScopedTempDir& dir, const std::string& name, const std::string& check,
                               const std::string& extra = "", const std::string& n_r = "-0.0512") {
  const sim::ShipParameters ship = Kvlcc2();
  const auto path = dir / name;
  std::ofstream f(path);
  // The layout of `kelvin identify` (identification/derivative_set_io.cc).
  f << "derivative_set:\n  name: test set\n  ship: KVLCC2\n  source: campaign.h5\nhull:\n";
  for (int i = 0; i < sim::HullCoefficients<double>::kCount; ++i) {
    const std::string key(sim::HullCoefficients<double>::kNames[static_cast<std::size_t>(i)]);
    f << "  " << key << ": " << (key == "N_r" ? n_r : fmt::format("{}", ship.hull[i])) << "\n";
  }
  f << "standard_errors:\n  N_r: 0.0004\nfit:\n  runs: 7\n  converged: true\n  warnings: []\n";
  f << extra << check;
  return path;
}

TEST(DerivativeSet, LoadsTheHullAndThePassingCheck) {
  const testing::ScopedTempDir dir;
  const auto path = WriteSet(dir, "d.yaml",
                             "check:\n  passed: true\n  reference: free-running CFD zig-zag 20/20\n  date: 2026-11-20\n");
  const DerivativeSet set = LoadDerivativeSet(path);
  const sim::ShipParameters ship = Kvlcc2();
  EXPECT_EQ(set.name, "test set");
  EXPECT_EQ(set.hull.N_r, -0.0512);
  EXPECT_EQ(set.hull.Y_v, ship.hull.Y_v);
  EXPECT_EQ(set.hull.J_z, ship.hull.J_z);
  ASSERT_TRUE(set.check.has_value());
  EXPECT_TRUE(set.check->passed);
  const DerivativeAssessment a = AssessDerivatives(ship, set, /*require_checked=*/true);
  EXPECT_EQ(a.status, DerivativeStatus::kChecked);
  EXPECT_EQ(a.message, "derivative set " + path.string() + " passed its check against free-running CFD zig-zag 20/20");
}

// A set's interaction section (identified from CFD runs with propeller and
// rudder) replaces the ship file's values in the surrogate; a key outside
// the MMG interaction coefficients, or a non-number, is one error naming it.
TEST(DerivativeSet, InteractionSectionReplacesTheShipFilesCoefficients) {
  const testing::ScopedTempDir dir;
  const auto path = WriteSet(dir, "i.yaml", "", "interaction: {epsilon: 0.99, kappa: 0.87, f_alpha: 2.96}\n");
  const DerivativeSet set = LoadDerivativeSet(path);
  ASSERT_EQ(set.interaction.size(), 3u);
  const sim::ShipParameters file = Kvlcc2();
  const sim::ShipParameters ship = sim::SurrogateShip(file, "kvlcc2.yaml", &set);
  EXPECT_EQ(ship.rudder.epsilon, 0.99);
  EXPECT_EQ(ship.rudder.kappa, 0.87);
  EXPECT_EQ(ship.rudder.f_alpha, 2.96);
  EXPECT_EQ(ship.rudder.gamma_R_plus, file.rudder.gamma_R_plus);  // not in the set
  EXPECT_EQ(ship.propeller.t_P, file.propeller.t_P);
  for (const auto& [section, needle] :
       {std::pair{"interaction: {gamma_R: 0.3}\n", "gamma_R"}, {"interaction: {t_R: abc}\n", "t_R"},
        {"interaction: [1, 2]\n", "interaction"}}) {
    const auto bad = WriteSet(dir, "bad.yaml", "", section);
    try {
      LoadDerivativeSet(bad);
      ADD_FAILURE() << "no error for " << section;
    } catch (const ConfigError& e) {
      EXPECT_THAT(e.what(), HasSubstr(needle));
      EXPECT_THAT(e.what(), HasSubstr("bad.yaml"));
    }
  }
}

// The contract with identification: the YAML that `kelvin identify` writes
// loads as a derivative set with the same hull coefficients, unchecked until
// a check section is added.
TEST(DerivativeSet, ReadsTheFileKelvinIdentifyWrites) {
  const sim::ShipParameters ship = Kvlcc2();
  data::CaptiveCampaign campaign;
  campaign.ship.name = "KVLCC2";
  ident::JointFitResult fit;
  fit.coefficients = ship.hull;
  fit.coefficients.N_r = -0.0512345678901234;
  for (int i = 0; i < sim::HullCoefficients<double>::kCount; ++i) {
    fit.status[static_cast<std::size_t>(i)] = ident::CoefficientStatus::kIdentified;
    fit.std_error[static_cast<std::size_t>(i)] = 1e-3;
  }
  fit.converged = true;
  ident::IdentificationReport report;
  report.source = "virtual_campaign.h5";
  report.campaign = &campaign;
  report.fit = &fit;
  const testing::ScopedTempDir dir;
  const auto path = dir / "derivatives.yaml";
  ident::WriteDerivativeYaml(report, path);

  const DerivativeSet set = LoadDerivativeSet(path);
  EXPECT_EQ(set.name, "KVLCC2 hull derivatives identified by kelvin identify");
  for (int i = 0; i < sim::HullCoefficients<double>::kCount; ++i) {
    EXPECT_EQ(set.hull[i], fit.coefficients[i]) << sim::HullCoefficients<double>::kNames[static_cast<std::size_t>(i)];
  }
  EXPECT_FALSE(set.check.has_value());
  EXPECT_EQ(AssessDerivatives(ship, set, false).status, DerivativeStatus::kUnchecked);

  // The check stage appends its section.
  std::ofstream(path, std::ios::app) << "check:\n  passed: true\n  reference: CFD zig-zag 10/10\n";
  const DerivativeSet checked = LoadDerivativeSet(path);
  ASSERT_TRUE(checked.check.has_value());
  EXPECT_EQ(AssessDerivatives(ship, checked, true).status, DerivativeStatus::kChecked);
}

TEST(DerivativeSet, ShipFileSetIsAReferenceNotCfdChecked) {
  const sim::ShipParameters ship = Kvlcc2();
  const std::string expected =
      "streaming the hull derivatives of the ship file ('KVLCC2', Yasukawa & Yoshimura (2015), J. Mar. Sci. Technol. "
      "20:37-52): a published reference set, not checked against this project's CFD";
  const DerivativeAssessment a = AssessDerivatives(ship, std::nullopt, false);
  EXPECT_EQ(a.status, DerivativeStatus::kShipReference);
  EXPECT_EQ(a.message, expected);
  try {
    AssessDerivatives(ship, std::nullopt, true);
    FAIL() << "expected a refusal";
  } catch (const ArgumentError& e) {
    EXPECT_EQ(std::string(e.what()), "--require-checked: refusing to stream: " + expected);
  }
}

TEST(DerivativeSet, WithoutCheckWarnsAndRefusesWhenRequired) {
  const testing::ScopedTempDir dir;
  const auto path = WriteSet(dir, "d.yaml", "");
  const DerivativeSet set = LoadDerivativeSet(path);
  EXPECT_FALSE(set.check.has_value());
  const DerivativeAssessment a = AssessDerivatives(Kvlcc2(), set, false);
  EXPECT_EQ(a.status, DerivativeStatus::kUnchecked);
  EXPECT_EQ(a.message, "derivative set " + path.string() + " has no 'check' section: it was never checked against CFD");
  EXPECT_THROW(AssessDerivatives(Kvlcc2(), set, true), ArgumentError);
}

TEST(DerivativeSet, FailedCheckWarnsAndRefusesWhenRequired) {
  const testing::ScopedTempDir dir;
  const auto path = WriteSet(dir, "d.yaml",
                             "check:\n  passed: false\n  reference: CFD turning circle\n  summary: advance off by 7%\n");
  const DerivativeSet set = LoadDerivativeSet(path);
  const DerivativeAssessment a = AssessDerivatives(Kvlcc2(), set, false);
  EXPECT_EQ(a.status, DerivativeStatus::kCheckFailed);
  EXPECT_EQ(a.message, "derivative set " + path.string() +
                           " FAILED its check against CFD (CFD turning circle: advance off by 7%)");
  try {
    AssessDerivatives(Kvlcc2(), set, true);
    FAIL() << "expected a refusal";
  } catch (const ArgumentError& e) {
    EXPECT_EQ(std::string(e.what()), "--require-checked: refusing to stream: " + a.message);
  }
}

std::string LoadError(const std::filesystem::path& path) {
  try {
    LoadDerivativeSet(path);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

TEST(DerivativeSet, UnknownTopLevelKeyIsAnError) {
  const testing::ScopedTempDir dir;
  const auto path = WriteSet(dir, "d.yaml", "", "checks:\n  passed: true\n");
  const std::string m = LoadError(path);
  EXPECT_THAT(m, HasSubstr(path.string()));
  EXPECT_THAT(m, HasSubstr("unknown key 'checks'"));
  EXPECT_THAT(m, HasSubstr("check"));
}

TEST(DerivativeSet, UnknownCheckKeyIsAnError) {
  const testing::ScopedTempDir dir;
  const auto path = WriteSet(dir, "d.yaml", "check:\n  pased: true\n");
  EXPECT_THAT(LoadError(path), HasSubstr("unknown key 'check.pased'"));
}

TEST(DerivativeSet, MissingDerivativeIsAnError) {
  const testing::ScopedTempDir dir;
  const auto path = dir / "d.yaml";
  std::ofstream(path) << "hull:\n  R0_prime: 0.022\n";
  EXPECT_THAT(LoadError(path), HasSubstr("X_vv"));
}

TEST(DerivativeSet, NonNumericDerivativeIsAnError) {
  const testing::ScopedTempDir dir;
  const auto path = WriteSet(dir, "d.yaml", "", "", "abc");
  const std::string m = LoadError(path);
  EXPECT_THAT(m, HasSubstr("hull.N_r"));
  EXPECT_THAT(m, HasSubstr("abc"));
}

TEST(DerivativeSet, CheckPassedMustBeABoolean) {
  const testing::ScopedTempDir dir;
  const auto path = WriteSet(dir, "d.yaml", "check:\n  passed: maybe\n");
  const std::string m = LoadError(path);
  EXPECT_THAT(m, HasSubstr("check.passed"));
  EXPECT_THAT(m, HasSubstr("maybe"));
}

}  // namespace
}  // namespace kelvin::bridge
