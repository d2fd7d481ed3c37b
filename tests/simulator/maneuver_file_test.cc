// Reading maneuver result files back: what WriteManeuverResult writes reads
// back exactly, the source attribute, and every bad file.
#include "simulator/maneuvers/maneuver_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "data/schema/errors.h"
#include "data/schema/h5_file.h"
#include "tests/simulator/simulator_test_utilities.h"

namespace kelvin::sim {
namespace {

using ::testing::HasSubstr;

ManeuverResult RunKvlcc2(const std::string& maneuver) {
  const MmgModel<double> model(testing::Kvlcc2());
  return RunManeuver(model, ManeuverSpec::Parse(maneuver), RunOptions{});
}

TEST(ManeuverFile, ReadsBackWhatTheSimulatorWrites) {
  const kelvin::testing::ScopedTempDir dir;
  const ManeuverResult r = RunKvlcc2("zigzag:20/20:port");
  WriteManeuverResult(r, dir / "z.h5", "cvode");
  const ManeuverFile f = ReadManeuverResult(dir / "z.h5");
  EXPECT_EQ(f.path, (dir / "z.h5").string());
  EXPECT_EQ(f.source, "simulator");
  EXPECT_EQ(f.integrator, "cvode");
  const ManeuverResult& b = f.result;
  EXPECT_EQ(b.spec.ToString(), "zigzag:20/20:port");
  EXPECT_EQ(b.ship_name, "KVLCC2");
  EXPECT_EQ(b.Lpp, r.Lpp);
  EXPECT_EQ(b.approach_speed, r.approach_speed);
  EXPECT_EQ(b.approach_rps, r.approach_rps);
  EXPECT_EQ(b.execute_times, r.execute_times);
  ASSERT_EQ(b.trajectory.size(), r.trajectory.size());
  for (std::size_t i = 0; i < r.trajectory.size(); ++i) {
    const TrajectorySample &x = r.trajectory[i], &y = b.trajectory[i];
    EXPECT_EQ(x.t, y.t);
    EXPECT_EQ(x.x, y.x);
    EXPECT_EQ(x.y, y.y);
    EXPECT_EQ(x.psi, y.psi);
    EXPECT_EQ(x.u, y.u);
    EXPECT_EQ(x.v, y.v);
    EXPECT_EQ(x.r, y.r);
    EXPECT_EQ(x.delta, y.delta);
    EXPECT_EQ(x.n, y.n);
  }
  EXPECT_EQ(b.trajectory.phases(), r.trajectory.phases());
  ASSERT_EQ(b.metrics.size(), r.metrics.size());
  for (const MetricRow& m : r.metrics) {
    const auto it =
        std::find_if(b.metrics.begin(), b.metrics.end(), [&](const MetricRow& x) { return x.name == m.name; });
    ASSERT_NE(it, b.metrics.end()) << m.name;
    EXPECT_EQ(it->value, m.value) << m.name;
    EXPECT_EQ(it->unit, m.unit) << m.name;
    EXPECT_EQ(it->description, m.description) << m.name;
  }
  ASSERT_EQ(b.verdicts.size(), r.verdicts.size());
  for (std::size_t i = 0; i < r.verdicts.size(); ++i) {
    EXPECT_EQ(b.verdicts[i].criterion, r.verdicts[i].criterion);
    EXPECT_EQ(b.verdicts[i].value, r.verdicts[i].value);
    EXPECT_EQ(b.verdicts[i].limit, r.verdicts[i].limit);
    EXPECT_EQ(b.verdicts[i].pass, r.verdicts[i].pass);
  }
}

TEST(ManeuverFile, ReadsTheSourceAttribute) {
  const kelvin::testing::ScopedTempDir dir;
  WriteManeuverResult(RunKvlcc2("turning:35:stbd"), dir / "t.h5", "cvode");
  {
    data::H5Writer w(dir / "t.h5", data::H5Writer::Mode::kAppend);
    w.SetAttribute("/", "source", "cfd");
    w.Commit();
  }
  EXPECT_EQ(ReadManeuverResult(dir / "t.h5").source, "cfd");
}

std::string ReadError(const std::filesystem::path& path) {
  try {
    ReadManeuverResult(path);
  } catch (const DataFileError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ManeuverFile, MissingFileIsAnError) {
  const std::string m = ReadError("/nonexistent/run.h5");
  EXPECT_THAT(m, HasSubstr("/nonexistent/run.h5: file not found"));
  EXPECT_THAT(m, HasSubstr("expected a maneuver result"));
}

TEST(ManeuverFile, NotHdf5IsAnError) {
  const kelvin::testing::ScopedTempDir dir;
  std::ofstream(dir / "d.yaml") << "hull: {}\n";
  const std::string m = ReadError(dir / "d.yaml");
  EXPECT_THAT(m, HasSubstr((dir / "d.yaml").string() + ": not an HDF5 file"));
  EXPECT_THAT(m, HasSubstr("expected a maneuver result (HDF5"));
}

TEST(ManeuverFile, Hdf5WithoutTheSchemaIsNotAManeuverResult) {
  const kelvin::testing::ScopedTempDir dir;
  {
    data::H5Writer w(dir / "other.h5");
    w.WriteArray("x", std::vector<double>{1.0}, {1}, "m", "something");
    w.Commit();
  }
  EXPECT_THAT(
      ReadError(dir / "other.h5"),
      HasSubstr(": no attribute 'kelvin_schema': not a maneuver result (expected kelvin_schema = 'maneuver/1'"));
}

TEST(ManeuverFile, AnotherSchemaIsNotAManeuverResult) {
  const kelvin::testing::ScopedTempDir dir;
  {
    data::H5Writer w(dir / "captive.h5");
    w.SetAttribute("/", "kelvin_schema", "captive/1");
    w.Commit();
  }
  EXPECT_THAT(ReadError(dir / "captive.h5"),
              HasSubstr("attribute 'kelvin_schema' = 'captive/1': not a maneuver result (expected 'maneuver/1')"));
}

TEST(ManeuverFile, UnparsableManeuverIsAnError) {
  const kelvin::testing::ScopedTempDir dir;
  WriteManeuverResult(RunKvlcc2("turning:35:stbd"), dir / "t.h5", "cvode");
  {
    data::H5Writer w(dir / "t.h5", data::H5Writer::Mode::kAppend);
    w.SetAttribute("/", "maneuver", "loop:3");
    w.Commit();
  }
  const std::string m = ReadError(dir / "t.h5");
  EXPECT_THAT(m, HasSubstr((dir / "t.h5").string() + ": attribute 'maneuver': maneuver 'loop:3': unknown maneuver "
                                                     "kind 'loop'"));
}

TEST(ManeuverFile, NonPositiveApproachSpeedIsAnError) {
  const kelvin::testing::ScopedTempDir dir;
  WriteManeuverResult(RunKvlcc2("turning:35:stbd"), dir / "t.h5", "cvode");
  {
    data::H5Writer w(dir / "t.h5", data::H5Writer::Mode::kAppend);
    w.SetAttribute("/", "approach_speed", 0.0);
    w.Commit();
  }
  EXPECT_THAT(ReadError(dir / "t.h5"), HasSubstr("attribute 'approach_speed' = 0 m/s: expected a positive number"));
}

}  // namespace
}  // namespace kelvin::sim
