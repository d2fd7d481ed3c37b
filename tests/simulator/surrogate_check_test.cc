// The surrogate check (kelvin check): a set checked against references the
// simulator produced from the same set has zero differences and passes;
// against references of a perturbed hull it fails in the expected direction
// and says so in the set's check section; every bad input is one clear
// error; the report files are readable.
#include "simulator/maneuvers/surrogate_check.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <numbers>

#include <fmt/format.h>

#include "data/schema/errors.h"
#include "data/schema/h5_file.h"
#include "simulator/maneuvers/identified_range.h"
#include "simulator/mmg/derivative_check_io.h"
#include "tests/simulator/surrogate_check_fixtures.h"

namespace kelvin::sim {
namespace {

using kelvin::testing::ReadText;
using kelvin::testing::ScopedTempDir;
using ::testing::HasSubstr;
using testing::ShipFile;
using testing::WriteReference;
using testing::WriteSetFromShip;

const MetricComparison& Metric(const ManeuverCheck& m, const std::string& name) {
  for (const MetricComparison& c : m.metrics) {
    if (c.name == name) return c;
  }
  throw std::runtime_error("no metric " + name);
}

SurrogateCheckOptions Options(const std::filesystem::path& set, const std::string& ship,
                              std::vector<std::filesystem::path> refs) {
  SurrogateCheckOptions o;
  o.derivatives = set;
  o.ship = ShipFile(ship);
  o.references = std::move(refs);
  o.date = "2026-11-23T10:00:00Z";
  return o;
}

// References produced by the simulator from the same derivatives: the
// surrogate reproduces them exactly, metric by metric and along the track.
TEST(SurrogateCheck, SameDerivativesGiveZeroDifferencesAndPass) {
  const ScopedTempDir dir;
  const auto set = WriteSetFromShip(dir / "wigley_set.yaml", "wigley");
  const auto turning = WriteReference(dir.path(), "wigley", set, "turning:35:stbd");
  const auto zigzag = WriteReference(dir.path(), "wigley", set, "zigzag:20/20:port");
  const SurrogateCheck check = RunSurrogateCheck(Options(set, "wigley", {turning, zigzag}));
  EXPECT_TRUE(check.passed);
  ASSERT_EQ(check.maneuvers.size(), 2u);
  for (const ManeuverCheck& m : check.maneuvers) {
    EXPECT_TRUE(m.passed) << m.summary;
    EXPECT_EQ(m.surrogate.approach_rps, m.reference.result.approach_rps);
    EXPECT_EQ(m.metrics.size(), m.reference.result.metrics.size());
    for (const MetricComparison& c : m.metrics) {
      ASSERT_TRUE(c.reference && c.surrogate) << c.name;
      EXPECT_EQ(c.difference, 0.0) << c.name;
      EXPECT_NE(c.verdict, MetricComparison::Verdict::kFail) << c.name;
    }
    EXPECT_GT(m.track.time.size(), 100u);
    EXPECT_EQ(m.track.max_position, 0.0);
    EXPECT_EQ(m.track.rms_position, 0.0);
    EXPECT_EQ(m.track.max_heading, 0.0);
  }
  // The default tolerances give the verdicts.
  const ManeuverCheck& t = check.maneuvers[0];
  EXPECT_EQ(Metric(t, "advance").verdict, MetricComparison::Verdict::kPass);
  EXPECT_EQ(Metric(t, "tactical_diameter").verdict, MetricComparison::Verdict::kPass);
  EXPECT_EQ(Metric(t, "tactical_diameter").tolerance->text, "5%");
  EXPECT_EQ(Metric(t, "transfer").verdict, MetricComparison::Verdict::kNone);
  const ManeuverCheck& z = check.maneuvers[1];
  EXPECT_EQ(Metric(z, "first_overshoot").verdict, MetricComparison::Verdict::kPass);
  EXPECT_EQ(Metric(z, "second_overshoot").tolerance->text, "2deg");
  EXPECT_EQ(Metric(z, "period").verdict, MetricComparison::Verdict::kNone);

  // The section names the references, one summary line per maneuver.
  EXPECT_TRUE(check.section.passed);
  EXPECT_EQ(check.section.reference, turning.string() + ", " + zigzag.string());
  EXPECT_EQ(check.section.date, "2026-11-23T10:00:00Z");
  EXPECT_EQ(check.section.summary, check.maneuvers[0].summary + "\n" + check.maneuvers[1].summary);
  EXPECT_THAT(check.maneuvers[0].summary, HasSubstr("turning:35:stbd against " + turning.string() + ": pass"));

  // Written and read back.
  WriteDerivativeCheck(set, check.section);
  const DerivativeSet back = LoadDerivativeSet(set);
  ASSERT_TRUE(back.check.has_value());
  EXPECT_TRUE(back.check->passed);
  EXPECT_EQ(back.check->reference, check.section.reference);
  EXPECT_EQ(back.check->summary, check.section.summary);
}

// A set identified over a narrower range than the maneuvers fly: the check
// names the reference and the surrogate that went beyond it, with how far
// (kelvin check prints the lines); a set whose range spans them, or that
// has none, gives no warning.
TEST(SurrogateCheck, ManeuversBeyondTheIdentifiedRangeAreNamed) {
  const ScopedTempDir dir;
  const auto narrow = WriteSetFromShip(dir / "narrow.yaml", "wigley", 1.0, "",
                                       "  range: {drift_deg: 2, r_prime: 0.1}\n");
  const auto wide = WriteSetFromShip(dir / "wide.yaml", "wigley", 1.0, "",
                                     "  range: {drift_deg: 60, r_prime: 3}\n");
  const auto bare = WriteSetFromShip(dir / "bare.yaml", "wigley");
  const auto turning = WriteReference(dir.path(), "wigley", bare, "turning:35:stbd");
  const SurrogateCheck n = RunSurrogateCheck(Options(narrow, "wigley", {turning}));
  ASSERT_EQ(n.maneuvers.size(), 1u);
  const ManeuverCheck& m = n.maneuvers[0];
  const MotionRange e = TrajectoryExtent(m.reference.result.trajectory, m.reference.result.Lpp);
  EXPECT_GT(e.drift, 2.0 * std::numbers::pi / 180.0);
  EXPECT_GT(e.r_prime, 0.1);
  ASSERT_EQ(m.warnings.size(), 2u);
  EXPECT_THAT(m.warnings[0], HasSubstr("WARNING: the simulator reference of turning:35:stbd reached drift"));
  EXPECT_THAT(m.warnings[0], HasSubstr(fmt::format("r' {:.2f}", e.r_prime)));
  EXPECT_THAT(m.warnings[0], HasSubstr("identified up to drift 2.0 deg and r' 0.10"));
  EXPECT_THAT(m.warnings[1], HasSubstr("WARNING: the surrogate's turning:35:stbd reached"));
  EXPECT_THAT(FormatCheckTable(n), HasSubstr(m.warnings[1]));
  EXPECT_TRUE(RunSurrogateCheck(Options(wide, "wigley", {turning})).maneuvers[0].warnings.empty());
  EXPECT_TRUE(RunSurrogateCheck(Options(bare, "wigley", {turning})).maneuvers[0].warnings.empty());
}

// References from a hull whose yaw damping N_r is 1.2 times the set's: the
// reference turns on a wider circle, so the surrogate's tactical diameter is
// smaller (negative difference), by more than 5% on the KVLCC2, and the check
// fails and says so in the set.
TEST(SurrogateCheck, PerturbedHullFailsInTheExpectedDirection) {
  const ScopedTempDir dir;
  const auto set = WriteSetFromShip(dir / "kvlcc2_set.yaml", "kvlcc2");
  const auto perturbed = WriteSetFromShip(dir / "perturbed.yaml", "kvlcc2", 1.2);
  const auto turning = WriteReference(dir.path(), "kvlcc2", perturbed, "turning:35:stbd");
  const SurrogateCheck check = RunSurrogateCheck(Options(set, "kvlcc2", {turning}));
  ASSERT_EQ(check.maneuvers.size(), 1u);
  const ManeuverCheck& m = check.maneuvers[0];
  const MetricComparison& td = Metric(m, "tactical_diameter");
  EXPECT_LT(td.difference, 0);
  EXPECT_LT(td.relative, -0.05);
  EXPECT_DOUBLE_EQ(td.difference, *td.surrogate - *td.reference);
  EXPECT_DOUBLE_EQ(td.relative, td.difference / *td.reference);
  EXPECT_DOUBLE_EQ(td.allowed, 0.05 * *td.reference);
  EXPECT_GT(td.used, 1);
  EXPECT_EQ(td.verdict, MetricComparison::Verdict::kFail);
  EXPECT_LT(Metric(m, "advance").difference, 0);
  // A stronger yaw damping also turns more slowly: the surrogate's rate is higher.
  EXPECT_GT(Metric(m, "steady_rate").difference, 0);
  EXPECT_FALSE(m.passed);
  EXPECT_FALSE(check.passed);
  EXPECT_GT(m.track.max_position, 0.1 * m.reference.result.Lpp);
  EXPECT_GT(m.track.max_position, m.track.rms_position);
  EXPECT_GT(m.track.max_heading, 0);
  EXPECT_THAT(m.summary, HasSubstr("FAIL; worst tactical_diameter"));
  EXPECT_THAT(m.summary, HasSubstr("tolerance 5%"));

  WriteDerivativeCheck(set, check.section);
  const DerivativeSet back = LoadDerivativeSet(set);
  ASSERT_TRUE(back.check.has_value());
  EXPECT_FALSE(back.check->passed);
  EXPECT_EQ(back.check->reference, turning.string());
  EXPECT_EQ(back.check->date, "2026-11-23T10:00:00Z");
  EXPECT_EQ(back.check->summary, m.summary);
  EXPECT_EQ(back.hull.N_r, LoadDerivativeSet(WriteSetFromShip(dir / "again.yaml", "kvlcc2")).hull.N_r);

  // A tolerance wide enough passes the same references.
  SurrogateCheckOptions wide = Options(set, "kvlcc2", {turning});
  wide.tolerances = ParseCheckTolerances("advance=10%,tactical_diameter=10%");
  EXPECT_TRUE(RunSurrogateCheck(wide).passed);
}

TEST(SurrogateCheck, ZigZagOvershootToleranceIsInDegrees) {
  const ScopedTempDir dir;
  const auto set = WriteSetFromShip(dir / "set.yaml", "wigley");
  const auto perturbed = WriteSetFromShip(dir / "perturbed.yaml", "wigley", 1.2);
  const auto zigzag = WriteReference(dir.path(), "wigley", perturbed, "zigzag:20/20:stbd");
  SurrogateCheckOptions o = Options(set, "wigley", {zigzag});
  const SurrogateCheck loose = RunSurrogateCheck(o);
  const MetricComparison& first = Metric(loose.maneuvers[0], "first_overshoot");
  // Less yaw damping in the surrogate: it overshoots more.
  EXPECT_GT(first.difference, 0);
  EXPECT_LT(first.difference, 2.0);
  EXPECT_TRUE(loose.passed);
  o.tolerances = ParseCheckTolerances("overshoot=0.5deg");
  const SurrogateCheck tight = RunSurrogateCheck(o);
  EXPECT_EQ(Metric(tight.maneuvers[0], "first_overshoot").verdict, MetricComparison::Verdict::kFail);
  EXPECT_EQ(Metric(tight.maneuvers[0], "second_overshoot").allowed, 0.5);
  EXPECT_FALSE(tight.passed);
}

TEST(SurrogateCheck, ReportFilesAreReadable) {
  const ScopedTempDir dir;
  const auto set = WriteSetFromShip(dir / "set.yaml", "wigley");
  const auto perturbed = WriteSetFromShip(dir / "perturbed.yaml", "wigley", 1.2);
  const auto turning = WriteReference(dir.path(), "wigley", perturbed, "turning:35:stbd");
  const SurrogateCheck check = RunSurrogateCheck(Options(set, "wigley", {turning}));
  WriteCheckReport(check, dir / "report");
  const std::string md = ReadText(dir / "report/check_report.md");
  EXPECT_THAT(md, HasSubstr("| metric | unit | reference | surrogate | difference | relative | tolerance | verdict |"));
  EXPECT_THAT(md, HasSubstr("| tactical_diameter | m |"));
  EXPECT_THAT(md, HasSubstr("| position / Lpp |"));
  const std::string table = FormatCheckTable(check);
  EXPECT_THAT(table, HasSubstr("tactical_diameter"));
  EXPECT_THAT(table, HasSubstr("position error max"));

  const data::H5Reader h5(dir / "report/track_errors.h5");
  const data::Series t = h5.Read("maneuver_0/time"), e = h5.Read("maneuver_0/position_error");
  const data::Series eL = h5.Read("maneuver_0/position_error_over_L"), h = h5.Read("maneuver_0/heading_error");
  const TrackErrors& track = check.maneuvers[0].track;
  EXPECT_EQ(t.values, track.time);
  EXPECT_EQ(e.values, track.position_error);
  EXPECT_EQ(e.units, "m");
  EXPECT_EQ(h.units, "deg");
  ASSERT_EQ(eL.values.size(), e.values.size());
  EXPECT_DOUBLE_EQ(eL.values.back(), e.values.back() / check.maneuvers[0].reference.result.Lpp);
  EXPECT_EQ(h5.StringAttribute("maneuver_0", "reference"), turning.string());
  EXPECT_EQ(h5.NumberAttribute("maneuver_0", "max_position_error"), track.max_position);

  const auto surrogate = SurrogateRunPath(check, 0, dir / "report");
  EXPECT_EQ(surrogate.filename(), "surrogate_0_Wigley_turning_35_stbd.h5");
  const ManeuverFile f = ReadManeuverResult(surrogate);
  EXPECT_EQ(f.source, "surrogate");
  EXPECT_EQ(f.result.spec.ToString(), "turning:35:stbd");
  EXPECT_EQ(f.result.trajectory.size(), check.maneuvers[0].surrogate.trajectory.size());
}

TEST(SurrogateCheck, ReferenceApproachStateIsUsed) {
  // A reference run at another speed and rps than the ship file's: the
  // surrogate starts from the reference's.
  const ScopedTempDir dir;
  const auto set = WriteSetFromShip(dir / "set.yaml", "wigley");
  const DerivativeSet s = LoadDerivativeSet(set);
  const ShipParameters ship = SurrogateShip(LoadShip(ShipFile("wigley")), "wigley", &s);
  const MmgModel<double> model(ship);
  RunOptions run;
  run.approach_speed = 0.8;
  run.approach_rps = 1.05 * SelfPropulsionRps(model, 0.8);
  WriteManeuverResult(RunManeuver(model, ManeuverSpec::Parse("turning:35:port"), run), dir / "ref.h5", "cvode");
  const SurrogateCheck check = RunSurrogateCheck(Options(set, "wigley", {dir / "ref.h5"}));
  const ManeuverCheck& m = check.maneuvers[0];
  EXPECT_EQ(m.surrogate.approach_speed, 0.8);
  EXPECT_EQ(m.surrogate.approach_rps, run.approach_rps);
  EXPECT_NE(m.self_propulsion_rps, run.approach_rps);
  EXPECT_EQ(m.track.max_position, 0.0);
  EXPECT_TRUE(check.passed);
}

// ---------------------------------------------------------------- bad input

template <typename Error>
std::string CheckError(const SurrogateCheckOptions& o) {
  try {
    RunSurrogateCheck(o);
  } catch (const Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("wrong exception type: ") + e.what();
  }
  return "no error";
}

class SurrogateCheckErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    set_ = WriteSetFromShip(dir_ / "set.yaml", "wigley");
    turning_ = WriteReference(dir_.path(), "wigley", set_, "turning:35:stbd");
  }
  ScopedTempDir dir_;
  std::filesystem::path set_, turning_;
};

