// The bridge on memq:// (in-process LCM): a scripted zig-zag streamed at
// speedup 100 reproduces the fast-time fixed-step run (`kelvin simulate
// --integrator fixed`) at every publish instant, its events match the
// fast-time metrics, helm orders drive the rudder at its rate limit, and
// every bad option gives its one message.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sched.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>

#include "bridge/bridge.h"
#include "bridge/listener.h"
#include "bridge/pacer.h"
#include "data/schema/errors.h"
#include "data/schema/h5_file.h"
#include "simulator/maneuvers/runner.h"
#include "simulator/mmg/ship_parameters.h"
#include "tests/test_utilities/test_utilities.h"
#include "tests/simulator/simulator_test_utilities.h"

namespace kelvin::bridge {
namespace {

using ::testing::HasSubstr;
constexpr double kDeg = M_PI / 180.0;

using sim::testing::Kvlcc2;

// Delivers what the bridge published after its last drain.
void Flush(lcm::LCM& lcm) {
  while (lcm.handleTimeout(0) > 0) {
  }
}

double AngleDiff(double a, double b) { return std::remainder(a - b, 2.0 * M_PI); }

std::string Sci(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.3e", v);
  return buf;
}

struct ZigZagRun {
  BridgeSummary summary;
  std::vector<kelvin::ship_state_t> states;
  std::vector<kelvin::maneuver_event_t> events;
  double step = 0;
};

ZigZagRun StreamZigZag() {
  lcm::LCM lcm("memq://");
  BridgeOptions o;
  o.rate = 20;
  o.speedup = 100;
  o.script = "zigzag:20/20:stbd";
  Bridge bridge(Kvlcc2(), o, lcm);
  Listener listener(lcm, "KELVIN");
  ZigZagRun run;
  run.summary = bridge.Run();
  Flush(lcm);
  EXPECT_EQ(listener.malformed(), 0);
  EXPECT_EQ(listener.out_of_sequence(), 0);
  run.states = listener.states();
  run.events = listener.events();
  run.step = bridge.step();
  return run;
}

TEST(BridgeMemq, ZigZagAtSpeedup100EqualsFastTimeFixedStepRun) {
  const ZigZagRun run = StreamZigZag();
  ASSERT_EQ(run.summary.status, BridgeStatus::kCompleted);
  EXPECT_EQ(run.step, 0.025);  // 1/20 s in two steps of at most Lpp/U0/200 = 0.0297 s

  const sim::ShipParameters ship = Kvlcc2();
  const sim::MmgModel<double> model(ship);
  sim::RunOptions ro;
  ro.integrator.method = sim::SimulatorOptions::Method::kFixedStep;
  ro.integrator.fixed_step = run.step;
  ro.output_interval = 1.0 / 20.0;
  const sim::ManeuverResult ref = sim::RunManeuver(model, sim::ManeuverSpec::Parse("zigzag:20/20:stbd"), ro);

  ASSERT_EQ(run.states.size(), ref.trajectory.size());
  ASSERT_GT(run.states.size(), 1000u);
  double worst = 0;
  for (std::size_t i = 0; i < run.states.size(); ++i) {
    const auto& s = run.states[i];
    const auto& r = ref.trajectory[i];
    const double d[] = {s.t - r.t,     s.x - r.x,     s.y - r.y, AngleDiff(s.heading, r.psi), s.u - r.u,
                        s.v - r.v,     s.r - r.r,     s.rudder_angle - r.delta,
                        s.propeller_rps - r.n};
    for (double e : d) worst = std::max(worst, std::abs(e));
    ASSERT_EQ(s.seq, static_cast<std::int64_t>(i));
    ASSERT_EQ(s.maneuver_phase, ref.trajectory.phases()[i]) << "sample " << i;
  }
  EXPECT_LE(worst, 1e-9);
  RecordProperty("max_abs_difference", Sci(worst));
}

TEST(BridgeMemq, ZigZagEqualsKelvinSimulateOutputFile) {
  const testing::ScopedTempDir dir;
  const auto res = testing::RunCommand((testing::ToolsDir() / "kelvin").string() + " simulate " +
                                       (testing::SourceDir() / "data/ships/kvlcc2.yaml").string() +
                                       " -m zigzag:20/20:stbd --integrator fixed --step 0.025 --output-interval 0.05 "
                                       "-o " + dir.path().string());
  ASSERT_EQ(res.exit_code, 0) << res.output;
  std::filesystem::path file;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) file = e.path();
  const data::H5Reader h5(file);
  const auto t = h5.Read("trajectory/time"), x = h5.Read("trajectory/x"), y = h5.Read("trajectory/y"),
             psi = h5.Read("trajectory/psi"), u = h5.Read("trajectory/u"), v = h5.Read("trajectory/v"),
             r = h5.Read("trajectory/r"), rudder = h5.Read("trajectory/rudder"), rps = h5.Read("trajectory/rps");

