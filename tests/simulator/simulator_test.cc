// The SUNDIALS integrators against exact solutions: the linearized MMG model
// (an affine ODE, solved exactly by the matrix exponential), actuator kinks,
// heading events, and agreement of CVODE with the fixed-step ERK integrator on
// a 35 deg turning circle.
#include "simulator/integrators/simulator.h"

#include "data/schema/errors.h"

#include <gtest/gtest.h>

#include <unsupported/Eigen/MatrixFunctions>

#include "simulator/maneuvers/runner.h"
#include "tests/simulator/simulator_test_utilities.h"

namespace kelvin::sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

// Exact solution of z' = f0 + A z + B du (z = y - y0) from z(0) = z0, by the
// exponential of the augmented matrix [[A, c], [0, 0]].
StateVec ExactLinear(const LinearPlant& p, const StateVec& z0, double ddelta, double dn, double t) {
  Eigen::Matrix<double, 7, 7> M = Eigen::Matrix<double, 7, 7>::Zero();
  M.topLeftCorner<6, 6>() = p.A();
  M.topRightCorner<6, 1>() = p.f0() + p.B() * Eigen::Vector2d(ddelta, dn);
  Eigen::Matrix<double, 7, 1> z;
  z << z0, 1.0;
  const Eigen::Matrix<double, 7, 7> E = (M * t).exp();
  return (E * z).head<6>();
}

class LinearPlantTest : public ::testing::TestWithParam<SimulatorOptions::Method> {};

TEST_P(LinearPlantTest, MatchesMatrixExponentialTo1e8) {
  const ShipParameters ship = testing::Kvlcc2();
  const MmgModel<double> model(ship);
  const double U0 = ship.approach_speed;
  const double n0 = SelfPropulsionRps(model, U0);
  StateVec y0;
  y0 << 0, 0, 0, U0, 0, 0;
  const LinearPlant plant = LinearPlant::Linearize(model, y0, 0.0, n0);
  // f0 is the straight-running derivative: x' = U0, everything else 0.
  EXPECT_NEAR(plant.f0()[kX], U0, 1e-12);
  EXPECT_NEAR(plant.f0()[kU], 0.0, 1e-12);

  SimulatorOptions opt;
  opt.method = GetParam();
  opt.rtol = 1e-12;
  opt.atol = 1e-12;
  opt.fixed_step = 0.005;
  Simulator sim(std::make_unique<LinearPlant>(plant), opt);
  // Start off equilibrium (a sway and yaw disturbance) with 10 deg of rudder
  // held from t = 0, so the input is constant.
  const double delta = 10 * kDeg;
  StateVector start{0, 0, 0, U0, 0.01, -0.002};
  sim.Reset(0.0, start, delta, n0);
  const double L = ship.principal.Lpp;
  for (double t : {5.0, 20.0, 60.0}) {
    sim.Advance(t);
    StateVec z0;
    for (int i = 0; i < kStateSize; ++i) z0[i] = start[i] - y0[i];
    const StateVec exact = ExactLinear(plant, z0, delta, 0.0, t) + y0;
    const auto& y = sim.state();
    EXPECT_NEAR(y[kX] / L, exact[kX] / L, 1e-8) << "t = " << t;
    EXPECT_NEAR(y[kY] / L, exact[kY] / L, 1e-8) << "t = " << t;
    EXPECT_NEAR(y[kPsi], exact[kPsi], 1e-8) << "t = " << t;
    EXPECT_NEAR(y[kU] / U0, exact[kU] / U0, 1e-8) << "t = " << t;
    EXPECT_NEAR(y[kV] / U0, exact[kV] / U0, 1e-8) << "t = " << t;
    EXPECT_NEAR(y[kR] * L / U0, exact[kR] * L / U0, 1e-8) << "t = " << t;
  }
}

INSTANTIATE_TEST_SUITE_P(BothIntegrators, LinearPlantTest,
                         ::testing::Values(SimulatorOptions::Method::kAdaptive,
                                           SimulatorOptions::Method::kFixedStep),
                         [](const auto& param_info) {
                           return param_info.param == SimulatorOptions::Method::kAdaptive ? "Cvode" : "FixedStep";
                         });

