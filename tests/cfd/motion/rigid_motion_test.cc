// Prescribed motions: rates are the exact derivatives of the pose, the laws
// after the ramp are those of the captive schema, and every bad key of the
// motion: section is one clear error.
#include "cfd/motion/rigid_motion.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

using ::testing::HasSubstr;
constexpr double kDeg = std::numbers::pi / 180.0;

MotionOptions Options(PrescribedMotion kind) {
  MotionOptions o;
  o.kind = kind;
  o.speed = 1.3;
  o.ramp_time = 2.0;
  o.period = 5.0;
  o.periods = 2;
  if (kind == PrescribedMotion::kStaticDrift || kind == PrescribedMotion::kYawDrift ||
      kind == PrescribedMotion::kCircularMotion) {
    o.drift_angle = 7.0 * kDeg;
  }
  o.sway_amplitude = kind == PrescribedMotion::kPureSway ? 0.2 : 0.0;
  o.yaw_amplitude = (kind == PrescribedMotion::kPureYaw || kind == PrescribedMotion::kYawDrift)
                        ? 8.0 * kDeg
                        : 0.0;
  o.yaw_rate = kind == PrescribedMotion::kCircularMotion ? 0.25 : 0.0;
  return o;
}

class EveryMotion : public ::testing::TestWithParam<PrescribedMotion> {};

TEST_P(EveryMotion, RatesAreTheDerivativesOfThePose) {
  const RigidMotion motion(Options(GetParam()));
  const double h = 1e-5;
  for (double t : {0.3, 1.0, 1.9, 2.5, 4.2, 9.7}) {
    const Pose p = motion.At(t), a = motion.At(t - h), b = motion.At(t + h);
    EXPECT_NEAR(p.dx0, (b.x0 - a.x0) / (2 * h), 1e-8) << "t = " << t;
    EXPECT_NEAR(p.dy0, (b.y0 - a.y0) / (2 * h), 1e-8) << "t = " << t;
    EXPECT_NEAR(p.r, (b.psi - a.psi) / (2 * h), 1e-8) << "t = " << t;
  }
  // At rest at t = 0 (smooth start).
  const Pose p0 = motion.At(0.0);
  EXPECT_EQ(p0.x0, 0.0);
  EXPECT_EQ(p0.dx0, 0.0);
  EXPECT_EQ(p0.y0, 0.0);
}

INSTANTIATE_TEST_SUITE_P(Kinds, EveryMotion,
                         ::testing::Values(PrescribedMotion::kStaticDrift,
                                           PrescribedMotion::kPureSway, PrescribedMotion::kPureYaw,
                                           PrescribedMotion::kYawDrift,
                                           PrescribedMotion::kCircularMotion));

TEST(RigidMotion, LawsAfterTheRamp) {
  const double t = 3.7;
  {
    const MotionOptions o = Options(PrescribedMotion::kStaticDrift);
    const Pose p = RigidMotion(o).At(t);
    EXPECT_DOUBLE_EQ(p.u(), o.speed * std::cos(o.drift_angle));
    EXPECT_DOUBLE_EQ(p.v(), -o.speed * std::sin(o.drift_angle));
    EXPECT_DOUBLE_EQ(p.x0, o.speed * (t - 0.5 * o.ramp_time));
  }
  {
    const MotionOptions o = Options(PrescribedMotion::kPureSway);
    const Pose p = RigidMotion(o).At(t);
    EXPECT_DOUBLE_EQ(p.y0, -o.sway_amplitude * std::sin(o.omega() * t));
    EXPECT_DOUBLE_EQ(p.v(), -o.sway_amplitude * o.omega() * std::cos(o.omega() * t));
    EXPECT_EQ(p.psi, 0.0);
  }
  {
    const MotionOptions o = Options(PrescribedMotion::kPureYaw);
    const Pose p = RigidMotion(o).At(t);
    const double w = o.omega();
    EXPECT_DOUBLE_EQ(p.psi, o.yaw_amplitude * std::cos(w * t));
    EXPECT_DOUBLE_EQ(p.y0, o.speed * o.yaw_amplitude / w * std::sin(w * t));
    EXPECT_DOUBLE_EQ(p.r, -o.yaw_amplitude * w * std::sin(w * t));
  }
  {
    const MotionOptions o = Options(PrescribedMotion::kCircularMotion);
    const RigidMotion m(o);
    for (double tt : {2.0, 5.0, 11.0}) {
      const Pose p = m.At(tt);
      EXPECT_NEAR(p.u(), o.speed * std::cos(o.drift_angle), 1e-14);
      EXPECT_NEAR(p.v(), -o.speed * std::sin(o.drift_angle), 1e-14);
      EXPECT_DOUBLE_EQ(p.r, o.yaw_rate);
      // On the circle of radius U / r around (0, U / r).
      const double R = o.speed / o.yaw_rate;
      EXPECT_NEAR(std::hypot(p.x0, p.y0 - R), R, 1e-12);
    }
  }
}

