// The bridge and kelvin check: a set whose check (written by `kelvin check`)
// passed streams with --require-checked; one whose check failed is refused
// with the check's summary in the message.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "bridge/derivative_set.h"
#include "data/schema/errors.h"
#include "tests/simulator/simulator_test_utilities.h"
#include "tests/simulator/surrogate_check_fixtures.h"

namespace kelvin::bridge {
namespace {

namespace fs = std::filesystem;
using sim::testing::ShipFile;
using sim::testing::WriteSetFromShip;
using ::testing::HasSubstr;
using ::testing::Not;

std::string Kelvin() { return (testing::ToolsDir() / "kelvin").string(); }

// The last line of the output (the error message).
std::string LastLine(const std::string& output) {
  std::string s = output;
  while (!s.empty() && s.back() == '\n') s.pop_back();
  const std::size_t nl = s.rfind('\n');
  return nl == std::string::npos ? s : s.substr(nl + 1);
}

// kelvin simulate with `reference_set`, then kelvin check of `set` against
// that run; returns the exit code of the check.
int SimulateAndCheck(const testing::ScopedTempDir& dir, const fs::path& set, const fs::path& reference_set,
                     fs::path* reference) {
  const std::string ship = ShipFile("kvlcc2").string();
  const auto sim = testing::RunCommand(Kelvin() + " simulate " + ship + " --derivatives " + reference_set.string() +
                                       " -m turning:35:stbd -o " + (dir / "ref").string());
  EXPECT_EQ(sim.exit_code, 0) << sim.output;
  *reference = dir / "ref/KVLCC2_turning_35_stbd.h5";
  const auto check = testing::RunCommand(Kelvin() + " check " + set.string() + " --ship " + ship + " --against " +
                                         reference->string() + " -o " + (dir / "report").string());
  return check.exit_code;
}

testing::CommandResult BridgeRequiringChecked(const fs::path& set) {
  return testing::RunCommand(Kelvin() + " bridge " + ShipFile("kvlcc2").string() + " --derivatives " + set.string() +
                             " --require-checked --lcm-url memq:// --duration 1 --speedup 100");
}

TEST(BridgeCheckedSet, ASetThatPassedKelvinCheckStreams) {
  const testing::ScopedTempDir dir;
  const auto set = WriteSetFromShip(dir / "set.yaml", "kvlcc2");
  fs::path reference;
  ASSERT_EQ(SimulateAndCheck(dir, set, set, &reference), 0);
  const sim::DerivativeSet loaded = sim::LoadDerivativeSet(set);
  const DerivativeAssessment a = AssessDerivatives(sim::testing::Kvlcc2(), loaded, /*require_checked=*/true);
  EXPECT_EQ(a.status, DerivativeStatus::kChecked);
  EXPECT_EQ(a.message, "derivative set " + set.string() + " passed its check against " + reference.string());

  const auto r = BridgeRequiringChecked(set);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("passed its check against " + reference.string()));
  EXPECT_THAT(r.output, Not(HasSubstr("UNCHECKED")));
  EXPECT_THAT(r.output, HasSubstr("bridge completed: t = 1.000 s"));
}

TEST(BridgeCheckedSet, ASetThatFailedKelvinCheckIsRefusedWithItsSummary) {
  const testing::ScopedTempDir dir;
  const auto set = WriteSetFromShip(dir / "set.yaml", "kvlcc2");
  const auto perturbed = WriteSetFromShip(dir / "perturbed.yaml", "kvlcc2", 1.2);
  fs::path reference;
  ASSERT_EQ(SimulateAndCheck(dir, set, perturbed, &reference), 3);
  const sim::DerivativeSet loaded = sim::LoadDerivativeSet(set);
  ASSERT_TRUE(loaded.check.has_value());
  ASSERT_FALSE(loaded.check->passed);
  const std::string& summary = loaded.check->summary;
  EXPECT_THAT(summary, HasSubstr("turning:35:stbd against " + reference.string() + ": FAIL; worst tactical_diameter"));

  const std::string expected = "--require-checked: refusing to stream: derivative set " + set.string() +
                               " FAILED its check against CFD (" + reference.string() + ": " + summary + ")";
  try {
    AssessDerivatives(sim::testing::Kvlcc2(), loaded, /*require_checked=*/true);
    FAIL() << "expected a refusal";
  } catch (const ArgumentError& e) {
    EXPECT_EQ(std::string(e.what()), expected);
  }
  const auto r = BridgeRequiringChecked(set);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(LastLine(r.output), "kelvin: error: " + expected);
}

// A derivative set of another ship is refused by kelvin simulate and kelvin
// bridge as by kelvin check (sim::SurrogateShip): one line naming the set's
// key, its value and the ship file's ship.
TEST(BridgeCheckedSet, ASetOfAnotherShipIsRefusedBySimulateAndBridge) {
  const testing::ScopedTempDir dir;
  const auto set = WriteSetFromShip(dir / "kvlcc2_set.yaml", "kvlcc2");
  const std::string wigley = ShipFile("wigley").string();
  const std::string expected = "kelvin: error: " + set.string() +
                               ":4: key 'derivative_set.ship' = 'KVLCC2': expected a derivative set of ship "
                               "'Wigley', the ship of the ship file " + wigley;
  const auto simulate = testing::RunCommand(Kelvin() + " simulate " + wigley + " --derivatives " + set.string() +
                                            " -m turning:35:stbd -o " + (dir / "sim").string());
  EXPECT_EQ(simulate.exit_code, 1) << simulate.output;
  EXPECT_EQ(LastLine(simulate.output), expected);
  EXPECT_FALSE(fs::exists(dir / "sim/Wigley_turning_35_stbd.h5"));
  const auto bridge = testing::RunCommand(Kelvin() + " bridge " + wigley + " --derivatives " + set.string() +
                                          " --lcm-url memq:// --duration 1 --speedup 100");
  EXPECT_EQ(bridge.exit_code, 1) << bridge.output;
  EXPECT_EQ(LastLine(bridge.output), expected);
}

}  // namespace
}  // namespace kelvin::bridge
