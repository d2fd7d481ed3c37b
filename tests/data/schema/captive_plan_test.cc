// Campaign plans: bad sampling options and designs name the field, and the
// runs of a design are named and ramped as documented.
#include "data/schema/captive_plan.h"

#include <gtest/gtest.h>

#include <numbers>
#include <string>
#include <vector>

#include "data/schema/errors.h"

namespace kelvin::data {
namespace {

TEST(CaptivePlanTest, BadSamplingOptionsAndDesignsNameTheField) {
  VirtualCaptiveOptions o;
  o.samples_per_period = 4;
  try {
    o.Validate();
    FAIL();
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("'samples_per_period' = 4: expected at least 8"),
              std::string::npos);
  }
  CampaignDesign d = StandardDesign(1.0, true);
  d.sway_amplitudes = {0.1, -0.2};
  try {
    d.Validate();
    FAIL();
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("'sway_amplitudes' = -0.2"), std::string::npos)
        << e.what();
  }
  d = StandardDesign(0.0, true);
  try {
    d.Validate();
    FAIL();
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("'U' = 0"), std::string::npos) << e.what();
  }
}

// Run names and motions follow the design; t_ramp is ramp_periods periods for
// harmonic runs and steady_ramp for steady ones.
TEST(CaptivePlanTest, RunsAreNamedAndRampedFromTheDesign) {
  constexpr double kDeg = std::numbers::pi / 180.0;
  CampaignDesign d;
  d.U = 1.0;
  d.drift_angles = {5 * kDeg};
  d.sway_amplitudes = {0.1};
  d.yaw_amplitudes = {0.3};
  d.yaw_drift_angles = {-6 * kDeg};
  d.circular = {{0.0, 0.3}};
  VirtualCaptiveOptions o;
  o.ramp_periods = 2;
  o.steady_ramp = 3.0;
  const double Lpp = 2.0, omega = 3.0 * d.U / Lpp, T = 2 * std::numbers::pi / omega;
  const std::vector<PlannedRun> runs = PlanRuns(d, Lpp, o);
  ASSERT_EQ(runs.size(), 5u);
  const std::vector<std::string> names = {"drift_+5.0deg", "sway_v0.100", "yaw_r0.300",
                                          "yaw_drift_-6.0deg_r0.400", "circular_+0.0deg_r0.300"};
  for (std::size_t i = 0; i < runs.size(); ++i) {
    EXPECT_EQ(runs[i].name, names[i]);
    EXPECT_EQ(runs[i].motion.U, 1.0) << names[i];
  }
  EXPECT_EQ(runs[0].motion.kind, MotionKind::kStaticDrift);
  EXPECT_DOUBLE_EQ(runs[0].motion.beta, 5 * kDeg);
  EXPECT_EQ(runs[0].motion.t_ramp, 3.0);
  EXPECT_EQ(runs[1].motion.kind, MotionKind::kPureSway);
  EXPECT_DOUBLE_EQ(runs[1].motion.y_a, 0.1 * d.U / omega);
  EXPECT_DOUBLE_EQ(runs[1].motion.t_ramp, 2 * T);
  EXPECT_EQ(runs[2].motion.kind, MotionKind::kPureYaw);
  EXPECT_DOUBLE_EQ(runs[2].motion.psi_a, 0.1);
  EXPECT_EQ(runs[3].motion.kind, MotionKind::kYawDrift);
  EXPECT_DOUBLE_EQ(runs[3].motion.psi_a, 0.4 / 3.0);
  EXPECT_EQ(runs[4].motion.kind, MotionKind::kCircularMotion);
  EXPECT_EQ(runs[4].motion.r_prime, 0.3);
  EXPECT_EQ(runs[4].motion.t_ramp, 3.0);
}

TEST(CaptivePlanTest, SampleTimesOfHarmonicAndSteadyRuns) {
  const VirtualCaptiveOptions o;  // 200 samples per period, 1 + 5 periods; steady 5 + 20 s at 10 Hz
  MotionParameters sway{.kind = MotionKind::kPureSway, .U = 1.0, .y_a = 0.1, .omega = 0.5};
  const RunSampleTimes h = SampleTimes(sway, o);
  const double T = 2 * std::numbers::pi / 0.5;
  EXPECT_DOUBLE_EQ(h.t_ramp, T);
  EXPECT_DOUBLE_EQ(h.dt, T / 200);
  EXPECT_EQ(h.samples, 6u * 200u);
  const RunSampleTimes s = SampleTimes({.kind = MotionKind::kStaticDrift, .U = 1.0, .beta = 0.1}, o);
  EXPECT_EQ(s.t_ramp, 5.0);
  EXPECT_EQ(s.dt, 0.1);
  EXPECT_EQ(s.samples, 250u);
}

}  // namespace
}  // namespace kelvin::data
