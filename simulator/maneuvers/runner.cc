#include "simulator/maneuvers/runner.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>

#include "data/schema/errors.h"
#include "data/schema/h5_file.h"

namespace kelvin::sim {

namespace {

constexpr double kDeg = M_PI / 180.0;

void AddMetrics(ManeuverResult& r) {
  const double L = r.Lpp;
  auto add = [&](std::string name, double value, std::string unit, std::string description) {
    r.metrics.push_back({std::move(name), value, std::move(unit), std::move(description)});
  };
  if (r.turning) {
    const TurningMetrics& m = *r.turning;
    add("advance", m.advance, "m", "advance at 90 deg heading change");
    add("advance_over_L", m.advance / L, "1", "advance / Lpp");
    add("transfer", m.transfer, "m", "transfer at 90 deg heading change");
    add("tactical_diameter", m.tactical_diameter, "m", "transfer at 180 deg heading change");
    add("tactical_diameter_over_L", m.tactical_diameter / L, "1", "tactical diameter / Lpp");
    add("steady_diameter", m.steady_diameter, "m", "distance between positions at 360 and 540 deg");
    add("steady_diameter_over_L", m.steady_diameter / L, "1", "steady turning diameter / Lpp");
    add("steady_rate", m.steady_rate / kDeg, "deg/s", "steady yaw rate");
    add("steady_speed", m.steady_speed, "m/s", "steady speed in the turn");
    add("speed_ratio", m.steady_speed / r.approach_speed, "1", "steady speed / approach speed");
    add("time_to_90", m.time_to_90, "s", "time from execute to 90 deg heading change");
    add("time_to_180", m.time_to_180, "s", "time from execute to 180 deg heading change");
  }
  if (r.zigzag) {
    const ZigZagMetrics& z = *r.zigzag;
    add("first_overshoot", z.first_overshoot / kDeg, "deg", "first overshoot angle");
    add("second_overshoot", z.second_overshoot / kDeg, "deg", "second overshoot angle");
    add("first_overshoot_time", z.first_overshoot_time, "s", "time of the first heading extremum");
    add("second_overshoot_time", z.second_overshoot_time, "s", "time of the second heading extremum");
    add("time_to_first_reversal", z.time_to_first_reversal, "s", "time until the first rudder reversal");
    add("period", z.period, "s", "time between the first and third rudder reversals");
    add("reach_at_10deg_over_L", z.reach_at_10deg / L, "1", "track length / Lpp until 10 deg heading change");
  }
  for (std::size_t i = 0; i < r.spiral.size(); ++i) {
    add(fmt::format("spiral_{:02d}_rudder", i), r.spiral[i].rudder / kDeg, "deg", "spiral step rudder angle");
    add(fmt::format("spiral_{:02d}_r_prime", i), r.spiral[i].rate_prime, "1", "steady r L / U at this step");
  }
  if (r.stopping) {
    const StoppingMetrics& s = *r.stopping;
    add("track_reach_over_L", s.track_reach / L, "1", "track reach / Lpp");
    add("head_reach_over_L", s.head_reach / L, "1", "head reach / Lpp");
    add("lateral_deviation_over_L", s.lateral_deviation / L, "1", "lateral deviation / Lpp");
    add("time_to_stop", s.time_to_stop, "s", "time until the ship stops");
  }
}

void AddVerdicts(ManeuverResult& r, double max_rudder) {
  const double L = r.Lpp;
  auto verdict = [&](std::string name, double value, double limit, std::string unit) {
    r.verdicts.push_back({std::move(name), value, limit, std::move(unit), value <= limit});
  };
  const double lv_full = L / r.approach_speed * std::sqrt(r.scale);
  const auto& s = r.spec;
  if (r.turning && (std::abs(s.rudder - 35 * kDeg) < 1e-9 || std::abs(s.rudder - max_rudder) < 1e-9)) {
    verdict("turning: advance / L", r.turning->advance / L, 4.5, "1");
    verdict("turning: tactical diameter / L", r.turning->tactical_diameter / L, 5.0, "1");
  }
  if (r.zigzag && std::abs(s.rudder - 10 * kDeg) < 1e-9 && std::abs(s.heading - 10 * kDeg) < 1e-9) {
    verdict("initial turning: track / L at 10 deg", r.zigzag->reach_at_10deg / L, 2.5, "1");
    verdict("zig-zag 10/10: first overshoot", r.zigzag->first_overshoot / kDeg,
            ImoZigZag10FirstOvershootLimitDeg(lv_full), "deg");
    verdict("zig-zag 10/10: second overshoot", r.zigzag->second_overshoot / kDeg,
            ImoZigZag10SecondOvershootLimitDeg(lv_full), "deg");
  }
  if (r.zigzag && std::abs(s.rudder - 20 * kDeg) < 1e-9 && std::abs(s.heading - 20 * kDeg) < 1e-9) {
    verdict("zig-zag 20/20: first overshoot", r.zigzag->first_overshoot / kDeg, 25.0, "deg");
  }
  if (r.stopping) verdict("stopping: track reach / L", r.stopping->track_reach / L, 15.0, "1");
}

}  // namespace

void RunOptions::Validate() const {
  integrator.Validate();
  if (approach_speed < 0 || !std::isfinite(approach_speed)) {
    throw ArgumentError(fmt::format("approach speed {} m/s: expected a positive speed", approach_speed));
  }
  if (output_interval < 0 || !std::isfinite(output_interval)) {
    throw ArgumentError(fmt::format("output interval {} s: expected a positive interval", output_interval));
  }
  if (approach_rps < 0 || !std::isfinite(approach_rps)) {
    throw ArgumentError(fmt::format("approach propeller speed {} 1/s: expected a positive rps", approach_rps));
  }
}

ManeuverResult RunManeuver(const MmgModel<double>& model, const ManeuverSpec& spec, const RunOptions& options,
                           Progress* progress) {
  options.Validate();
  const auto wall0 = std::chrono::steady_clock::now();
  const ShipParameters& ship = model.ship();
  ManeuverResult res;
  res.spec = spec;
  res.ship_name = ship.name;
  res.Lpp = ship.principal.Lpp;
  res.scale = ship.scale;
  res.approach_speed = options.approach_speed > 0 ? options.approach_speed : ship.approach_speed;
  if (!(res.approach_speed > 0)) {
    throw ArgumentError(fmt::format("ship '{}' gives no approach speed (conditions.approach_speed): pass --speed",
                                    ship.name));
  }
  res.approach_rps = options.approach_rps > 0 ? options.approach_rps : SelfPropulsionRps(model, res.approach_speed);

  Simulator sim(model, options.integrator);
  sim.Reset(0.0, {0, 0, 0, res.approach_speed, 0, 0}, 0.0, res.approach_rps);
  ManeuverController ctrl(spec, ship, res.approach_speed, res.approach_rps);
  res.trajectory.Record(sim, static_cast<int>(ManeuverPhase::kApproach));
  ctrl.Start(sim);
  const double t_limit = ctrl.time_limit();

  const bool fixed = options.integrator.method == SimulatorOptions::Method::kFixedStep;
  double dt_out = options.output_interval > 0 ? options.output_interval : res.Lpp / res.approach_speed / 40.0;
  long stride = 1;
  if (fixed) {
    stride = std::max(1L, std::lround(dt_out / options.integrator.fixed_step));
    dt_out = stride * options.integrator.fixed_step;
  }
  long out_index = 0;
  while (!ctrl.Finished(sim)) {
    if (fixed) {
      for (long k = 0; k < stride; ++k) StepManeuver(sim, ctrl);
    } else {
      const double t_next = std::min((out_index + 1) * dt_out, ctrl.NextTimeEvent());
      const bool hit = sim.Advance(t_next, ctrl.NextHeadingEvent());
      if (hit) {
        ctrl.OnHeadingEvent(sim);
        res.trajectory.Record(sim, static_cast<int>(ctrl.phase()));
        continue;
      }
      if (sim.time() >= ctrl.NextTimeEvent()) {
        res.trajectory.Record(sim, static_cast<int>(ctrl.phase()));
        ctrl.OnTimeEvent(sim);
      }
    }
    if (sim.time() >= (out_index + 1) * dt_out - 1e-9) ++out_index;
    res.trajectory.Record(sim, static_cast<int>(ctrl.phase()));
    for (double v : sim.state()) {
      if (!std::isfinite(v)) {
        throw std::runtime_error(fmt::format("maneuver {} diverged at t = {} s (non-finite state)", spec.ToString(),
                                             sim.time()));
      }
    }
    if (progress) progress->Update(sim.time() / t_limit * 100.0);
  }
  if (progress) progress->Finish();
  res.execute_times = ctrl.execute_times();
  res.integrator_steps = sim.steps_taken();

  ComputeManeuverMetrics(res, ctrl, ship.limits.rudder_max, sim.time());
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return res;
}

void ComputeManeuverMetrics(ManeuverResult& res, const ManeuverController& ctrl, double max_rudder, double t_end) {
  const ManeuverSpec& spec = res.spec;
  const double psi0 = ctrl.start_heading(), t0 = ctrl.start_time();
  switch (spec.kind) {
    case ManeuverSpec::Kind::kTurning: res.turning = ComputeTurning(res.trajectory, t0, psi0, spec.side); break;
    case ManeuverSpec::Kind::kZigZag:
      res.zigzag = ComputeZigZag(res.trajectory, res.execute_times, psi0, spec.heading, spec.side);
      break;
    case ManeuverSpec::Kind::kSpiral:
      res.spiral = ComputeSpiral(res.trajectory, res.execute_times, ctrl.spec().spiral_rudders, t_end, res.Lpp);
      break;
    case ManeuverSpec::Kind::kStopping: res.stopping = ComputeStopping(res.trajectory, t0, psi0); break;
  }
  AddMetrics(res);
  AddVerdicts(res, max_rudder);
}

void WriteManeuverResult(const ManeuverResult& r, const std::filesystem::path& path,
                         const std::string& integrator_name) {
  data::H5Writer out(path);
  out.SetAttribute("/", "kelvin_schema", "maneuver/1");
  out.SetAttribute("/", "ship", r.ship_name);
  out.SetAttribute("/", "maneuver", r.spec.ToString());
  out.SetAttribute("/", "integrator", integrator_name);
  out.SetAttribute("/", "source", r.source);
  out.SetAttribute("/", "scale", r.scale);
  out.SetAttribute("/", "Lpp", r.Lpp);
  out.SetAttribute("/", "approach_speed", r.approach_speed);
  out.SetAttribute("/", "approach_rps", r.approach_rps);
  r.trajectory.Write(out, "trajectory");
  out.WriteArray("execute_times", r.execute_times, {r.execute_times.size()}, "s", "rudder execute times");
  for (const MetricRow& m : r.metrics) {
    out.WriteArray("metrics/" + m.name, std::vector<double>{m.value}, {1}, m.unit, m.description);
  }
  for (std::size_t i = 0; i < r.verdicts.size(); ++i) {
    const ImoVerdict& v = r.verdicts[i];
    const std::string name = fmt::format("imo/criterion_{}", i);
    out.WriteArray(name, std::vector<double>{v.value, v.limit, v.pass ? 1.0 : 0.0}, {3}, v.unit,
                   "IMO MSC.137(76): " + v.criterion + " [value, limit, pass]");
  }
  out.Commit();
}

std::string FormatManeuverReport(const ManeuverResult& r) {
  std::string s = fmt::format("{} {}: approach {:.4g} m/s, self-propulsion {:.4g} rps, {} samples\n", r.ship_name,
                              r.spec.ToString(), r.approach_speed, r.approach_rps, r.trajectory.size());
  for (const MetricRow& m : r.metrics) {
    s += fmt::format("  {:<28} {:>12.5g} {:<6} {}\n", m.name, m.value, m.unit, m.description);
  }
  if (!r.verdicts.empty()) s += "  IMO MSC.137(76):\n";
  for (const ImoVerdict& v : r.verdicts) {
    s += fmt::format("  {:<40} {:>8.3f} <= {:<8.3g} {:<4} {}\n", v.criterion, v.value, v.limit, v.unit,
                     v.pass ? "PASS" : "FAIL");
  }
  return s;
}

}  // namespace kelvin::sim
