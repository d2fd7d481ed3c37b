// Free-running CFD maneuvers of the 1 m Wigley (data/cases/free_running/
// wigley_turning.yaml) on the quickstart's captive grid: the body-force
// rudder steered by the simulator's own maneuver controller
// (cfd/run/maneuver_pilot.h), its result in the simulator's schema, a
// restart in the middle of the maneuver, the inputs a maneuver cannot run
// with, and a campaign of maneuvers (kelvin run -m ... --jobs N) that
// resumes.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "cfd/campaign/maneuver_campaign.h"
#include "cfd/propulsion/rudder.h"
#include "data/schema/errors.h"
#include "data/schema/h5_file.h"
#include "tests/cfd/run/wigley_free_running_fixture.h"

namespace kelvin::cfd {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;
using testing::FreeRunning;
constexpr double kDeg = std::numbers::pi / 180.0;

// The turning circle cut to 8 s: approach, release at 2 s, execute at 5 s.
std::string ShortTurn() {
  std::string text = FreeRunning::CaseText("wigley_turning");
  FreeRunning::Replace(text, "end: 80.0", "end: 8.0");
  return text;
}

TEST_F(FreeRunning, TurningIsFlownByTheSimulatorsControllerAndWrittenInItsSchema) {
  const RunSummary s = Run("turn", ShortTurn());
  ASSERT_EQ(s.status, RunSummary::Status::kCompleted);
  const data::H5Reader h(tmp_->path() / "turn/out/history.h5");
  const auto t = h.Read("time").values, rudder = h.Read("rudder/state").values;
  const auto traj = h.Read("body/trajectory").values, inflow = h.Read("rudder/inflow").values;
  // The Wigley's steering gear: 23.4 deg/s from the execute at 5 s, at most 35 deg.
  const double rate = 23.4 * kDeg;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double order = rudder[3 * i + 1], delta = rudder[3 * i];
    // The row of the step that reaches 5 s is written before the pilot
    // orders; the blade moves from the next step on.
    if (t[i] < 5.0 + 1e-9) {
      EXPECT_EQ(order, 0.0) << "t " << t[i];
      EXPECT_EQ(delta, 0.0) << "t " << t[i];
    } else {
      EXPECT_NEAR(order, 35 * kDeg, 1e-12) << "t " << t[i];
      EXPECT_NEAR(delta, std::min(rate * (t[i] - 5.0), 35 * kDeg), 1e-9) << "t " << t[i];
    }
  }
  // Starboard rudder: the normal force is positive, the heading turns to
  // starboard (psi grows) after the execute, and the rudder sees the flow
  // from ahead.
  const std::size_t last = t.size() - 1;
  EXPECT_GT(rudder[3 * last + 2], 0.0);
  EXPECT_GT(traj[3 * last + 2], 5 * kDeg);
  EXPECT_GT(inflow[5 * last], 0.5);
  // The blade went beyond the angle of attack where its force is validated,
  // and the run's report says so with the history's largest |alpha_R|.
  double max_alpha = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) max_alpha = std::max(max_alpha, std::abs(inflow[5 * i + 2]));
  ASSERT_GT(max_alpha, Rudder::kValidatedAngle);
  char reached[64];
  std::snprintf(reached, sizeof reached, "angle of attack reached %.1f deg", max_alpha / kDeg);
  EXPECT_THAT(s.message, HasSubstr(std::string("WARNING: the rudder's ") + reached)) << s.message;
  // The result in the simulator's schema: its trajectory is the body's.
  const data::H5Reader m(tmp_->path() / "turn/out/maneuver.h5");
  const auto mt = m.Read("trajectory/time").values, mpsi = m.Read("trajectory/psi").values;
  ASSERT_EQ(mt.size(), t.size());
  EXPECT_EQ(mpsi.back(), traj[3 * last + 2]);
  EXPECT_EQ(m.Read("trajectory/rudder").values.back(), rudder[3 * last]);
}

TEST_F(FreeRunning, ManeuverRestartContinuesBitForBit) {
  ASSERT_EQ(Run("mv_whole", ShortTurn()).status, RunSummary::Status::kCompleted);
  std::string half = ShortTurn();
  Replace(half, "end: 8.0", "end: 6.0");  // one second after the execute
  ASSERT_EQ(Run("mv_half", half).status, RunSummary::Status::kCompleted);
  ASSERT_EQ(Run("mv_rest", ShortTurn(), tmp_->path() / "mv_half/out/checkpoint.h5").status,
            RunSummary::Status::kCompleted);
  const data::H5Reader a(tmp_->path() / "mv_whole/out/maneuver.h5"), b(tmp_->path() / "mv_rest/out/maneuver.h5");
  for (const char* name : {"trajectory/time", "trajectory/x", "trajectory/y", "trajectory/psi", "trajectory/r",
                           "trajectory/rudder"}) {
    const auto x = a.Read(name).values, y = b.Read(name).values;
    ASSERT_EQ(x.size(), y.size()) << name;
    for (std::size_t i = 0; i < x.size(); ++i) ASSERT_EQ(x[i], y[i]) << name << " " << i;
  }
}

