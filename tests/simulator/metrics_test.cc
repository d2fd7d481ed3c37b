// Metric extraction on synthetic trajectories with known answers: a steady
// circle (advance = transfer = R, tactical and steady diameter 2R) and a
// sinusoidal heading history (overshoot = amplitude - trigger angle).
#include "simulator/maneuvers/metrics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kelvin::sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

Trajectory Circle(double R, double omega, int side, double dt, double t_end) {
  Trajectory traj;
  for (double t = 0; t <= t_end + 1e-12; t += dt) {
    const double a = omega * t;
    traj.Add({t, R * std::sin(a), side * R * (1 - std::cos(a)), side * a, R * omega, 0.0, side * omega, side * 0.6,
              10.0},
             1);
  }
  return traj;
}

TEST(MetricsTest, SteadyCircleStarboard) {
  const double R = 100.0, omega = 0.02;
  const Trajectory traj = Circle(R, omega, +1, 1.0, 3.2 * M_PI / omega);
  const TurningMetrics m = ComputeTurning(traj, 0.0, 0.0, +1);
  EXPECT_NEAR(m.advance, R, 1e-6 * R);
  EXPECT_NEAR(m.transfer, R, 1e-6 * R);
  EXPECT_NEAR(m.tactical_diameter, 2 * R, 1e-6 * R);
  EXPECT_NEAR(m.steady_diameter, 2 * R, 1e-6 * R);
  EXPECT_NEAR(m.time_to_90, M_PI / 2 / omega, 1e-6);
  EXPECT_NEAR(m.time_to_180, M_PI / omega, 1e-6);
  EXPECT_NEAR(m.steady_rate, omega, 1e-12);
  EXPECT_NEAR(m.steady_speed, R * omega, 1e-12);
}

TEST(MetricsTest, SteadyCirclePortGivesPositiveDistances) {
  const double R = 40.0, omega = 0.05;
  const Trajectory traj = Circle(R, omega, -1, 0.5, 3.2 * M_PI / omega);
  const TurningMetrics m = ComputeTurning(traj, 0.0, 0.0, -1);
  EXPECT_NEAR(m.advance, R, 1e-6 * R);
  EXPECT_NEAR(m.transfer, R, 1e-6 * R);
  EXPECT_NEAR(m.tactical_diameter, 2 * R, 1e-6 * R);
}

TEST(MetricsTest, SinusoidalZigZag) {
  // psi = A sin(w t): rudder reversals where |psi| reaches the trigger h,
  // extrema at w t = pi/2 and 3 pi/2, so both overshoots are A - h and the
  // period between the first and third reversal is 2 pi / w.
  const double A = 15 * kDeg, h = 10 * kDeg, w = 0.1, U = 2.0;
  Trajectory traj;
  double x = 0, y = 0;
  const double dt = 0.05;
  for (double t = 0; t <= 50.0; t += dt) {
    const double psi = A * std::sin(w * t);
    traj.Add({t, x, y, psi, U, 0.0, A * w * std::cos(w * t), 0.0, 10.0}, 1);
    // Positions consistent with the velocities: fine midpoint sub-steps.
    const int sub = 200;
    for (int k = 0; k < sub; ++k) {
      const double tm = t + (k + 0.5) * dt / sub;
      x += U * std::cos(A * std::sin(w * tm)) * dt / sub;
      y += U * std::sin(A * std::sin(w * tm)) * dt / sub;
    }
  }
  const double s = std::asin(h / A) / w;
  const std::vector<double> executes = {0.0, s, M_PI / w + s, 2 * M_PI / w + s, 3 * M_PI / w + s};
  const ZigZagMetrics z = ComputeZigZag(traj, executes, 0.0, h, +1);
  EXPECT_NEAR(z.first_overshoot, A - h, 1e-6);
  EXPECT_NEAR(z.second_overshoot, A - h, 1e-6);
  EXPECT_NEAR(z.first_overshoot_time, M_PI / 2 / w, 1e-3);
  EXPECT_NEAR(z.second_overshoot_time, 1.5 * M_PI / w, 1e-3);
  EXPECT_NEAR(z.period, 2 * M_PI / w, 1e-12);
  EXPECT_NEAR(z.time_to_first_reversal, s, 1e-12);
  EXPECT_NEAR(z.reach_at_10deg, U * std::asin(10 * kDeg / A) / w, 1e-6);
}

TEST(MetricsTest, ZigZagOvershootIsTheHeadingBeyondTheTriggerOnEitherSide) {
  // From psi0 = 1 rad with a 20 deg trigger: 25 deg to starboard and 25 deg
  // to port are both 5 deg overshoots; an extremum short of the trigger is negative.
  EXPECT_NEAR(ZigZagOvershoot(1.0 + 25 * kDeg, 1.0, 20 * kDeg, +1), 5 * kDeg, 1e-15);
  EXPECT_NEAR(ZigZagOvershoot(1.0 - 25 * kDeg, 1.0, 20 * kDeg, -1), 5 * kDeg, 1e-15);
  EXPECT_NEAR(ZigZagOvershoot(1.0 + 15 * kDeg, 1.0, 20 * kDeg, +1), -5 * kDeg, 1e-15);
}

TEST(MetricsTest, StoppingOnUniformDeceleration) {
  // u = U0 - a t on a straight course: stops at U0/a after U0^2 / (2a).
  const double U0 = 3.0, a = 0.05;
  Trajectory traj;
  for (double t = 0; t <= 70.0; t += 0.5) {
    const double u = U0 - a * t;
    traj.Add({t, U0 * t - 0.5 * a * t * t, 0.0, 0.0, u, 0.0, 0.0, 0.0, -5.0}, 1);
  }
  const StoppingMetrics m = ComputeStopping(traj, 0.0, 0.0);
  EXPECT_NEAR(m.time_to_stop, U0 / a, 1e-9);
  EXPECT_NEAR(m.head_reach, U0 * U0 / (2 * a), 1e-6);
  EXPECT_NEAR(m.track_reach, U0 * U0 / (2 * a), 1e-6);
  EXPECT_NEAR(m.lateral_deviation, 0.0, 1e-12);
}

TEST(MetricsTest, ImoZigZagLimitsFollowLoverV) {
  // MSC.137(76) 5.4.2: 10 deg below L/V 10 s, 20 deg from 30 s, 5 + L/(2V) between.
  EXPECT_DOUBLE_EQ(ImoZigZag10FirstOvershootLimitDeg(8), 10);
  EXPECT_DOUBLE_EQ(ImoZigZag10FirstOvershootLimitDeg(20), 15);
  EXPECT_DOUBLE_EQ(ImoZigZag10FirstOvershootLimitDeg(40), 20);
  EXPECT_DOUBLE_EQ(ImoZigZag10SecondOvershootLimitDeg(8), 25);
  EXPECT_DOUBLE_EQ(ImoZigZag10SecondOvershootLimitDeg(20), 32.5);
  EXPECT_DOUBLE_EQ(ImoZigZag10SecondOvershootLimitDeg(30), 40);
}

}  // namespace
}  // namespace kelvin::sim
