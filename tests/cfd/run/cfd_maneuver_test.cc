// Free-running CFD maneuvers of the 1 m Wigley (data/cases/free_running/
// wigley_turning.yaml) on the quickstart's captive grid: the body-force
// rudder steered by the simulator's own maneuver controller
// (cfd/run/maneuver_pilot.h), its result in the simulator's schema, a
// restart in the middle of the maneuver, and the inputs a maneuver cannot
// run with.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

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

}  // namespace
}  // namespace kelvin::cfd