TEST(RigidMotion, EndTimeCountsWholePeriodsAfterTheRamp) {
  MotionOptions o = Options(PrescribedMotion::kPureSway);
  o.ramp_time = 5.0;  // exactly one period
  EXPECT_DOUBLE_EQ(o.EndTime(), 3 * 5.0);
  o.ramp_time = 5.5;
  EXPECT_DOUBLE_EQ(o.EndTime(), 4 * 5.0);
}

TEST(RigidMotion, PlacementMapsTheReferencePointToItsEarthPosition) {
  const MotionOptions o = Options(PrescribedMotion::kYawDrift);
  const Pose p = RigidMotion(o).At(3.3);
  const Eigen::Vector3d c(0.5, 0.1, -0.2);
  const Eigen::Vector3d earth = p.Rotation() * c + p.Translation(c);
  EXPECT_NEAR((earth - (c + Eigen::Vector3d(p.x0, -p.y0, 0.0))).norm(), 0.0, 1e-15);
  // The bow (body +x) turns to starboard (-y in the z-up grid) for psi > 0.
  EXPECT_GT(p.psi, 0.0);
  EXPECT_LT((p.Rotation() * Eigen::Vector3d::UnitX()).y(), 0.0);
}

struct BadMotion {
  std::string yaml;
  std::string message;
};

class BadMotionTest : public ::testing::TestWithParam<BadMotion> {};

TEST_P(BadMotionTest, IsOneClearError) {
  const auto root = data::ConfigNode::LoadString(GetParam().yaml, "case.yaml");
  try {
    LoadMotionOptions(root["motion"]);
    FAIL() << "accepted " << GetParam().yaml;
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("case.yaml"));
    EXPECT_THAT(e.what(), HasSubstr(GetParam().message));
  }
}

INSTANTIATE_TEST_SUITE_P(
    Inputs, BadMotionTest,
    ::testing::Values(
        BadMotion{"motion: {kind: zigzag, speed: 1}",
                  "key 'motion.kind' = 'zigzag': expected one of static_drift, pure_sway"},
        BadMotion{"motion: {kind: static_drift, speed: 1, sway_amplitude: 0.1}",
                  "unknown key 'motion.sway_amplitude'"},
        BadMotion{"motion: {kind: pure_sway, speed: -1, sway_amplitude: 0.1, period: 4}",
                  "motion.speed"},
        BadMotion{"motion: {kind: pure_sway, speed: 1, period: 4}", "motion.sway_amplitude"},
        BadMotion{"motion: {kind: pure_yaw, speed: 1, period: 4, yaw_amplitude_deg: 95}",
                  "motion.yaw_amplitude_deg = 95: expected an amplitude in (0, 90) degrees"},
        BadMotion{"motion: {kind: pure_yaw, speed: 1, period: 4, yaw_amplitude_deg: 5, periods: 0}",
                  "key 'motion.periods' = '0': expected a number of periods >= 1"},
        BadMotion{"motion: {kind: circular_motion, speed: 1, yaw_rate: 0}",
                  "motion.yaw_rate = 0: expected a finite non-zero yaw rate"},
        BadMotion{"motion: {kind: static_drift, speed: 1, drift_angle_deg: 91}",
                  "motion.drift_angle_deg = 91: expected |angle| < 90 degrees"},
        BadMotion{"motion: {kind: static_drift, speed: 1, centre: [0, 1]}", "motion.centre"}));

}  // namespace
}  // namespace kelvin::cfd