TEST_F(SurrogateCheckErrors, SetOfAnotherShipThanTheShipFile) {
  const auto kvlcc2 = WriteSetFromShip(dir_ / "kvlcc2.yaml", "kvlcc2");
  EXPECT_EQ(CheckError<ConfigError>(Options(kvlcc2, "wigley", {turning_})),
            (dir_ / "kvlcc2.yaml").string() +
                ":4: key 'derivative_set.ship' = 'KVLCC2': expected a derivative set of ship 'Wigley', the ship of the "
                "ship file " +
                ShipFile("wigley").string());
}

TEST_F(SurrogateCheckErrors, ReferenceOfAnotherShip) {
  const auto kvlcc2_set = WriteSetFromShip(dir_ / "kvlcc2.yaml", "kvlcc2");
  const auto kvlcc2_ref = WriteReference(dir_.path(), "kvlcc2", kvlcc2_set, "turning:35:stbd");
  EXPECT_EQ(CheckError<ArgumentError>(Options(set_, "wigley", {turning_, kvlcc2_ref})),
            "--against " + kvlcc2_ref.string() +
                ": attribute 'ship' = 'KVLCC2': expected a maneuver of ship 'Wigley', the ship of the derivative set " +
                set_.string() + " and of the ship file " + ShipFile("wigley").string());
}

