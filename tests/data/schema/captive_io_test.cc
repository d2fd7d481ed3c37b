// Captive campaign files: HDF5 and CSV round trips, and one clear error per
// bad input (acceptance 5 of issue 9), each naming the run and the channel.
#include "data/schema/captive_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "data/schema/errors.h"
#include "data/schema/h5_file.h"
#include "tests/data/schema/captive_test_fixtures.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::data {
namespace {

using fixtures::SmallCampaign;

void ExpectSameCampaign(const CaptiveCampaign& a, const CaptiveCampaign& b) {
  EXPECT_EQ(a.ship.name, b.ship.name);
  EXPECT_EQ(a.ship.Lpp, b.ship.Lpp);
  EXPECT_EQ(a.ship.mass, b.ship.mass);
  EXPECT_EQ(a.ship.I_zG, b.ship.I_zG);
  EXPECT_EQ(a.ship.x_G, b.ship.x_G);
  ASSERT_EQ(a.runs.size(), b.runs.size());
  for (std::size_t r = 0; r < a.runs.size(); ++r) {
    const CaptiveRun *x = &a.runs[r], *y = nullptr;
    for (const CaptiveRun& run : b.runs) {
      if (run.name == x->name) y = &run;
    }
    ASSERT_NE(y, nullptr) << x->name;
    EXPECT_EQ(x->motion.kind, y->motion.kind);
    EXPECT_EQ(x->motion.U, y->motion.U);
    EXPECT_EQ(x->motion.beta, y->motion.beta);
    EXPECT_EQ(x->motion.y_a, y->motion.y_a);
    EXPECT_EQ(x->motion.psi_a, y->motion.psi_a);
    EXPECT_EQ(x->motion.omega, y->motion.omega);
    EXPECT_EQ(x->motion.t_ramp, y->motion.t_ramp);
    EXPECT_EQ(x->includes_rigid_body_inertia, y->includes_rigid_body_inertia);
    EXPECT_EQ(x->time, y->time);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(x->force[c], y->force[c]);
  }
}

TEST(CaptiveIoTest, H5RoundTripIsExact) {
  testing::ScopedTempDir dir;
  const CaptiveCampaign c = SmallCampaign();
  WriteCampaignH5(c, dir / "c.h5");
  ExpectSameCampaign(c, ReadCampaignH5(dir / "c.h5"));
}

TEST(CaptiveIoTest, CsvRoundTripIsExact) {
  testing::ScopedTempDir dir;
  const CaptiveCampaign c = SmallCampaign();
  CaptiveCampaign back;
  back.ship = c.ship;
  for (const CaptiveRun& run : c.runs) {
    WriteRunCsv(run, dir / (run.name + ".csv"));
    back.runs.push_back(ReadRunCsv(dir / (run.name + ".csv")));
  }
  ExpectSameCampaign(c, back);
}

// Writes a campaign by hand so that single channels can be broken.
struct H5Edit {
  std::string drop_channel;   // "run/channel" left out
  std::string units_channel;  // "run/channel" written with wrong units
  std::string units = "kN";
};
void WriteEdited(const CaptiveCampaign& c, const std::filesystem::path& path, const H5Edit& edit) {
  H5Writer w(path);
  w.SetAttribute("/", "schema", kCaptiveSchema);
  w.SetAttribute("/ship", "name", c.ship.name);
  for (auto [k, v] : std::vector<std::pair<std::string, double>>{{"Lpp", c.ship.Lpp},
                                                                 {"B", c.ship.B},
                                                                 {"d", c.ship.d},
                                                                 {"rho", c.ship.rho},
                                                                 {"mass", c.ship.mass},
                                                                 {"x_G", c.ship.x_G},
                                                                 {"I_zG", c.ship.I_zG}}) {
    w.SetAttribute("/ship", k, v);
  }
  for (const CaptiveRun& run : c.runs) {
    const std::string g = "/runs/" + run.name;
    w.SetAttribute(g, "kind", MotionKindName(run.motion.kind));
    for (auto [k, v] : std::vector<std::pair<std::string, double>>{{"U", run.motion.U},
                                                                   {"beta", run.motion.beta},
                                                                   {"y_a", run.motion.y_a},
                                                                   {"psi_a", run.motion.psi_a},
                                                                   {"omega", run.motion.omega},
                                                                   {"t_ramp", run.motion.t_ramp}}) {
      w.SetAttribute(g, k, v);
    }
    w.SetAttribute(g, "rigid_body_inertia", "included");
    const std::array<std::pair<std::string, const std::vector<double>*>, 4> ch = {
        {{"time", &run.time}, {"X", &run.force[0]}, {"Y", &run.force[1]}, {"N", &run.force[2]}}};
    const std::array<std::string, 4> units = {"s", "N", "N", "N m"};
    for (int i = 0; i < 4; ++i) {
      const std::string key = run.name + "/" + ch[i].first;
      if (key == edit.drop_channel) continue;
      const std::string u = key == edit.units_channel ? edit.units : units[i];
      w.DeclareSeries(g + "/" + ch[i].first, u, "");
      w.Append(g + "/" + ch[i].first, *ch[i].second);
    }
  }
  w.Commit();
}

std::string ReadError(const std::filesystem::path& path) {
  try {
    ReadCampaignH5(path);
  } catch (const DataFileError& e) {
    return e.what();
  }
  return "no error";
}

TEST(CaptiveIoTest, MissingChannelNamesRunAndChannel) {
  testing::ScopedTempDir dir;
  const CaptiveCampaign c = SmallCampaign();
  const std::string run = c.runs[1].name;
  H5Edit edit;
  edit.drop_channel = run + "/Y";
  WriteEdited(c, dir / "c.h5", edit);
  const std::string msg = ReadError(dir / "c.h5");
  EXPECT_NE(msg.find("run '" + run + "': channel 'Y' is missing"), std::string::npos) << msg;
}

TEST(CaptiveIoTest, InconsistentUnitsNameRunAndChannel) {
  testing::ScopedTempDir dir;
  const CaptiveCampaign c = SmallCampaign();
  const std::string run = c.runs[2].name;
  H5Edit edit;
  edit.units_channel = run + "/N";
  edit.units = "kN m";
  WriteEdited(c, dir / "c.h5", edit);
  const std::string msg = ReadError(dir / "c.h5");
  EXPECT_NE(msg.find("run '" + run + "': channel 'N' has units 'kN m'; expected 'N m'"),
            std::string::npos)
      << msg;
  edit.units_channel = run + "/time";
  edit.units = "ms";
  WriteEdited(c, dir / "d.h5", edit);
  const std::string msg2 = ReadError(dir / "d.h5");
  EXPECT_NE(msg2.find("run '" + run + "': channel 'time' has units 'ms'; expected 's'"),
            std::string::npos)
      << msg2;
}

TEST(CaptiveIoTest, LessThanOnePeriodAfterRampNamesRunAndChannels) {
  testing::ScopedTempDir dir;
  CaptiveCampaign c = SmallCampaign();
  CaptiveRun& run = c.runs[1];  // pure sway: 1 ramp period + 2 periods of 50 samples
  ASSERT_EQ(run.motion.kind, MotionKind::kPureSway);
  const std::size_t keep = 50 + 49;  // the ramp-up and 49/50 of a period
  run.time.resize(keep);
  for (auto& f : run.force) f.resize(keep);
  WriteCampaignH5(c, dir / "c.h5");
  const std::string msg = ReadError(dir / "c.h5");
  EXPECT_NE(msg.find("run '" + run.name + "': channels 'X', 'Y', 'N': less than one whole period"),
            std::string::npos)
      << msg;
  // One more sample (t = 2T - dt) completes the period: accepted.
  CaptiveCampaign ok = SmallCampaign();
  ok.runs[1].time.resize(keep + 1);
  for (auto& f : ok.runs[1].force) f.resize(keep + 1);
  EXPECT_NO_THROW(ValidateCampaign(ok, "ok"));
}

TEST(CaptiveIoTest, NanInForcesNamesRunChannelAndSample) {
  testing::ScopedTempDir dir;
  CaptiveCampaign c = SmallCampaign();
  c.runs[3].force[2][17] = std::numeric_limits<double>::quiet_NaN();
  WriteCampaignH5(c, dir / "c.h5");
  const std::string msg = ReadError(dir / "c.h5");
  EXPECT_NE(msg.find("run '" + c.runs[3].name + "': channel 'N': sample 17"), std::string::npos)
      << msg;
  EXPECT_NE(msg.find("nan"), std::string::npos) << msg;
}

TEST(CaptiveIoTest, NonIncreasingTimeNamesRun) {
  CaptiveCampaign c = SmallCampaign();
  c.runs[0].time[5] = c.runs[0].time[4];
  try {
    ValidateCampaign(c, "c.h5");
    FAIL();
  } catch (const DataFileError& e) {
    EXPECT_NE(std::string(e.what()).find("run '" + c.runs[0].name + "': channel 'time': sample 5"),
              std::string::npos)
        << e.what();
  }
}

TEST(CaptiveIoTest, BadMotionAttributesNameRunAndAttribute) {
  CaptiveCampaign c = SmallCampaign();
  c.runs[1].motion.omega = 0;
  try {
    ValidateCampaign(c, "c.h5");
    FAIL();
  } catch (const DataFileError& e) {
    EXPECT_NE(std::string(e.what()).find("run '" + c.runs[1].name + "': attribute 'omega' = 0"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(ParseMotionKind("pure_surge", "c.h5: run 'a'"), DataFileError);
  try {
    ParseMotionKind("pure_surge", "c.h5: run 'a'");
  } catch (const DataFileError& e) {
    EXPECT_NE(
        std::string(e.what()).find("unknown motion kind 'pure_surge'; valid kinds: static_drift"),
        std::string::npos);
  }
}

TEST(CaptiveIoTest, NotACampaignFile) {
  testing::ScopedTempDir dir;
  {
    H5Writer w(dir / "other.h5");
    w.SetAttribute("/", "schema", "kelvin.maneuver/1");
    w.Commit();
  }
  EXPECT_NE(ReadError(dir / "other.h5")
                .find("attribute 'schema' = 'kelvin.maneuver/1': expected 'kelvin.captive/1'"),
            std::string::npos);
  EXPECT_NE(ReadError(dir / "missing.h5").find("missing.h5: no such file"), std::string::npos);
}

// CSV: write a run, break one thing, expect one message naming it.
std::string CsvError(const std::filesystem::path& path, const std::string& text) {
  {
    std::ofstream out(path);
    out << text;
  }
  try {
    ReadRunCsv(path);
  } catch (const DataFileError& e) {
    return e.what();
  }
  return "no error";
}

std::string CsvText(const CaptiveRun& run) {
  testing::ScopedTempDir dir;
  WriteRunCsv(run, dir / "r.csv");
  std::ifstream in(dir / "r.csv");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string Replace(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

TEST(CaptiveIoTest, CsvBadInputsNameRunAndChannel) {
  testing::ScopedTempDir dir;
  const CaptiveRun run = SmallCampaign().runs[1];
  const std::string text = CsvText(run);
  const std::string prefix = "run '" + run.name + "'";
  std::string msg = CsvError(
      dir / "a.csv", Replace(text, "time [s],X [N],Y [N],N [N m]", "time [s],X [N],N [N m]"));
  EXPECT_NE(msg.find(prefix + ": channel 'Y' is missing"), std::string::npos) << msg;
  msg = CsvError(dir / "b.csv", Replace(text, "X [N]", "X [kN]"));
  EXPECT_NE(msg.find(prefix + ": channel 'X' has units 'kN'; expected 'N'"), std::string::npos)
      << msg;
  msg = CsvError(dir / "c.csv", Replace(text, "# kind: pure_sway", "# kind: pure_swing"));
  EXPECT_NE(msg.find("unknown motion kind 'pure_swing'"), std::string::npos) << msg;
  msg = CsvError(dir / "d.csv", Replace(text, "# omega:", "# omgea:"));
  EXPECT_NE(msg.find("unknown header key 'omgea'"), std::string::npos) << msg;
  // A NaN parses; validation names the run, the channel and the sample.
  CaptiveRun bad = run;
  bad.force[1][3] = std::nan("");
  WriteRunCsv(bad, dir / "e.csv");
  CaptiveCampaign c;
  c.ship = SmallCampaign().ship;
  c.runs.push_back(ReadRunCsv(dir / "e.csv"));
  try {
    ValidateCampaign(c, "e.csv");
    FAIL();
  } catch (const DataFileError& e) {
    EXPECT_NE(std::string(e.what()).find(prefix + ": channel 'Y': sample 3"), std::string::npos)
        << e.what();
  }
  msg = CsvError(dir / "f.csv", text + "1.0,abc,2.0,3.0\n");
  EXPECT_NE(msg.find(prefix + ": channel 'X': 'abc' is not a number"), std::string::npos) << msg;
}

}  // namespace
}  // namespace kelvin::data