  const ZigZagRun run = StreamZigZag();
  ASSERT_EQ(run.states.size(), t.rows);
  double worst = 0;
  for (std::size_t i = 0; i < t.rows; ++i) {
    const auto& s = run.states[i];
    const double d[] = {s.t - t.at(i),        s.x - x.at(i), s.y - y.at(i), AngleDiff(s.heading, psi.at(i)),
                        s.u - u.at(i),        s.v - v.at(i), s.r - r.at(i), s.rudder_angle - rudder.at(i),
                        s.propeller_rps - rps.at(i)};
    for (double e : d) worst = std::max(worst, std::abs(e));
  }
  EXPECT_LE(worst, 1e-9);
}

TEST(BridgeMemq, ZigZagEventsMatchFastTimeMetrics) {
  const ZigZagRun run = StreamZigZag();
  const sim::MmgModel<double> model(Kvlcc2());
  sim::RunOptions ro;
  ro.integrator.method = sim::SimulatorOptions::Method::kFixedStep;
  ro.integrator.fixed_step = run.step;
  ro.output_interval = run.step;  // every step: the reference interpolates the same samples
  const sim::ManeuverResult ref = sim::RunManeuver(model, sim::ManeuverSpec::Parse("zigzag:20/20:stbd"), ro);
  ASSERT_TRUE(ref.zigzag.has_value());
  ASSERT_EQ(ref.execute_times.size(), 5u);  // start + 4 reversals

  std::vector<kelvin::maneuver_event_t> executes, overshoots, stops, starts;
  for (const auto& e : run.events) {
    if (e.kind == kelvin::maneuver_event_t::START) starts.push_back(e);
    if (e.kind == kelvin::maneuver_event_t::EXECUTE) executes.push_back(e);
    if (e.kind == kelvin::maneuver_event_t::OVERSHOOT) overshoots.push_back(e);
    if (e.kind == kelvin::maneuver_event_t::STOP) stops.push_back(e);
  }
  ASSERT_EQ(starts.size(), 1u);
  ASSERT_EQ(executes.size(), 4u);
  ASSERT_EQ(stops.size(), 1u);
  ASSERT_GE(overshoots.size(), 3u);  // after reversals 1, 2, 3 (the run stops at the 4th)
  EXPECT_EQ(run.events.front().kind, kelvin::maneuver_event_t::START);
  EXPECT_EQ(run.events.back().kind, kelvin::maneuver_event_t::STOP);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(executes[i].t, ref.execute_times[i + 1], 1e-12);
    EXPECT_EQ(executes[i].index, static_cast<int>(i + 1));
    EXPECT_NEAR(std::abs(executes[i].rudder_order), 20 * kDeg, 1e-15);
  }
  const auto& stop = stops[0];
  EXPECT_NEAR(stop.period, ref.zigzag->period, 1e-12);
  EXPECT_NEAR(overshoots[0].overshoot, stop.first_overshoot, 0.0);
  EXPECT_NEAR(overshoots[1].overshoot, stop.second_overshoot, 0.0);
  // The bridge takes the heading extremum where the yaw rate, linear within
  // one 0.025 s step, vanishes; the reference interpolates the same samples
  // with cubic Hermite polynomials. Both are O(h^3) in the heading, far
  // below 1e-8 rad here (measured: 3e-10 and 1.4e-10 rad).
  EXPECT_NEAR(stop.first_overshoot, ref.zigzag->first_overshoot, 1e-8);
  EXPECT_NEAR(stop.second_overshoot, ref.zigzag->second_overshoot, 1e-8);
  EXPECT_NEAR(stop.first_overshoot_time, ref.zigzag->first_overshoot_time, 1e-3);
  EXPECT_NEAR(stop.second_overshoot_time, ref.zigzag->second_overshoot_time, 1e-3);
  RecordProperty("first_overshoot_deg", Sci(stop.first_overshoot / kDeg));
  RecordProperty("first_overshoot_diff_rad", Sci(stop.first_overshoot - ref.zigzag->first_overshoot));
  RecordProperty("second_overshoot_diff_rad", Sci(stop.second_overshoot - ref.zigzag->second_overshoot));
}