TEST(SimulatorTest, RudderMovesAtItsRateAndCvodeStopsAtTheKink) {
  const ShipParameters ship = testing::Kvlcc2();
  const MmgModel<double> model(ship);
  Simulator sim(model, {});
  sim.Reset(0.0, {0, 0, 0, 1.179, 0, 0}, 0.0, 11.85);
  sim.SetRudderOrder(35 * kDeg);
  const double rate = ship.limits.rudder_rate;
  const double t_kink = 35 * kDeg / rate;
  sim.Advance(1.0);
  EXPECT_NEAR(sim.rudder(), rate * 1.0, 1e-15);
  sim.Advance(t_kink + 1.0);
  EXPECT_DOUBLE_EQ(sim.rudder(), 35 * kDeg);
  // Orders beyond the ship's limit are clamped.
  sim.SetRudderOrder(80 * kDeg);
  EXPECT_DOUBLE_EQ(sim.rudder_order(), ship.limits.rudder_max);
}

TEST(SimulatorTest, RpsOrderIsClampedToRpsMaxOnlyWhenTheShipGivesOne) {
  ShipParameters ship = testing::Kvlcc2();
  ASSERT_FALSE(ship.limits.rps_max.has_value());
  {
    const MmgModel<double> model(ship);
    Simulator sim(model, {});
    sim.Reset(0.0, {0, 0, 0, 1.179, 0, 0}, 0.0, 11.85);
    sim.SetRpsOrder(1e6);
    EXPECT_EQ(sim.rps_order(), 1e6);
    sim.SetRpsOrder(-5.0);  // no reverse thrust data: not below 0
    EXPECT_EQ(sim.rps_order(), 0.0);
  }
  ship.limits.rps_max = 15.0;
  ship.propeller.reverse_kt = std::array<double, 3>{-0.35, -0.3, 0.0};
  const MmgModel<double> model(ship);
  Simulator sim(model, {});
  sim.Reset(0.0, {0, 0, 0, 1.179, 0, 0}, 0.0, 11.85);
  sim.SetRpsOrder(20.0);
  EXPECT_EQ(sim.rps_order(), 15.0);
  sim.SetRpsOrder(-20.0);
  EXPECT_EQ(sim.rps_order(), -15.0);
}

TEST(SimulatorTest, HeadingEventIsLocatedByRootFinding) {
  const MmgModel<double> model(testing::Kvlcc2());
  Simulator sim(model, {});
  sim.Reset(0.0, {0, 0, 0, 1.179, 0, 0}, 0.0, 11.85);
  sim.SetRudderOrder(20 * kDeg);
  const bool hit = sim.Advance(100.0, 20 * kDeg);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(sim.state()[kPsi], 20 * kDeg, 1e-9);
  EXPECT_LT(sim.time(), 100.0);
}

TEST(SimulatorTest, CvodeAndFixedStepAgreeOnA35DegTurningCircle) {
  const ShipParameters ship = testing::Kvlcc2();
  const MmgModel<double> model(ship);
  const ManeuverSpec spec = ManeuverSpec::Parse("turning:35:stbd");
  RunOptions adaptive;
  adaptive.output_interval = 0.5;
  RunOptions fixed = adaptive;
  fixed.integrator.method = SimulatorOptions::Method::kFixedStep;
  fixed.integrator.fixed_step = 0.01;
  const ManeuverResult a = RunManeuver(model, spec, adaptive);
  const ManeuverResult b = RunManeuver(model, spec, fixed);
  const double L = ship.principal.Lpp;
  const double t_end = std::min(a.trajectory.samples().back().t, b.trajectory.samples().back().t);
  double max_err = 0;
  int compared = 0;
  for (const auto& s : b.trajectory.samples()) {
    if (s.t > t_end) break;
    const auto p = a.trajectory.At(s.t);
    max_err = std::max(max_err, std::hypot(p.x - s.x, p.y - s.y));
    ++compared;
  }
  EXPECT_GT(compared, 100);
  EXPECT_LT(max_err / L, 1e-4) << "max position difference " << max_err << " m over " << t_end << " s";
  EXPECT_NEAR(a.turning->tactical_diameter / L, b.turning->tactical_diameter / L, 1e-4);
}

TEST(SimulatorTest, FixedStepRejectsFractionalRuns) {
  const MmgModel<double> model(testing::Kvlcc2());
  SimulatorOptions opt;
  opt.method = SimulatorOptions::Method::kFixedStep;
  opt.fixed_step = 0.1;
  Simulator sim(model, opt);
  sim.Reset(0.0, {0, 0, 0, 1.179, 0, 0}, 0.0, 11.85);
  EXPECT_THROW(sim.Advance(0.25), ArgumentError);
  sim.Advance(0.3);
  EXPECT_NEAR(sim.time(), 0.3, 1e-12);
}

TEST(SimulatorTest, BadOptionsAreNamed) {
  SimulatorOptions opt;
  opt.fixed_step = -1;
  try {
    opt.Validate();
    FAIL();
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("step = -1 s"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace kelvin::sim