TEST_F(FreeRunning, AManeuverTheCaseCannotRunIsOneClearError) {
  struct Bad {
    std::string from, to, message;
  };
  const std::vector<Bad> cases = {
      {"rudder: {angle_deg: 0.0}\n", "", "a rudder: section as well"},
      {"kind: \"turning:35:stbd\"", "kind: \"stopping\"", "a crash stop needs reverse thrust"},
      {"kind: \"turning:35:stbd\"", "kind: \"turning:50:stbd\"", "exceeds the maximum of ship 'Wigley'"},
      {"free: [surge, sway, yaw]", "free: [sway, yaw]", "all three degrees of freedom"},
      {"execute_time: 5.0", "execute_time: 1.0", "after the body's release at 2 s"},
  };
  for (const Bad& b : cases) {
    std::string text = ShortTurn();
    Replace(text, b.from, b.to);
    try {
      Run("bad_maneuver", text);
      ADD_FAILURE() << b.to << " was accepted";
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(b.message)) << b.to;
      EXPECT_THAT(e.what(), HasSubstr("case.yaml")) << b.to;
    }
  }
  // A rudder below the domain, and one cutting the hull.
  for (const Bad& b : std::vector<Bad>{{"z_top: 0.012", "z_top: 5.0", "contains no cell"},
                                       {"x_R_prime: -0.563", "x_R_prime: -0.45", "touches wall patch 'hull'"}}) {
    std::string ship = kelvin::testing::ReadText(ship_);
    Replace(ship, b.from, b.to);
    const fs::path file = tmp_->path() / "bad_rudder_ship.yaml";
    std::ofstream(file) << ship;
    std::string text = ShortTurn();
    Replace(text, "ship: " + ship_.string(), "ship: " + file.string());
    try {
      Run("bad_rudder", text);
      ADD_FAILURE() << b.to << " was accepted";
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(b.message)) << b.to;
      EXPECT_THAT(e.what(), HasSubstr("rudder.A_R, H_R, x_R_prime, z_top")) << b.to;
    }
  }
}

// The trajectories of two maneuver.h5 files, equal bit for bit.
void ExpectSameManeuver(const fs::path& a_file, const fs::path& b_file) {
  const data::H5Reader a(a_file), b(b_file);
  for (const char* name : {"trajectory/time", "trajectory/x", "trajectory/y", "trajectory/psi", "trajectory/r",
                           "trajectory/rudder"}) {
    const auto x = a.Read(name).values, y = b.Read(name).values;
    ASSERT_EQ(x.size(), y.size()) << name << ": " << a_file << " against " << b_file;
    for (std::size_t i = 0; i < x.size(); ++i) ASSERT_EQ(x[i], y[i]) << name << " " << i;
  }
}

// Two turns cut to 6 s, one second after the execute.
struct Campaign {
  fs::path case_file, output;
  ManeuverCampaignOptions options;
};

Campaign ShortCampaign(const fs::path& dir, const fs::path& grid) {
  std::string text = ShortTurn();
  FreeRunning::Replace(text, "end: 8.0", "end: 6.0");
  FreeRunning::Replace(text, "checkpoint_interval: 100", "checkpoint_interval: 20");
  fs::create_directories(dir);
  Campaign c;
  c.case_file = dir / "case.yaml";
  std::ofstream(c.case_file) << text;
  c.output = dir / "out";
  c.options.maneuvers = {"turning:35:stbd", "turning:35:port"};
  c.options.output = c.output;
  c.options.run.progress = false;
  c.options.run.poly_mesh_override = grid / "constant/polyMesh";
  c.options.stream = stderr;
  return c;
}