TEST_F(SurrogateCheckErrors, ReferenceThatIsNotAManeuverResult) {
  {
    data::H5Writer w(dir_ / "captive.h5");
    w.SetAttribute("/", "kelvin_schema", "captive/1");
    w.Commit();
  }
  EXPECT_EQ(CheckError<DataFileError>(Options(set_, "wigley", {dir_ / "captive.h5"})),
            (dir_ / "captive.h5").string() +
                ": attribute 'kelvin_schema' = 'captive/1': not a maneuver result (expected 'maneuver/1')");
  EXPECT_THAT(CheckError<DataFileError>(Options(set_, "wigley", {set_})),
              HasSubstr(set_.string() + ": not an HDF5 file; expected a maneuver result"));
}

TEST_F(SurrogateCheckErrors, ReferenceAtAnotherScale) {
  const DerivativeSet s = LoadDerivativeSet(set_);
  const ShipParameters model_ship = SurrogateShip(LoadShip(ShipFile("wigley")), "wigley", &s);
  const ShipParameters full = ScaleShip(model_ship, model_ship.scale, false);
  const MmgModel<double> model(full);
  WriteManeuverResult(RunManeuver(model, ManeuverSpec::Parse("turning:35:stbd"), RunOptions{}), dir_ / "full.h5",
                      "cvode");
  EXPECT_EQ(CheckError<ArgumentError>(Options(set_, "wigley", {dir_ / "full.h5"})),
            "--against " + (dir_ / "full.h5").string() +
                ": attribute 'Lpp' = 100 m: expected the Lpp of the ship file " + ShipFile("wigley").string() +
                " (1 m), a reference at the ship file's scale");
}

