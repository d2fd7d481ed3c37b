// Captive motions of a body in the CFD solver (issue 7), on a 2D block
// (length 1 m, beam 0.5 m) in a box at Re = U L / nu = 20, where the flow is
// steady and the runs take seconds:
//  - Galilean consistency (acceptance 2): the body towed through still water
//    on the moving mesh in the earth frame has the drag of the fixed-mesh run
//    with uniform inflow.
//  - Static drift symmetry (acceptance 3): Y and N antisymmetric, X symmetric
//    at +-beta.
//  - Pure sway and pure yaw (acceptance 4, first part): the forces repeat from
//    one period to the next once the ramp-up is over.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "cfd/run/run_case.h"
#include "cfd/motion/ship_forces.h"
#include "data/schema/config.h"

namespace kelvin::cfd {
namespace {

constexpr double kNu = 0.05;
constexpr double kRho = 1000.0;

// The box reaches 4 m ahead of the bow side of the block and 5.5 m behind
// it, 3 m to each side; cells of 0.125 m; the block spans x in [-0.5, 0.5],
// y in [-0.25, 0.25], so the grid is symmetric about the centreline y = 0.
const char* kMesh = R"(mesh:
  box: {min: [-6, -3, 0], max: [4, 3, 1], cells: [80, 48, 1], empty: z,
        obstacle: {min: [44, 22, 0], max: [52, 26, 1]}}
physics: {nu: 0.05, rho: 1000}
schemes: {time: backward, convection: linear_upwind}
solution:
  n_correctors: 2
  momentum: {solver: bicgstab, relative_tolerance: 1.0e-10, absolute_tolerance: 1.0e-14}
  pressure: {solver: pcg_amg, relative_tolerance: 1.0e-8, final_relative_tolerance: 1.0e-10}
output: {directory: out, vtu_interval: -1, checkpoint_interval: -1, forces: [obstacle]}
)";

// Body moving in still water; far field by the sign of the relative flux,
// switched smoothly over relative normal velocities of +-0.3 m/s (with the
// hard switch of inletOutlet/outletInlet the sides of a swaying domain flip
// faces between inflow and outflow and the PMM forces never become periodic:
// 5 % change per period after 8 periods, against 0.02 % with the band).
std::string MovingCase(const std::string& motion, const std::string& time) {
  return std::string(kMesh) + motion + time + R"(boundary:
  xmin: {U: {type: farField, inflow: [0, 0, 0], band: 0.3}, p: {type: farField, value: 0, band: 0.3}}
  xmax: {U: {type: farField, inflow: [0, 0, 0], band: 0.3}, p: {type: farField, value: 0, band: 0.3}}
  ymin: {U: {type: farField, inflow: [0, 0, 0], band: 0.3}, p: {type: farField, value: 0, band: 0.3}}
  ymax: {U: {type: farField, inflow: [0, 0, 0], band: 0.3}, p: {type: farField, value: 0, band: 0.3}}
  obstacle: {U: {type: movingWallVelocity}, p: {type: zeroGradient}}
)";
}

struct Sample {
  double t;
  PlanarLoad load;
};

// Runs a case and returns the ship-axis loads on the obstacle at every step.
std::vector<Sample> RunCaseText(const std::string& yaml,
                                const Vector3& initial_velocity = Vector3::Zero()) {
  const auto root = data::ConfigNode::LoadString(yaml, "captive_motion_test.yaml");
  Case c = LoadCase(root, ".");
  for (Vector3& u : c.solver->U().values()) u = initial_velocity;
  const std::vector<int> hull = {c.mesh->FindPatch("obstacle")};
  std::vector<Sample> out;
  const int steps = static_cast<int>(std::lround(c.settings.time.end / c.settings.time.dt));
  for (int i = 0; i < steps; ++i) {
    const StepSummary s = c.solver->Step(c.settings.time.dt);
    EXPECT_TRUE(s.finite);
    if (!s.finite) break;
    const Pose pose = c.motion ? c.motion->body().At(s.time) : Pose{};
    const Vector3 centre = c.motion ? c.motion->body().centre() : Vector3::Zero();
    out.push_back({s.time, ComputeHullLoads(*c.solver, hull, kRho, kNu, pose, centre).Total()});
  }
  return out;
}

// Relative change of a steady load over the last `window` samples.
double Unsteadiness(const std::vector<Sample>& s, int window, double PlanarLoad::*channel) {
  const double last = s.back().load.*channel;
  double worst = 0.0;
  for (std::size_t i = s.size() - window; i < s.size(); ++i)
    worst = std::max(worst, std::abs(s[i].load.*channel - last));
  return worst / std::abs(last);
}