// A campaign stopped in its first run (as SIGTERM stops kelvin run) resumes
// that run from its checkpoint, then flies the second; the results equal an
// uninterrupted campaign's bit for bit, and a rerun skips both.
TEST_F(FreeRunning, ManeuverCampaignResumesBitForBitAndSkipsFinishedRuns) {
  Campaign whole = ShortCampaign(tmp_->path() / "campaign_whole", grid_);
  const ManeuverCampaignSummary a = RunManeuverCampaign(whole.case_file, whole.options);
  ASSERT_TRUE(a.complete) << a.table;

  Campaign stopped = ShortCampaign(tmp_->path() / "campaign_stopped", grid_);
  int polls = 0;
  // Stopped at 5.4 s, after the execute at 5 s.
  stopped.options.run.stop_requested = [&polls] { return ++polls >= 135 ? 15 : 0; };
  const ManeuverCampaignSummary b = RunManeuverCampaign(stopped.case_file, stopped.options);
  ASSERT_TRUE(b.interrupted);
  EXPECT_FALSE(b.complete);
  ASSERT_EQ(b.runs.size(), 2u);
  EXPECT_EQ(b.runs[0].state, ManeuverRun::State::kInterrupted);
  EXPECT_EQ(b.runs[1].state, ManeuverRun::State::kLeft);
  EXPECT_FALSE(fs::exists(stopped.output / "turning_35_stbd/maneuver.h5"));
  ASSERT_TRUE(fs::exists(stopped.output / "turning_35_stbd/checkpoint.h5"));

  stopped.options.run.stop_requested = nullptr;
  const ManeuverCampaignSummary c = RunManeuverCampaign(stopped.case_file, stopped.options);
  ASSERT_TRUE(c.complete) << c.table;
  for (const char* run : {"turning_35_stbd", "turning_35_port"}) {
    ExpectSameManeuver(whole.output / run / "maneuver.h5", stopped.output / run / "maneuver.h5");
  }
  // Port and starboard differ (the maneuvers were really replaced).
  const data::H5Reader stbd(whole.output / "turning_35_stbd/maneuver.h5"),
      port(whole.output / "turning_35_port/maneuver.h5");
  EXPECT_GT(stbd.Read("trajectory/psi").values.back(), 0.02);
  EXPECT_LT(port.Read("trajectory/psi").values.back(), -0.02);

  const auto written = fs::last_write_time(stopped.output / "turning_35_port/maneuver.h5");
  const ManeuverCampaignSummary d = RunManeuverCampaign(stopped.case_file, stopped.options);
  ASSERT_TRUE(d.complete);
  for (const ManeuverRun& r : d.runs) EXPECT_EQ(r.state, ManeuverRun::State::kFinishedBefore) << r.maneuver;
  EXPECT_EQ(fs::last_write_time(stopped.output / "turning_35_port/maneuver.h5"), written);

  // The stopped run's checkpoint belongs to the starboard turn: restarting
  // the port turn from it is one clear error.
  RunOptions o = stopped.options.run;
  o.maneuver = "turning:35:port";
  o.output_override = tmp_->path() / "campaign_wrong_restart";
  o.restart = whole.output / "turning_35_stbd/checkpoint.h5";
  try {
    RunCase(stopped.case_file, o);
    ADD_FAILURE() << "a checkpoint of another maneuver was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("the checkpoint is of maneuver 'turning:35:stbd'; the case flies maneuver "
                                    "'turning:35:port'"));
  }
}

// kelvin run -m ... --jobs 2: the runs as two worker processes give the
// serial campaign's results bit for bit.
TEST_F(FreeRunning, ManeuverCampaignInWorkerProcessesMatchesTheSerialOne) {
  Campaign serial = ShortCampaign(tmp_->path() / "campaign_serial", grid_);
  ASSERT_TRUE(RunManeuverCampaign(serial.case_file, serial.options).complete);
  // The workers read the case itself: its mesh path made absolute.
  std::string text = kelvin::testing::ReadText(serial.case_file);
  FreeRunning::Replace(text, "../../../build/grids/wigley_captive_quick/constant/polyMesh",
                       (grid_ / "constant/polyMesh").string());
  const fs::path dir = tmp_->path() / "campaign_jobs";
  fs::create_directories(dir);
  std::ofstream(dir / "case.yaml") << text;
  const std::string kelvin = (kelvin::testing::ToolsDir() / "kelvin").string();
  const auto r = kelvin::testing::RunCommand(kelvin + " run " + (dir / "case.yaml").string() +
                                             " -m turning:35:stbd -m turning:35:port --jobs 2 -o " +
                                             (dir / "out").string() + " 2>&1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("turning:35:port"));
  for (const char* run : {"turning_35_stbd", "turning_35_port"}) {
    ExpectSameManeuver(serial.output / run / "maneuver.h5", dir / "out" / run / "maneuver.h5");
  }
}

// The campaign's bad arguments: each one clear error, before any run.
TEST(ManeuverCampaignErrors, BadDefinitionsTwiceAndACaseWithoutAManeuver) {
  const fs::path cases = kelvin::testing::SourceDir() / "data/cases/free_running";
  const std::string kelvin = (kelvin::testing::ToolsDir() / "kelvin").string();
  struct Bad {
    std::string args, message;
  };
  for (const Bad& b : std::vector<Bad>{
           {(cases / "wigley_turning.yaml").string() + " -m turning:35:sideways", "--maneuver turning:35:sideways"},
           {(cases / "wigley_turning.yaml").string() + " -m turning:35:stbd -m turning:35.0:stbd", "given twice"},
           {(cases / "wigley_turning.yaml").string() + " -m turning:35:stbd --jobs 0", "--jobs 0: expected at least 1"},
           {(cases / "wigley_turning.yaml").string() + " -m turning:35:stbd --restart x.h5", "--restart: not with -m"},
           {(cases / "wigley_self_propulsion.yaml").string() + " -m turning:35:stbd",
            "has no maneuver: section; expected a free-running case"},
       }) {
    const auto r = kelvin::testing::RunCommand(kelvin + " run " + b.args + " 2>&1");
    EXPECT_EQ(r.exit_code, 2) << b.args << "\n" << r.output;
    EXPECT_THAT(r.output, HasSubstr(b.message)) << b.args;
  }
}

}  // namespace
}  // namespace kelvin::cfd