TEST_F(SurrogateCheckErrors, ReferenceOfAnotherManeuverThanAsked) {
  SurrogateCheckOptions o = Options(set_, "wigley", {turning_});
  o.maneuvers = {"zigzag:20/20:stbd"};
  EXPECT_EQ(CheckError<ArgumentError>(o), "--against " + turning_.string() +
                                              ": attribute 'maneuver' = 'turning:35:stbd': expected the maneuver "
                                              "--maneuver asks for (zigzag:20/20:stbd)");
}

TEST_F(SurrogateCheckErrors, AskedManeuverWithoutReference) {
  SurrogateCheckOptions o = Options(set_, "wigley", {turning_});
  o.maneuvers = {"turning:35:stbd", "turning:35:port"};
  EXPECT_EQ(CheckError<ArgumentError>(o),
            "--maneuver turning:35:port: no reference file is of this maneuver; "
            "expected one among --against: " +
                turning_.string() + " (turning:35:stbd)");
  o.maneuvers = {"turning:35"};
  EXPECT_THAT(CheckError<ArgumentError>(o),
              HasSubstr("maneuver 'turning:35': turning needs a rudder angle and a side"));
}

TEST_F(SurrogateCheckErrors, MissingFiles) {
  EXPECT_EQ(CheckError<ArgumentError>(Options(dir_ / "none.yaml", "wigley", {turning_})),
            "derivative set " + (dir_ / "none.yaml").string() + ": file not found");
  SurrogateCheckOptions o = Options(set_, "wigley", {turning_});
  o.ship = dir_ / "none_ship.yaml";
  EXPECT_EQ(CheckError<ArgumentError>(o), "--ship " + (dir_ / "none_ship.yaml").string() + ": file not found");
  EXPECT_EQ(CheckError<ArgumentError>(Options(set_, "wigley", {turning_, dir_ / "none.h5"})),
            "--against " + (dir_ / "none.h5").string() + ": file not found");
  EXPECT_THAT(CheckError<ArgumentError>(Options(set_, "wigley", {})), HasSubstr("--against: no reference file given"));
}

