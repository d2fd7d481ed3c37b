// Maneuver metrics read off recorded trajectories, and the IMO
// manoeuvrability criteria of Resolution MSC.137(76) (2002).
//
// Positions are those of midship, in axes of the initial heading: "along" is
// the advance direction, "across" is positive toward the turn. Heading
// events (90 deg, 180 deg, overshoot extrema) are located on the cubic
// Hermite interpolant of the trajectory.
#pragma once

#include <string>
#include <vector>

#include "simulator/maneuvers/trajectory.h"

namespace kelvin::sim {

struct MetricRow {
  std::string name;
  double value;
  std::string unit;
  std::string description;
};

struct TurningMetrics {
  double advance = 0;            // m, along the initial course at 90 deg heading change
  double transfer = 0;           // m, toward the turn at 90 deg
  double tactical_diameter = 0;  // m, toward the turn at 180 deg
  double steady_diameter = 0;    // m, distance between the positions at 360 and 540 deg
  double steady_rate = 0;        // rad/s, |r| at the end of the run
  double steady_speed = 0;       // m/s, U at the end of the run
  double time_to_90 = 0;         // s after rudder execute
  double time_to_180 = 0;        // s
};

struct ZigZagMetrics {
  double first_overshoot = 0;        // rad
  double second_overshoot = 0;       // rad
  double first_overshoot_time = 0;   // s after the first execute, at the heading extremum
  double second_overshoot_time = 0;  // s
  double time_to_first_reversal = 0; // s, heading change reaches the trigger angle
  double period = 0;                 // s, between the first and third rudder reversals
  double reach_at_10deg = 0;         // m, path length until the heading has changed 10 deg
};

struct SpiralPoint {
  double rudder = 0;      // rad
  double rate_prime = 0;  // r L / U at the end of the hold
};

struct StoppingMetrics {
  double track_reach = 0;        // m, path length until the ship stops
  double head_reach = 0;         // m, along the initial course
  double lateral_deviation = 0;  // m
  double time_to_stop = 0;       // s
};

struct ImoVerdict {
  std::string criterion;
  double value = 0;
  double limit = 0;
  std::string unit;
  bool pass = false;
};

TurningMetrics ComputeTurning(const Trajectory& traj, double t0, double psi0, int side);
// `executes` are the rudder execute times (initial order first, then each reversal).
ZigZagMetrics ComputeZigZag(const Trajectory& traj, const std::vector<double>& executes, double psi0,
                            double trigger_heading, int side);
std::vector<SpiralPoint> ComputeSpiral(const Trajectory& traj, const std::vector<double>& executes,
                                       const std::vector<double>& rudders, double t_end, double Lpp);
StoppingMetrics ComputeStopping(const Trajectory& traj, double t0, double psi0);

// The zig-zag overshoot angle (rad) at a heading extremum psi_extremum: how far
// the heading went past the trigger heading change `trigger_heading` (> 0)
// from the initial heading psi0, with `sign` = +1 while the ship was turning
// to starboard and -1 to port. ComputeZigZag reads it off a trajectory; the
// bridge applies it to the extremum it finds while stepping.
double ZigZagOvershoot(double psi_extremum, double psi0, double trigger_heading, int sign);

// IMO MSC.137(76) limits. L/V is taken at full scale (L/V scales with the
// square root of the geometric scale), since the criteria are written for
// ships.
double ImoZigZag10FirstOvershootLimitDeg(double L_over_V_full);
double ImoZigZag10SecondOvershootLimitDeg(double L_over_V_full);

}  // namespace kelvin::sim