TEST(BridgeMemq, HelmOrderMovesTheRudderAtItsRateLimit) {
  const sim::ShipParameters ship = Kvlcc2();
  lcm::LCM lcm("memq://");
  BridgeOptions o;
  o.rate = 20;
  o.speedup = 100;
  o.duration = 2.0;
  o.helm.sources = {7};
  Bridge bridge(ship, o, lcm);
  Listener listener(lcm, "KELVIN");
  kelvin::helm_command_t cmd{};
  cmd.utime = RealtimeMicroseconds();
  cmd.source_id = 7;
  cmd.rudder_order = 10 * kDeg;
  cmd.rps_order = bridge.approach_rps();
  lcm.publish(bridge.helm_channel(), &cmd);
  const BridgeSummary s = bridge.Run();
  Flush(lcm);
  EXPECT_EQ(s.helm.received, 1);
  EXPECT_EQ(s.helm.accepted, 1);
  ASSERT_EQ(listener.states().size(), 41u);  // t = 0, 0.05, ..., 2.0
  const double rate = ship.limits.rudder_rate;
  for (const auto& st : listener.states()) {
    EXPECT_EQ(st.maneuver_phase, kelvin::ship_state_t::PHASE_FREE);
    if (st.seq == 0) continue;  // published before the order was read
    EXPECT_DOUBLE_EQ(st.rudder_order, 10 * kDeg);
    EXPECT_NEAR(st.rudder_angle, std::min(10 * kDeg, rate * st.t), 1e-12) << "t = " << st.t;
  }
  // The ship answers a starboard rudder by turning to starboard.
  EXPECT_GT(listener.states().back().r, 0.0);
}

TEST(BridgeMemq, HelmOrdersAreIgnoredWhileAScriptSteers) {
  lcm::LCM lcm("memq://");
  BridgeOptions o;
  o.speedup = 100;
  o.duration = 1.0;
  o.script = "turning:35:port";
  Bridge bridge(Kvlcc2(), o, lcm);
  Listener listener(lcm, "KELVIN");
  kelvin::helm_command_t cmd{};
  cmd.utime = RealtimeMicroseconds();
  cmd.rudder_order = 10 * kDeg;
  cmd.rps_order = bridge.approach_rps();
  lcm.publish(bridge.helm_channel(), &cmd);
  const BridgeSummary s = bridge.Run();
  Flush(lcm);
  EXPECT_EQ(s.helm.accepted, 1);
  EXPECT_EQ(s.helm_ignored_scripted, 1);
  EXPECT_DOUBLE_EQ(listener.states().back().rudder_order, -35 * kDeg);
  // The run ends before the turning circle does: START, then STOP at 1 s.
  ASSERT_EQ(listener.events().size(), 2u);
  EXPECT_EQ(listener.events()[0].kind, kelvin::maneuver_event_t::START);
  EXPECT_EQ(listener.events()[1].kind, kelvin::maneuver_event_t::STOP);
  EXPECT_DOUBLE_EQ(listener.events()[1].t, 1.0);
  EXPECT_TRUE(std::isnan(listener.events()[1].first_overshoot));
}

