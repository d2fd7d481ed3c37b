#include "simulator/maneuvers/metrics.h"

#include <cmath>

namespace kelvin::sim {

namespace {

struct Local {
  double along, across;
};

Local ToInitialAxes(const TrajectorySample& s, const TrajectorySample& origin, double psi0, int side) {
  const double dx = s.x - origin.x, dy = s.y - origin.y;
  return {dx * std::cos(psi0) + dy * std::sin(psi0), side * (-dx * std::sin(psi0) + dy * std::cos(psi0))};
}

}  // namespace

TurningMetrics ComputeTurning(const Trajectory& traj, double t0, double psi0, int side) {
  TurningMetrics m;
  const TrajectorySample origin = traj.At(t0);
  auto at_heading = [&](double change) {
    return traj.FirstCrossing(t0, psi0 + side * change, &TrajectorySample::psi, side);
  };
  const double t90 = at_heading(M_PI / 2), t180 = at_heading(M_PI);
  if (t90 > 0) {
    const Local p = ToInitialAxes(traj.At(t90), origin, psi0, side);
    m.advance = p.along;
    m.transfer = p.across;
    m.time_to_90 = t90 - t0;
  }
  if (t180 > 0) {
    m.tactical_diameter = ToInitialAxes(traj.At(t180), origin, psi0, side).across;
    m.time_to_180 = t180 - t0;
  }
  const double t360 = at_heading(2 * M_PI), t540 = at_heading(3 * M_PI);
  if (t360 > 0 && t540 > 0) {
    const TrajectorySample a = traj.At(t360), b = traj.At(t540);
    m.steady_diameter = std::hypot(b.x - a.x, b.y - a.y);
  }
  const TrajectorySample& end = traj[traj.size() - 1];
  m.steady_rate = std::abs(end.r);
  m.steady_speed = std::hypot(end.u, end.v);
  return m;
}

ZigZagMetrics ComputeZigZag(const Trajectory& traj, const std::vector<double>& executes, double psi0,
                            double trigger_heading, int side) {
  ZigZagMetrics z;
  if (executes.empty()) return z;
  const double t0 = executes[0];
  const double t10 = traj.FirstCrossing(t0, psi0 + side * 10.0 * M_PI / 180.0, &TrajectorySample::psi, side);
  if (t10 > 0) z.reach_at_10deg = traj.PathLength(t0, t10);
  if (executes.size() > 1) z.time_to_first_reversal = executes[1] - t0;
  // First overshoot: after the first reversal the yaw rate toward the first
  // side falls through zero at the heading extremum.
  if (executes.size() > 1) {
    const double te = traj.FirstCrossing(executes[1], 0.0, &TrajectorySample::r, -side);
    if (te > 0) {
      z.first_overshoot = ZigZagOvershoot(traj.At(te).psi, psi0, trigger_heading, side);
      z.first_overshoot_time = te - t0;
    }
  }
  if (executes.size() > 2) {
    const double te = traj.FirstCrossing(executes[2], 0.0, &TrajectorySample::r, side);
    if (te > 0) {
      z.second_overshoot = ZigZagOvershoot(traj.At(te).psi, psi0, trigger_heading, -side);
      z.second_overshoot_time = te - t0;
    }
  }
  if (executes.size() > 3) z.period = executes[3] - executes[1];
  return z;
}

double ZigZagOvershoot(double psi_extremum, double psi0, double trigger_heading, int sign) {
  return sign * (psi_extremum - psi0) - trigger_heading;
}

std::vector<SpiralPoint> ComputeSpiral(const Trajectory& traj, const std::vector<double>& executes,
                                       const std::vector<double>& rudders, double t_end, double Lpp) {
  std::vector<SpiralPoint> out;
  for (std::size_t i = 0; i < executes.size() && i < rudders.size(); ++i) {
    const double t_hold_end = i + 1 < executes.size() ? executes[i + 1] : t_end;
    const TrajectorySample s = traj.At(t_hold_end - 1e-9);
    const double U = std::hypot(s.u, s.v);
    out.push_back({rudders[i], U > 0 ? s.r * Lpp / U : 0.0});
  }
  return out;
}

StoppingMetrics ComputeStopping(const Trajectory& traj, double t0, double psi0) {
  StoppingMetrics m;
  const double ts = traj.FirstCrossing(t0, 0.0, &TrajectorySample::u, -1);
  if (ts < 0) return m;
  const TrajectorySample origin = traj.At(t0);
  const Local p = ToInitialAxes(traj.At(ts), origin, psi0, +1);
  m.time_to_stop = ts - t0;
  m.track_reach = traj.PathLength(t0, ts);
  m.head_reach = p.along;
  m.lateral_deviation = p.across;
  return m;
}

double ImoZigZag10FirstOvershootLimitDeg(double lv) {
  if (lv < 10) return 10;
  if (lv >= 30) return 20;
  return 5 + 0.5 * lv;
}

double ImoZigZag10SecondOvershootLimitDeg(double lv) {
  if (lv < 10) return 25;
  if (lv >= 30) return 40;
  return 17.5 + 0.75 * lv;
}

}  // namespace kelvin::sim
