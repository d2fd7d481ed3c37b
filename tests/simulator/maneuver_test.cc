// Maneuver strings, controllers and their bad-input paths.
#include "simulator/maneuvers/maneuver.h"

#include <gmock/gmock.h>

#include "data/schema/errors.h"
#include <gtest/gtest.h>

#include "simulator/maneuvers/runner.h"
#include "tests/simulator/simulator_test_utilities.h"

namespace kelvin::sim {
namespace {

using ::testing::HasSubstr;
constexpr double kDeg = M_PI / 180.0;

TEST(ManeuverSpecTest, ParsesEveryForm) {
  const auto t = ManeuverSpec::Parse("turning:35:stbd");
  EXPECT_EQ(t.kind, ManeuverSpec::Kind::kTurning);
  EXPECT_DOUBLE_EQ(t.rudder, 35 * kDeg);
  EXPECT_EQ(t.side, +1);
  const auto z = ManeuverSpec::Parse("zigzag:20/10:port");
  EXPECT_EQ(z.kind, ManeuverSpec::Kind::kZigZag);
  EXPECT_DOUBLE_EQ(z.rudder, 20 * kDeg);
  EXPECT_DOUBLE_EQ(z.heading, 10 * kDeg);
  EXPECT_EQ(z.side, -1);
  const auto s = ManeuverSpec::Parse("spiral:25:5");
  ASSERT_EQ(s.spiral_rudders.size(), 21u);  // 25 .. -25 and back up to 25
  EXPECT_DOUBLE_EQ(s.spiral_rudders.front(), 25 * kDeg);
  EXPECT_NEAR(s.spiral_rudders[10], -25 * kDeg, 1e-15);
  EXPECT_DOUBLE_EQ(s.spiral_rudders.back(), 25 * kDeg);
  EXPECT_EQ(ManeuverSpec::Parse("stopping").kind, ManeuverSpec::Kind::kStopping);
  for (const char* text : {"turning:35:stbd", "zigzag:20/10:port", "spiral:25:5", "stopping"}) {
    EXPECT_EQ(ManeuverSpec::Parse(text).ToString(), text);
  }
}

struct BadSpec {
  const char* text;
  const char* message;
};

class BadManeuverTest : public ::testing::TestWithParam<BadSpec> {};

TEST_P(BadManeuverTest, GivesOneClearError) {
  try {
    ManeuverSpec::Parse(GetParam().text);
    FAIL() << "accepted " << GetParam().text;
  } catch (const ArgumentError& e) {
    EXPECT_THAT(e.what(), HasSubstr(std::string("maneuver '") + GetParam().text + "'"));
    EXPECT_THAT(e.what(), HasSubstr(GetParam().message));
    EXPECT_THAT(e.what(), HasSubstr("expected turning:<deg>:stbd|port"));
  }
}

INSTANTIATE_TEST_SUITE_P(
    Strings, BadManeuverTest,
    ::testing::Values(BadSpec{"loop:3", "unknown maneuver kind 'loop'"},
                      BadSpec{"turning:35", "turning needs a rudder angle and a side"},
                      BadSpec{"turning:abc:stbd", "rudder angle 'abc' is not a number"},
                      BadSpec{"turning:35:left", "side 'left' is not stbd or port"},
                      BadSpec{"turning:95:stbd", "rudder angle 95 deg is outside (0, 90]"},
                      BadSpec{"zigzag:20-20:stbd", "'20-20' is not <rudder>/<heading>"},
                      BadSpec{"spiral:5:10", "the rudder step exceeds the maximum angle"},
                      BadSpec{"stopping:now", "stopping takes no parameters"}));

TEST(ManeuverControllerTest, RudderBeyondTheShipsLimitIsRefused) {
  ShipParameters ship = testing::Kvlcc2();
  ship.limits.rudder_max = 30 * kDeg;
  try {
    ManeuverController c(ManeuverSpec::Parse("turning:35:stbd"), ship, 1.179, 11.85);
    FAIL();
  } catch (const ArgumentError& e) {
    EXPECT_THAT(e.what(), HasSubstr("rudder angle 35 deg exceeds the maximum of ship 'KVLCC2' (30 deg)"));
  }
}

TEST(ManeuverControllerTest, CrashStopWithoutReverseThrustDataIsRefused) {
  const ShipParameters ship = testing::Kvlcc2();
  try {
    ManeuverController c(ManeuverSpec::Parse("stopping"), ship, 1.179, 11.85);
    FAIL();
  } catch (const ModelError& e) {
    EXPECT_THAT(e.what(), HasSubstr("ship 'KVLCC2' has no reverse-thrust data (propeller.reverse_KT)"));
  }
}

TEST(ManeuverControllerTest, CrashStopWithReverseThrustStopsTheShip) {
  ShipParameters ship = testing::Kvlcc2();
  // Fourth-quadrant K_T chosen so that reversing at the approach rps gives
  // astern thrust (a test ship, not published data).
  ship.propeller.reverse_kt = std::array<double, 3>{-0.35, -0.3, 0.0};
  ship.limits.rps_rate = 2.0;
  const MmgModel<double> model(ship);
  const ManeuverResult r = RunManeuver(model, ManeuverSpec::Parse("stopping"), {});
  ASSERT_TRUE(r.stopping.has_value());
  EXPECT_GT(r.stopping->time_to_stop, 0.0);
  EXPECT_GT(r.stopping->track_reach, 0.0);
  // The path is at least as long as its projection on the initial course
  // (both come from the same interpolant: equal to round-off when straight).
  EXPECT_GE(r.stopping->track_reach, r.stopping->head_reach * (1 - 1e-12));
  EXPECT_LE(r.trajectory.samples().back().u, 1e-6);
}

TEST(ManeuverControllerTest, SpiralRatesFollowTheRudder) {
  const MmgModel<double> model(testing::Kvlcc2());
  ManeuverSpec spec = ManeuverSpec::Parse("spiral:20:10");
  spec.hold_time = 120.0;
  const ManeuverResult r = RunManeuver(model, spec, {});
  ASSERT_EQ(r.spiral.size(), spec.spiral_rudders.size());
  for (const SpiralPoint& p : r.spiral) {
    if (std::abs(p.rudder) >= 10 * kDeg) {
      EXPECT_GT(p.rudder * p.rate_prime, 0.0) << "rudder " << p.rudder / kDeg;
    }
  }
  // Larger rudder, faster turn.
  EXPECT_GT(r.spiral[0].rate_prime, r.spiral[1].rate_prime);
}

TEST(SelfPropulsionTest, NoPositiveRootIsAModelError) {
  ShipParameters ship = testing::Kvlcc2();
  ship.hull.R0 = -0.01;  // a hull that pushes itself: no thrust needed
  EXPECT_THROW(SelfPropulsionRps(MmgModel<double>(ship), 1.0), ModelError);
}

}  // namespace
}  // namespace kelvin::sim