// The loop runs with SCHED_FIFO while Run() lasts (observed from a
// subscriber callback, which runs on the bridge's thread) and the thread's
// scheduling is restored afterwards.
int g_policy_in_callback = -1;
void RecordPolicy(const lcm_recv_buf_t*, const char*, void*) { g_policy_in_callback = sched_getscheduler(0); }

TEST(BridgeMemq, RealtimePriorityHoldsForTheRunOnly) {
  lcm::LCM lcm("memq://");
  BridgeOptions o;
  o.speedup = 100;
  o.duration = 0.5;
  o.realtime_priority = 10;
  Bridge bridge(Kvlcc2(), o, lcm);
  lcm_subscribe(lcm.getUnderlyingLCM(), bridge.state_channel().c_str(), &RecordPolicy, nullptr);
  const int before = sched_getscheduler(0);
  const BridgeSummary s = bridge.Run();
  if (!s.realtime) GTEST_SKIP() << "no permission for SCHED_FIFO (needs root or CAP_SYS_NICE)";
  EXPECT_EQ(g_policy_in_callback, SCHED_FIFO);
  EXPECT_EQ(sched_getscheduler(0), before);
}

TEST(BridgeMemq, ChannelPrefixNamesTheChannels) {
  lcm::LCM lcm("memq://");
  BridgeOptions o;
  o.channel_prefix = "SIM_2";
  o.speedup = 100;
  o.duration = 0.5;
  Bridge bridge(Kvlcc2(), o, lcm);
  EXPECT_EQ(bridge.state_channel(), "SIM_2_STATE");
  EXPECT_EQ(bridge.helm_channel(), "SIM_2_HELM");
  EXPECT_EQ(bridge.event_channel(), "SIM_2_EVENT");
  Listener listener(lcm, "SIM_2");
  Listener other(lcm, "KELVIN");
  bridge.Run();
  Flush(lcm);
  EXPECT_EQ(listener.states().size(), 11u);
  EXPECT_TRUE(other.states().empty());
}

TEST(BridgeMemq, StateFieldsAreConsistent) {
  lcm::LCM lcm("memq://");
  BridgeOptions o;
  o.speedup = 100;
  o.script = "turning:35:stbd";
  o.duration = 60;
  o.origin = {10.0, -20.0};
  Bridge bridge(Kvlcc2(), o, lcm);
  Listener listener(lcm, "KELVIN");
  bridge.Run();
  Flush(lcm);
  const LocalOrigin origin({10.0, -20.0});
  for (const auto& s : listener.states()) {
    const GeoPoint p = origin.ToGeodetic(s.x, s.y);
    EXPECT_DOUBLE_EQ(s.latitude, p.latitude);
    EXPECT_DOUBLE_EQ(s.longitude, p.longitude);
    EXPECT_NEAR(s.speed_over_ground, std::hypot(s.u, s.v), 1e-15);
    EXPECT_NEAR(s.drift_angle, std::atan2(-s.v, s.u), 1e-15);
    // Course = heading - drift angle (beta = atan2(-v, u)).
    EXPECT_NEAR(AngleDiff(s.course_over_ground, s.heading - s.drift_angle), 0.0, 1e-12);
    EXPECT_GE(s.heading, 0.0);
    EXPECT_LT(s.heading, 2 * M_PI);
  }
  // In a starboard turn the drift angle is positive (bow inside the turn).
  EXPECT_GT(listener.states().back().drift_angle, 0.0);
}

// --- Bad options: one clear message each --------------------------------

std::string OptionError(const BridgeOptions& o) {
  try {
    o.Validate();
  } catch (const ArgumentError& e) {
    return e.what();
  }
  return "no error";
}

