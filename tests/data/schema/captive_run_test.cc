// Kinematics of the prescribed captive motions and the checks of a
// campaign's ship data and runs.
#include "data/schema/captive_run.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "data/schema/errors.h"
#include "tests/data/schema/captive_test_fixtures.h"

namespace kelvin::data {
namespace {

using fixtures::Kvlcc2Ship;


TEST(CaptiveRunTest, ClosedFormKinematics) {
  const double L = 7.0, t = 3.3;
  const MotionParameters sway = fixtures::SampleMotion(MotionKind::kPureSway);
  const BodyKinematics s = KinematicsAt(sway, L, t);
  EXPECT_DOUBLE_EQ(s.u, 1.2);
  EXPECT_NEAR(s.v, -0.3 * 0.6 * std::cos(0.6 * t), 1e-15);
  EXPECT_NEAR(s.dv, 0.3 * 0.36 * std::sin(0.6 * t), 1e-15);
  EXPECT_EQ(s.r, 0.0);
  const BodyKinematics y = KinematicsAt(fixtures::SampleMotion(MotionKind::kPureYaw), L, t);
  EXPECT_NEAR(y.r, -0.2 * 0.6 * std::sin(0.6 * t), 1e-15);
  EXPECT_NEAR(y.dr, -0.2 * 0.36 * std::cos(0.6 * t), 1e-15);
  // The PMM yaw law keeps the drift small: v = U (psi cos psi - sin psi) ~ -U psi^3 / 3.
  const double psi = 0.2 * std::cos(0.6 * t);
  EXPECT_NEAR(y.v, 1.2 * (psi * std::cos(psi) - std::sin(psi)), 1e-15);
  const BodyKinematics d = KinematicsAt(fixtures::SampleMotion(MotionKind::kStaticDrift), L, 10.0);
  EXPECT_NEAR(-std::atan(d.v / d.u), 0.15, 1e-15);  // beta = -atan(v/u) = psi
  EXPECT_NEAR(std::hypot(d.u, d.v), 1.2, 1e-15);
  EXPECT_EQ(KinematicsAt(fixtures::SampleMotion(MotionKind::kStaticDrift), L, 0.0).u, 0.0);  // ramp starts at rest
  const BodyKinematics c = KinematicsAt(fixtures::SampleMotion(MotionKind::kCircularMotion), L, t);
  EXPECT_NEAR(c.r * L / 1.2, 0.4, 1e-15);
  EXPECT_NEAR(-std::atan(c.v / c.u), 0.15, 1e-15);
  EXPECT_EQ(c.du, 0.0);
}

// The body accelerations must be the time derivatives of the body
// velocities (they include the r v and -r u transport terms).
TEST(CaptiveRunTest, AccelerationsAreDerivativesOfVelocities) {
  for (MotionKind kind : {MotionKind::kStaticDrift, MotionKind::kPureSway, MotionKind::kPureYaw,
                          MotionKind::kYawDrift}) {
    const MotionParameters m = fixtures::SampleMotion(kind);
    for (double t : {1.0, 2.7, 5.5, 9.1}) {
      const double h = 1e-5;
      const BodyKinematics a = KinematicsAt(m, 7.0, t - h), b = KinematicsAt(m, 7.0, t + h);
      const BodyKinematics k = KinematicsAt(m, 7.0, t);
      EXPECT_NEAR(k.du, (b.u - a.u) / (2 * h), 1e-8) << MotionKindName(kind) << " t " << t;
      EXPECT_NEAR(k.dv, (b.v - a.v) / (2 * h), 1e-8) << MotionKindName(kind) << " t " << t;
      EXPECT_NEAR(k.dr, (b.r - a.r) / (2 * h), 1e-8) << MotionKindName(kind) << " t " << t;
    }
  }
}

TEST(CaptiveRunTest, BadShipDataNamesTheAttribute) {
  CaptiveCampaign c;
  c.ship = Kvlcc2Ship();
  c.ship.I_zG = -1;
  try {
    ValidateCampaign(c, "c.h5");
    FAIL();
  } catch (const DataFileError& e) {
    EXPECT_NE(std::string(e.what()).find("c.h5: ship attribute 'I_zG' = -1"), std::string::npos)
        << e.what();
  }
  c.ship = Kvlcc2Ship();
  try {
    ValidateCampaign(c, "c.h5");
    FAIL();
  } catch (const DataFileError& e) {
    EXPECT_NE(std::string(e.what()).find("c.h5: the campaign holds no runs"), std::string::npos)
        << e.what();
  }
}

TEST(CaptiveRunTest, DuplicateRunNamesAreRejected) {
  CaptiveCampaign c;
  c.ship = Kvlcc2Ship();
  const CaptiveRun run = fixtures::SampledRun(c.ship, "sway", fixtures::SampleMotion(MotionKind::kPureSway));
  c.runs = {run, run};
  try {
    ValidateCampaign(c, "runs.csv");
    FAIL();
  } catch (const DataFileError& e) {
    EXPECT_NE(std::string(e.what()).find("runs.csv: run 'sway' appears twice (runs 0 and 1)"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace kelvin::data