TEST_F(SurrogateCheckErrors, ToleranceOfAMetricNoManeuverHas) {
  SurrogateCheckOptions o = Options(set_, "wigley", {turning_});
  o.tolerances = ParseCheckTolerances("advnce=3%");
  const std::string m = CheckError<ArgumentError>(o);
  EXPECT_THAT(m,
              HasSubstr("--tolerances 'advnce=3%': no maneuver checked has a metric 'advnce'; its metrics: advance, "));
  EXPECT_THAT(m, HasSubstr("(did you mean 'advance'?)"));
  // A default tolerance of another maneuver kind is no error (overshoots here).
  o.tolerances = ParseCheckTolerances("");
  EXPECT_EQ(CheckError<ArgumentError>(o), "no error");
}

TEST_F(SurrogateCheckErrors, ToleranceInAnotherUnitThanTheMetric) {
  SurrogateCheckOptions o = Options(set_, "wigley", {turning_});
  o.tolerances = ParseCheckTolerances("advance=2deg");
  EXPECT_EQ(CheckError<ArgumentError>(o),
            "--tolerances 'advance=2deg': advance is in m; expected a percentage or a value in m");
  o.tolerances = ParseCheckTolerances("advance=0.1");
  EXPECT_EQ(CheckError<ArgumentError>(o),
            "--tolerances 'advance=0.1': advance is in m; expected a percentage or a value in m");
  o.tolerances = ParseCheckTolerances("advance_over_L=0.1,advance=0.1m");
  EXPECT_EQ(CheckError<ArgumentError>(o), "no error");
}