TEST(BridgeOptions, EachBadOptionHasOneClearMessage) {
  BridgeOptions o;
  EXPECT_EQ(OptionError(o), "no error");
  o = {};
  o.rate = 0;
  EXPECT_EQ(OptionError(o), "--rate 0: expected a state rate between 0 and 1000 Hz");
  o = {};
  o.rate = std::nan("");
  EXPECT_EQ(OptionError(o), "--rate nan: expected a state rate between 0 and 1000 Hz");
  o = {};
  o.speedup = -1;
  EXPECT_EQ(OptionError(o), "--speedup -1: expected a factor between 0 and 10000 (1 = real time)");
  o = {};
  o.rate = 1000;
  o.speedup = 1000;
  EXPECT_EQ(OptionError(o), "--rate x --speedup 1000000: expected at most 100000 state messages per wall-clock second");
  o = {};
  o.duration = -2;
  EXPECT_EQ(OptionError(o), "--duration -2: expected a simulation time >= 0 s (0 = until the script ends)");
  o = {};
  o.step = -0.1;
  EXPECT_EQ(OptionError(o), "--step -0.1: expected an integrator step >= 0 s (0 = automatic)");
  o = {};
  o.approach_speed = -1;
  EXPECT_EQ(OptionError(o), "--speed -1: expected an approach speed >= 0 m/s (0 = the ship file's)");
  o = {};
  o.channel_prefix = "kelvin";
  EXPECT_EQ(OptionError(o), "--channel-prefix 'kelvin': expected an UPPER_SNAKE name such as KELVIN or SIM_2");
  o = {};
  o.channel_prefix = "A.*";
  EXPECT_EQ(OptionError(o), "--channel-prefix 'A.*': expected an UPPER_SNAKE name such as KELVIN or SIM_2");
  o = {};
  o.nmea_rate = 20;
  EXPECT_EQ(OptionError(o), "--nmea-rate 20: expected an NMEA rate between 1 and 10 Hz");
  o = {};
  o.helm.stale_timeout = 0;
  EXPECT_EQ(OptionError(o), "--stale-timeout 0: expected a positive time in s");
  o = {};
  o.realtime_priority = 100;
  EXPECT_EQ(OptionError(o),
            "--realtime-priority 100: expected a SCHED_FIFO priority between 1 and 99 (0 = normal scheduling)");
  o = {};
  o.helm.future_tolerance = -1;
  EXPECT_EQ(OptionError(o), "helm option future_tolerance = -1: expected a non-negative time in s");
}

std::string ConstructionError(const BridgeOptions& o) {
  lcm::LCM lcm("memq://");
  try {
    Bridge bridge(Kvlcc2(), o, lcm);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(BridgeOptions, StepMustDivideTheStatePeriod) {
  BridgeOptions o;
  o.step = 0.03;
  EXPECT_EQ(ConstructionError(o), "--step 0.03 s: expected a step that divides the state period 1/rate = 0.05 s");
  o.step = 0.01;
  EXPECT_EQ(ConstructionError(o), "no error");
}

TEST(BridgeOptions, BadScriptNamesTheAcceptedForms) {
  BridgeOptions o;
  o.script = "zigzag:20";
  EXPECT_THAT(ConstructionError(o), HasSubstr("zigzag:20"));
  o.script = "zigzag:40/20:stbd";
  EXPECT_THAT(ConstructionError(o), HasSubstr("exceeds the maximum"));
}

TEST(BridgeOptions, OriginMustBeAwayFromThePoles) {
  BridgeOptions o;
  o.origin = {89.5, 0};
  EXPECT_EQ(ConstructionError(o), "origin latitude 89.5 deg: expected a latitude between -89 and 89 deg");
  o.origin = {0, 200};
  EXPECT_EQ(ConstructionError(o), "origin longitude 200 deg: expected a longitude between -180 and 180 deg");
}

TEST(Pacer, DeadlinesAreAbsoluteAndDoNotAccumulateRoundOff) {
  // A period that is not a whole number of nanoseconds: adding it up would
  // drift by the rounding every tick; the pacer multiplies from the anchor.
  const double period = 1.0 / 3000.0;
  Pacer pacer(period, 10.0);
  pacer.Start();
  const std::int64_t anchor = pacer.deadline();
  for (int k = 1; k <= 300; ++k) {
    pacer.WaitNext();
    ASSERT_EQ(pacer.deadline() - anchor, std::llround(k * period * 1e9));
  }
  EXPECT_EQ(pacer.resyncs(), 0);
}

}  // namespace
}  // namespace kelvin::bridge