TEST(CaptiveMotion, TowedInStillWaterEqualsUniformInflowOnAFixedMesh) {
  const std::string time = "time: {dt: 0.05, end: 25}\n";
  // Earth frame: the block moves at 1 m/s along +x from rest in still water.
  const auto moving =
      RunCaseText(MovingCase("motion: {kind: static_drift, speed: 1.0, ramp_time: 0}\n", time));
  // Body frame: the water comes at -1 m/s from the bow side (xmax); the same
  // water at rest in the earth frame is u = -1 m/s at the start.
  const auto fixed = RunCaseText(std::string(kMesh) + time + R"(boundary:
  xmax: {U: {type: fixedValue, value: [-1, 0, 0]}, p: {type: zeroGradient}}
  xmin: {U: {type: zeroGradient}, p: {type: fixedValue, value: 0}}
  ymin: {U: {type: farField, inflow: [-1, 0, 0], band: 0.3}, p: {type: farField, value: 0, band: 0.3}}
  ymax: {U: {type: farField, inflow: [-1, 0, 0], band: 0.3}, p: {type: farField, value: 0, band: 0.3}}
  obstacle: {U: {type: noSlip}, p: {type: zeroGradient}}
)",
                                 Vector3(-1, 0, 0));
  ASSERT_EQ(moving.size(), fixed.size());
  const double x_moving = moving.back().load.X, x_fixed = fixed.back().load.X;
  const double rel = std::abs(x_moving - x_fixed) / std::abs(x_fixed);
  const double steady = Unsteadiness(fixed, 40, &PlanarLoad::X);
  std::printf(
      "steady drag: moving mesh %.10g N, fixed mesh %.10g N, relative difference %.3g; C_D = %.4f; "
      "change over the last 2 s %.2g\n",
      x_moving, x_fixed, rel, -x_fixed / (0.5 * kRho * 0.5 * 1.0), steady);
  EXPECT_LT(x_fixed, 0.0);  // resistance: the force on the body points aft
  EXPECT_LT(steady, 2e-3);  // steady
  EXPECT_LT(rel, 0.002);    // acceptance: within 0.2 %
  // The drift-free run has no side force or yaw moment.
  EXPECT_LT(std::abs(moving.back().load.Y), 1e-6 * std::abs(x_moving));
}

TEST(CaptiveMotion, StaticDriftIsSymmetric) {
  const std::string time = "time: {dt: 0.05, end: 20}\n";
  auto drift = [&](double deg) {
    return RunCaseText(
        MovingCase("motion: {kind: static_drift, speed: 1.0, ramp_time: 2.0, drift_angle_deg: " +
                       std::to_string(deg) + "}\n",
                   time));
  };
  const auto plus = drift(10.0), minus = drift(-10.0);
  const PlanarLoad p = plus.back().load, m = minus.back().load;
  const double dy = std::abs(p.Y + m.Y) / std::max(std::abs(p.Y), std::abs(m.Y));
  const double dn = std::abs(p.N + m.N) / std::max(std::abs(p.N), std::abs(m.N));
  const double dx = std::abs(p.X - m.X) / std::max(std::abs(p.X), std::abs(m.X));
  std::printf("drift +10: X %.6g Y %.6g N %.6g;  drift -10: X %.6g Y %.6g N %.6g\n", p.X, p.Y, p.N,
              m.X, m.Y, m.N);
  std::printf("asymmetry: Y %.3g, N %.3g, X %.3g; unsteadiness of Y %.2g\n", dy, dn, dx,
              Unsteadiness(plus, 40, &PlanarLoad::Y));
  EXPECT_LT(Unsteadiness(plus, 40, &PlanarLoad::Y), 1e-3);
  EXPECT_LT(dy, 0.01);
  EXPECT_LT(dn, 0.01);
  EXPECT_LT(dx, 0.01);
  // Physical signs (ship axes, beta = -atan(v/u) > 0 means v < 0: the body
  // slides to port): the side force resists the sliding (Y > 0, Y'_v < 0) and
  // the Munk moment turns the bow further away from the path (N > 0, N'_v < 0).
  EXPECT_GT(p.Y, 0.05 * std::abs(p.X));
  EXPECT_GT(p.N, 0.0);
}

// Largest change of the loads between the last two periods, relative to the
// range of each channel.
double PeriodChange(const std::vector<Sample>& s, int steps_per_period,
                    double PlanarLoad::*channel) {
  const std::size_t n = s.size();
  double lo = 1e300, hi = -1e300, change = 0.0;
  for (std::size_t i = n - steps_per_period; i < n; ++i) {
    const double now = s[i].load.*channel, before = s[i - steps_per_period].load.*channel;
    lo = std::min(lo, now);
    hi = std::max(hi, now);
    change = std::max(change, std::abs(now - before));
  }
  return change / (hi - lo);
}

TEST(CaptiveMotion, PureSwayAndPureYawArePeriodicAfterTheRamp) {
  // Period 4 s (omega' = omega L / U = 1.57), 80 steps per period, one period
  // of ramp-up then four (sway) or six (yaw) periods: the start-up transient
  // decays by a factor of about 2.5 (sway) and 2 (yaw) per period.
  const std::string time = "time: {dt: 0.05}\n";
  const auto sway =
      RunCaseText(MovingCase("motion: {kind: pure_sway, speed: 1.0, sway_amplitude: 0.1, period: "
                             "4.0, ramp_time: 4.0, periods: 4}\n",
                             time));
  const auto yaw =
      RunCaseText(MovingCase("motion: {kind: pure_yaw, speed: 1.0, yaw_amplitude_deg: 5, period: "
                             "4.0, ramp_time: 4.0, periods: 6}\n",
                             time));
  ASSERT_EQ(sway.size(), 400u);
  const double sway_y = PeriodChange(sway, 80, &PlanarLoad::Y),
               sway_n = PeriodChange(sway, 80, &PlanarLoad::N);
  const double yaw_y = PeriodChange(yaw, 80, &PlanarLoad::Y),
               yaw_n = PeriodChange(yaw, 80, &PlanarLoad::N);
  std::printf("period-to-period change (of the range): sway Y %.3g N %.3g; yaw Y %.3g N %.3g\n",
              sway_y, sway_n, yaw_y, yaw_n);
  EXPECT_LT(sway_y, 0.01);
  EXPECT_LT(sway_n, 0.01);
  EXPECT_LT(yaw_y, 0.01);
  EXPECT_LT(yaw_n, 0.01);
}

}  // namespace
}  // namespace kelvin::cfd
