// `kelvin check` from the command line: a set checked against the runs
// `kelvin simulate --derivatives` made with it passes (exit 0) and records
// it; against runs of a perturbed hull it prints its table, records the
// failure and exits 3; a bad input exits 1 or 2 with one message and leaves
// the set untouched; the plot script overlays reference and surrogate.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "simulator/mmg/derivative_set.h"
#include "tests/simulator/surrogate_check_fixtures.h"

namespace kelvin::cli {
namespace {

namespace fs = std::filesystem;
using kelvin::testing::ReadText;
using kelvin::testing::RunCommand;
using kelvin::testing::ScopedTempDir;
using sim::testing::ShipFile;
using sim::testing::WriteSetFromShip;
using ::testing::HasSubstr;
using ::testing::Not;

std::string Kelvin() { return (kelvin::testing::ToolsDir() / "kelvin").string(); }

int CountLines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

// kelvin simulate with `set` in the ship file, into `dir`.
void Simulate(const std::string& ship, const fs::path& set, const std::string& maneuvers, const fs::path& dir) {
  const auto r = RunCommand(Kelvin() + " simulate " + ShipFile(ship).string() + " --derivatives " + set.string() + " " +
                            maneuvers + " -o " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
}

std::string Check(const fs::path& set, const std::string& ship, const std::string& args) {
  return Kelvin() + " check " + set.string() + " --ship " + ShipFile(ship).string() + " " + args;
}

// A set identified over less than a maneuver flies: kelvin simulate and
// kelvin check both say the maneuver went beyond its range; within it,
// neither does.
TEST(KelvinCheckTest, ManeuversBeyondTheIdentifiedRangeAreNamed) {
  const ScopedTempDir dir;
  const auto narrow = WriteSetFromShip(dir / "narrow.yaml", "wigley", 1.0, "", "  range: {drift_deg: 1, r_prime: 0.05}\n");
  const auto wide = WriteSetFromShip(dir / "wide.yaml", "wigley", 1.0, "", "  range: {drift_deg: 60, r_prime: 3}\n");
  const auto sim = RunCommand(Kelvin() + " simulate " + ShipFile("wigley").string() + " --derivatives " +
                              narrow.string() + " -m turning:35:stbd -o " + (dir / "narrow").string());
  ASSERT_EQ(sim.exit_code, 0) << sim.output;
  EXPECT_THAT(sim.output, HasSubstr("WARNING: turning:35:stbd reached drift"));
  EXPECT_THAT(sim.output, HasSubstr("identified up to drift 1.0 deg and r' 0.05"));
  const fs::path turning = dir / "narrow/Wigley_turning_35_stbd.h5";
  const auto check = RunCommand(Check(narrow, "wigley", "--against " + turning.string()));
  ASSERT_EQ(check.exit_code, 0) << check.output;
  EXPECT_THAT(check.output, HasSubstr("WARNING: the simulator reference of turning:35:stbd reached drift"));
  EXPECT_THAT(check.output, HasSubstr("WARNING: the surrogate's turning:35:stbd reached drift"));
  const auto within = RunCommand(Kelvin() + " simulate " + ShipFile("wigley").string() + " --derivatives " +
                                 wide.string() + " -m turning:35:stbd -o " + (dir / "wide").string());
  ASSERT_EQ(within.exit_code, 0) << within.output;
  EXPECT_THAT(within.output, Not(HasSubstr("WARNING")));
}

TEST(KelvinCheckTest, SameDerivativesPassAndAreRecorded) {
  const ScopedTempDir dir;
  const auto set = WriteSetFromShip(dir / "wigley_set.yaml", "wigley");
  Simulate("wigley", set, "-m turning:35:stbd -m zigzag:20/20:stbd", dir / "ref");
  const fs::path turning = dir / "ref/Wigley_turning_35_stbd.h5", zigzag = dir / "ref/Wigley_zigzag_20_20_stbd.h5";
  const auto r = RunCommand(Check(set, "wigley",
                                  "--against " + turning.string() + " " + zigzag.string() +
                                      " -m turning:35:stbd -m zigzag:20/20:stbd -o " + (dir / "report").string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("tactical_diameter"));
  EXPECT_THAT(r.output, HasSubstr("first_overshoot"));
  EXPECT_THAT(r.output, HasSubstr("position error max 0 m (0 L)"));
  EXPECT_THAT(r.output, HasSubstr("check PASSED: 2 maneuver(s), 0 failed"));
  const sim::DerivativeSet back = sim::LoadDerivativeSet(set);
  ASSERT_TRUE(back.check.has_value());
  EXPECT_TRUE(back.check->passed);
  EXPECT_EQ(back.check->reference, turning.string() + ", " + zigzag.string());
  EXPECT_EQ(back.check->date.size(), std::string("2026-11-23T10:00:00Z").size()) << back.check->date;
  EXPECT_EQ(CountLines(back.check->summary), 1);  // two lines, one per maneuver
  EXPECT_TRUE(fs::exists(dir / "report/check_report.md"));
  EXPECT_TRUE(fs::exists(dir / "report/track_errors.h5"));
  const fs::path surrogate = dir / "report/surrogate_0_Wigley_turning_35_stbd.h5";
  ASSERT_TRUE(fs::exists(surrogate));

  if (RunCommand("/usr/bin/python3 -c 'import h5py, matplotlib, numpy'").exit_code != 0) {
    GTEST_SKIP() << "python3-h5py/python3-matplotlib not installed";
  }
  const std::string script = (kelvin::testing::SourceDir() / "tools/plot_maneuver.py").string();
  const auto plot = RunCommand("/usr/bin/python3 " + script + " " + turning.string() + " --overlay " +
                               surrogate.string() + " -o " + (dir / "plots").string());
  ASSERT_EQ(plot.exit_code, 0) << plot.output;
  EXPECT_TRUE(fs::exists(dir / "plots/Wigley_turning_35_stbd_vs_surrogate_0_Wigley_turning_35_stbd.png"));
  const auto mismatch = RunCommand("/usr/bin/python3 " + script + " " + turning.string() + " " + zigzag.string() +
                                   " --overlay " + surrogate.string());
  EXPECT_EQ(mismatch.exit_code, 2);
  EXPECT_THAT(mismatch.output, HasSubstr("--overlay: 1 files for 2 files to plot; expected one per file"));
}

TEST(KelvinCheckTest, PerturbedHullFailsWithExitThreeAndItsTable) {
  const ScopedTempDir dir;
  const auto set = WriteSetFromShip(dir / "kvlcc2_set.yaml", "kvlcc2");
  const auto perturbed = WriteSetFromShip(dir / "perturbed.yaml", "kvlcc2", 1.2);
  Simulate("kvlcc2", perturbed, "-m turning:35:stbd", dir / "ref");
  const fs::path turning = dir / "ref/KVLCC2_turning_35_stbd.h5";
  const auto r = RunCommand(Check(set, "kvlcc2", "--against " + turning.string() + " -o " + (dir / "report").string()));
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_THAT(r.output, HasSubstr("tactical_diameter"));
  EXPECT_THAT(r.output, HasSubstr("FAIL"));
  EXPECT_THAT(r.output, HasSubstr("check FAILED: 1 maneuver(s), 1 failed"));
  EXPECT_THAT(r.output, HasSubstr("kelvin: check FAILED: derivative set " + set.string()));
  const sim::DerivativeSet back = sim::LoadDerivativeSet(set);
  ASSERT_TRUE(back.check.has_value());
  EXPECT_FALSE(back.check->passed);
  EXPECT_THAT(back.check->summary, HasSubstr("FAIL; worst tactical_diameter"));
  // The same references with wider tolerances pass; the section is replaced.
  const auto wide =
      RunCommand(Check(set, "kvlcc2",
                       "--against " + turning.string() + " --tolerances advance=10%,tactical_diameter=10% -o " +
                           (dir / "report").string()));
  EXPECT_EQ(wide.exit_code, 0) << wide.output;
  EXPECT_TRUE(sim::LoadDerivativeSet(set).check->passed);
}

struct BadCheck {
  std::string args;
  int exit_code;
  std::string message;
};

TEST(KelvinCheckTest, EachBadInputExitsWithOneMessageAndLeavesTheSet) {
  const ScopedTempDir dir;
  const auto set = WriteSetFromShip(dir / "set.yaml", "wigley");
  const auto other = WriteSetFromShip(dir / "kvlcc2_set.yaml", "kvlcc2");
  Simulate("wigley", set, "-m turning:35:stbd", dir / "ref");
  Simulate("kvlcc2", other, "-m turning:35:stbd", dir / "ref");
  const std::string wigley_ref = (dir / "ref/Wigley_turning_35_stbd.h5").string();
  const std::string kvlcc2_ref = (dir / "ref/KVLCC2_turning_35_stbd.h5").string();
  const std::string before = ReadText(set);
  const BadCheck cases[] = {
      {Check(other, "wigley", "--against " + wigley_ref), 1,
       "kelvin: error: " + other.string() +
           ":4: key 'derivative_set.ship' = 'KVLCC2': expected a derivative set of "
           "ship 'Wigley'"},
      {Check(set, "wigley", "--against " + kvlcc2_ref), 2,
       "kelvin: error: --against " + kvlcc2_ref +
           ": attribute 'ship' = 'KVLCC2': expected a maneuver of ship 'Wigley'"},
      {Check(set, "wigley", "--against " + set.string()), 1,
       "kelvin: error: " + set.string() + ": not an HDF5 file; expected a maneuver result"},
      {Check(set, "wigley", "--against " + wigley_ref + " -m zigzag:20/20:stbd"), 2,
       "kelvin: error: --against " + wigley_ref +
           ": attribute 'maneuver' = 'turning:35:stbd': expected the maneuver --maneuver asks for (zigzag:20/20:stbd)"},
      {Check(set, "wigley", "--against " + (dir / "none.h5").string()), 2, (dir / "none.h5").string()},
      {Check(set, "wigley", "--against " + wigley_ref + " --tolerances advance=5parsecs"), 2,
       "kelvin: error: --tolerances 'advance=5parsecs': unknown unit 'parsecs'"},
      {Kelvin() + " check " + set.string() + " --against " + wigley_ref, 2, "--ship"},
  };
  for (const BadCheck& c : cases) {
    const auto r = RunCommand(c.args + " -o " + (dir / "report").string());
    EXPECT_EQ(r.exit_code, c.exit_code) << c.args << "\n" << r.output;
    EXPECT_EQ(CountLines(r.output), 1) << r.output;
    EXPECT_THAT(r.output, HasSubstr(c.message)) << c.args;
  }
  EXPECT_EQ(ReadText(set), before);
  EXPECT_FALSE(fs::exists(dir / "report"));
}

TEST(KelvinCheckTest, IsListedInTheHelp) {
  const auto r = RunCommand(Kelvin() + " --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("Check a derivative set's surrogate against reference maneuver runs"));
  const auto h = RunCommand(Kelvin() + " help check");
  EXPECT_EQ(h.exit_code, 0);
  EXPECT_THAT(h.output, HasSubstr("--against"));
  EXPECT_THAT(h.output, HasSubstr("--tolerances"));
  EXPECT_THAT(h.output, Not(HasSubstr("unknown command")));
}

}  // namespace
}  // namespace kelvin::cli