TEST_F(SurrogateCheckErrors, ManeuverWithoutAnyTolerance) {
  SurrogateCheckOptions o = Options(set_, "wigley", {turning_});
  o.tolerances = ParseCheckTolerances("advance=none,tactical_diameter=none");
  EXPECT_EQ(CheckError<ArgumentError>(o),
            "--tolerances: none of the metrics of turning:35:stbd (" + turning_.string() +
                ") has a tolerance (tolerances are set for: first_overshoot, second_overshoot); expected at least "
                "one, e.g. --tolerances advance=5%");
}

TEST(CheckTolerances, Defaults) {
  const CheckTolerances d = DefaultCheckTolerances();
  ASSERT_EQ(d.size(), 4u);
  EXPECT_EQ(d.at("advance").kind, MetricTolerance::Kind::kRelative);
  EXPECT_EQ(d.at("advance").value, 0.05);
  EXPECT_EQ(d.at("tactical_diameter").value, 0.05);
  EXPECT_EQ(d.at("first_overshoot").kind, MetricTolerance::Kind::kAbsolute);
  EXPECT_EQ(d.at("first_overshoot").value, 2.0);
  EXPECT_EQ(d.at("second_overshoot").unit, "deg");
}

TEST(CheckTolerances, ParsesOverTheDefaults) {
  const CheckTolerances t = ParseCheckTolerances(" advance=3% , overshoot=1.5deg,time_to_90=2s,transfer=none");
  EXPECT_EQ(t.at("advance").value, 0.03);
  EXPECT_EQ(t.at("advance").text, "3%");
  EXPECT_EQ(t.at("tactical_diameter").value, 0.05);
  EXPECT_EQ(t.at("first_overshoot").value, 1.5);
  EXPECT_EQ(t.at("second_overshoot").text, "1.5deg");
  EXPECT_EQ(t.at("time_to_90").unit, "s");
  EXPECT_EQ(t.at("transfer").kind, MetricTolerance::Kind::kNone);
}

TEST(CheckTolerances, BadItemsAreOneClearError) {
  const std::pair<const char*, const char*> cases[] = {
      {"advance", "--tolerances 'advance': no '='"},
      {"=5%", "--tolerances '=5%': no metric name"},
      {"advance=abc", "--tolerances 'advance=abc': 'abc' is not a number"},
      {"advance=-1%", "--tolerances 'advance=-1%': -1 is not a tolerance (>= 0)"},
      {"advance=5furlongs", "--tolerances 'advance=5furlongs': unknown unit 'furlongs'"},
  };
  for (const auto& [text, message] : cases) {
    try {
      ParseCheckTolerances(text);
      ADD_FAILURE() << "accepted " << text;
    } catch (const ArgumentError& e) {
      EXPECT_THAT(e.what(), HasSubstr(message));
      EXPECT_THAT(e.what(), HasSubstr("expected <metric>=<number>%"));
    }
  }
}

}  // namespace
}  // namespace kelvin::sim
