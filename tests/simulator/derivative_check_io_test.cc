// Writing the check section of a derivative set: the rest of the file is
// kept line for line, an old section is replaced, the file round-trips
// through LoadDerivativeSet, and a layout it cannot edit is one clear error.
#include "simulator/mmg/derivative_check_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "data/schema/errors.h"
#include "identification/derivative_set_io.h"
#include "tests/simulator/simulator_test_utilities.h"
#include "tests/simulator/surrogate_check_fixtures.h"

namespace kelvin::sim {
namespace {

using kelvin::testing::ReadText;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

DerivativeCheck Failed() {
  DerivativeCheck c;
  c.passed = false;
  c.reference = "runs/cfd turning.h5, runs/zigzag.h5";
  c.date = "2026-11-23T10:00:00Z";
  c.summary =
      "turning:35:stbd against runs/cfd turning.h5: FAIL; worst tactical_diameter: 21.8 vs 23.6 m (-1.77 m, -7.49%; "
      "tolerance 5%) # not a comment\n"
      "zigzag:20/20:stbd against runs/zigzag.h5: pass; worst first_overshoot: 'quoted' \"too\"";
  return c;
}

int Count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

void ExpectSameCheck(const DerivativeCheck& a, const DerivativeCheck& b) {
  EXPECT_EQ(a.passed, b.passed);
  EXPECT_EQ(a.reference, b.reference);
  EXPECT_EQ(a.date, b.date);
  EXPECT_EQ(a.summary, b.summary);
}

TEST(DerivativeCheckIo, FormatsTheSectionWithOneSummaryLinePerManeuver) {
  DerivativeCheck c;
  c.passed = true;
  c.reference = "a.h5";
  c.date = "2026-11-23T10:00:00Z";
  c.summary = "turning: pass\nzigzag: pass";
  EXPECT_EQ(FormatDerivativeCheck(c),
            "check:\n  passed: true\n  reference: a.h5\n  date: 2026-11-23T10:00:00Z\n  summary: |-\n"
            "    turning: pass\n    zigzag: pass\n");
}

TEST(DerivativeCheckIo, AppendsTheSectionAndKeepsEveryOtherLine) {
  const kelvin::testing::ScopedTempDir dir;
  const auto path = testing::WriteSetFromShip(dir / "d.yaml", "kvlcc2");
  const std::string before = ReadText(path);
  const DerivativeSet set_before = LoadDerivativeSet(path);
  WriteDerivativeCheck(path, Failed());
  const std::string after = ReadText(path);
  EXPECT_THAT(after, StartsWith(before));  // comments included
  EXPECT_EQ(after.substr(before.size()), FormatDerivativeCheck(Failed()));
  // Round trip: the same set, with the check.
  const DerivativeSet set = LoadDerivativeSet(path);
  EXPECT_EQ(set.name, set_before.name);
  for (int i = 0; i < HullCoefficients<double>::kCount; ++i) EXPECT_EQ(set.hull[i], set_before.hull[i]);
  ASSERT_TRUE(set.check.has_value());
  ExpectSameCheck(*set.check, Failed());
  // Nothing left beside the file.
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1);
}

TEST(DerivativeCheckIo, ReplacesAnExistingSectionInPlace) {
  const kelvin::testing::ScopedTempDir dir;
  // An old section (a literal block with blank lines) between the standard
  // errors and the fit, and a comment after it.
  const std::string text = ReadText(testing::WriteSetFromShip(dir / "src.yaml", "kvlcc2"));
  const std::size_t fit = text.find("fit:\n");
  std::ofstream(dir / "d.yaml") << text.substr(0, fit)
                                << "check:\n  passed: true\n  reference: old.h5\n  summary: |-\n    old line 1\n\n"
                                   "    old line 3\n\n# the fit comes after the check here\n"
                                << text.substr(fit);
  const std::string before = ReadText(dir / "d.yaml");
  WriteDerivativeCheck(dir / "d.yaml", Failed());
  const std::string after = ReadText(dir / "d.yaml");
  EXPECT_EQ(Count(after, "\ncheck:"), 1);
  EXPECT_THAT(after, Not(HasSubstr("old")));
  const std::size_t at = before.find("check:");
  EXPECT_EQ(after.substr(0, at), before.substr(0, at));
  EXPECT_THAT(after, HasSubstr(FormatDerivativeCheck(Failed()) + "\n# the fit comes after the check here\n" +
                               text.substr(fit)));
  ExpectSameCheck(*LoadDerivativeSet(dir / "d.yaml").check, Failed());
  // Again: still one section, now the new one.
  DerivativeCheck passed = Failed();
  passed.passed = true;
  WriteDerivativeCheck(dir / "d.yaml", passed);
  EXPECT_EQ(Count(ReadText(dir / "d.yaml"), "\ncheck:"), 1);
  ExpectSameCheck(*LoadDerivativeSet(dir / "d.yaml").check, passed);
}

TEST(DerivativeCheckIo, ReplacesAFlowStyleSection) {
  const kelvin::testing::ScopedTempDir dir;
  const auto path =
      testing::WriteSetFromShip(dir / "d.yaml", "wigley", 1.0, "", "check: {passed: true, reference: x}\n");
  WriteDerivativeCheck(path, Failed());
  EXPECT_THAT(ReadText(path), Not(HasSubstr("{passed: true")));
  ExpectSameCheck(*LoadDerivativeSet(path).check, Failed());
}

// The contract with identification: the file kelvin identify writes (with
// its comments, flow sequences and nested fit sections) takes a check and
// reads back as the same set.
TEST(DerivativeCheckIo, TheFileKelvinIdentifyWritesTakesACheck) {
  const ShipParameters ship = testing::Kvlcc2();
  data::CaptiveCampaign campaign;
  campaign.ship.name = "KVLCC2";
  ident::JointFitResult fit;
  fit.coefficients = ship.hull;
  for (int i = 0; i < HullCoefficients<double>::kCount; ++i) {
    fit.status[static_cast<std::size_t>(i)] = ident::CoefficientStatus::kIdentified;
    fit.std_error[static_cast<std::size_t>(i)] = 1e-3;
  }
  fit.converged = true;
  fit.warnings = {"a warning: with a colon"};
  ident::IdentificationReport report;
  report.source = "virtual_campaign.h5";
  report.campaign = &campaign;
  report.fit = &fit;
  const kelvin::testing::ScopedTempDir dir;
  const auto path = dir / "derivatives.yaml";
  ident::WriteDerivativeYaml(report, path);
  const std::string before = ReadText(path);
  WriteDerivativeCheck(path, Failed());
  EXPECT_THAT(ReadText(path), StartsWith(before));
  const DerivativeSet set = LoadDerivativeSet(path);
  for (int i = 0; i < HullCoefficients<double>::kCount; ++i) EXPECT_EQ(set.hull[i], fit.coefficients[i]);
  ExpectSameCheck(*set.check, Failed());
}

TEST(DerivativeCheckIo, AFlowStyleFileIsOneClearError) {
  const kelvin::testing::ScopedTempDir dir;
  const auto src = testing::WriteSetFromShip(dir / "src.yaml", "kvlcc2");
  const DerivativeSet set = LoadDerivativeSet(src);
  std::string flow = "{hull: {";
  for (int i = 0; i < HullCoefficients<double>::kCount; ++i) {
    flow += fmt::format("{}{}: {}", i ? ", " : "", HullCoefficients<double>::kNames[static_cast<std::size_t>(i)],
                        set.hull[i]);
  }
  flow += "}}\n";
  std::ofstream(dir / "flow.yaml") << flow;
  try {
    WriteDerivativeCheck(dir / "flow.yaml", Failed());
    FAIL() << "expected an error";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr((dir / "flow.yaml").string() + ": cannot add a check section to this file's "
                                                                   "layout"));
    EXPECT_THAT(e.what(), HasSubstr("expected a derivative set written as a block map"));
  }
  EXPECT_EQ(ReadText(dir / "flow.yaml"), flow);
}

TEST(DerivativeCheckIo, MissingFileIsAnError) {
  try {
    WriteDerivativeCheck("/nonexistent/d.yaml", Failed());
    FAIL() << "expected an error";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent/d.yaml: cannot read the derivative set"));
  }
}

TEST(DerivativeCheckIo, AFileThatIsNoDerivativeSetIsAnError) {
  const kelvin::testing::ScopedTempDir dir;
  std::ofstream(dir / "ship.yaml") << "ship: {name: X}\n";
  try {
    WriteDerivativeCheck(dir / "ship.yaml", Failed());
    FAIL() << "expected an error";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr((dir / "ship.yaml").string()));
    EXPECT_THAT(e.what(), HasSubstr("unknown key 'ship'"));
  }
}

}  // namespace
}  // namespace kelvin::sim
