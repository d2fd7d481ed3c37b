// IMO maneuvers as controllers that work with either integrator: a turning
// circle, a zig-zag, a Dieudonne spiral and a stopping test. The same
// controller runs in fast time (kelvin simulate), in real time (kelvin
// bridge) and in free-running CFD (cfd/run/maneuver_pilot.h): it drives a
// ManeuverPlant, so all of them fly the same maneuver logic.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "simulator/integrators/simulator.h"
#include "simulator/maneuvers/maneuver_plant.h"

namespace kelvin::sim {

struct ManeuverSpec {
  enum class Kind { kTurning, kZigZag, kSpiral, kStopping };
  Kind kind = Kind::kTurning;
  double rudder = 35.0 * M_PI / 180.0;   // rad, rudder angle (turning, zig-zag)
  double heading = 0.0;                  // rad, heading-change trigger (zig-zag)
  int side = +1;                         // +1 starboard first, -1 port first
  std::vector<double> spiral_rudders;    // rad, rudder sequence (spiral)
  double hold_time = 0.0;                // s, time per spiral step (0: from Lpp/U)

  // Parses "turning:35:stbd", "zigzag:20/20:port", "spiral:25:5" (max angle
  // and step), "stopping" (crash stop). Throws kelvin::ArgumentError naming
  // the string and the accepted forms.
  static ManeuverSpec Parse(std::string_view text);
  std::string ToString() const;
};

// Phases reported to the bridge and in trajectories.
enum class ManeuverPhase : int { kApproach = 0, kExecute = 1, kSteady = 2, kFinished = 3 };
std::string_view PhaseName(ManeuverPhase phase);

class ManeuverController {
 public:
  // `approach_rps` is the self-propulsion rps at the approach speed.
  ManeuverController(const ManeuverSpec& spec, const ShipParameters& ship, double approach_speed,
                     double approach_rps);

  // Executes the first action at the plant's current time (t0 of the
  // maneuver): heading psi0 is taken from the plant.
  void Start(ManeuverPlant& plant);
  // The absolute heading at which the next action happens, if any (zig-zag
  // rudder reversals).
  std::optional<double> NextHeadingEvent() const;
  // Called when the heading event was reached: reverses the rudder.
  void OnHeadingEvent(ManeuverPlant& plant);
  // Time-driven actions (spiral steps); returns the next time at which the
  // controller must be called, or +inf.
  double NextTimeEvent() const;
  void OnTimeEvent(ManeuverPlant& plant);
  // True when the maneuver has produced everything its metrics need.
  bool Finished(const ManeuverPlant& plant) const;

  ManeuverPhase phase() const { return phase_; }
  const ManeuverSpec& spec() const { return spec_; }
  double start_time() const { return t0_; }
  double start_heading() const { return psi0_; }
  // Times at which the rudder was ordered to a new angle (zig-zag executes).
  const std::vector<double>& execute_times() const { return execute_times_; }
  // Suggested end time when nothing else stops the run.
  double time_limit() const { return time_limit_; }

  // The controller's progress as numbers (a checkpoint of a CFD maneuver)
  // and back; Unpack throws kelvin::DataFileError for a vector that is not
  // a Pack of this maneuver.
  std::vector<double> Pack() const;
  void Unpack(std::span<const double> packed);

 private:
  ManeuverSpec spec_;
  double L_ = 0.0;
  double U0_ = 0.0;
  double n0_ = 0.0;
  double t0_ = 0.0;
  double psi0_ = 0.0;
  double time_limit_ = 0.0;
  ManeuverPhase phase_ = ManeuverPhase::kApproach;
  int reversals_ = 0;
  int sign_ = +1;  // sign of the current rudder order (zig-zag)
  std::size_t spiral_index_ = 0;
  double next_time_event_ = 0.0;
  bool reverse_thrust_ = false;
  std::vector<double> execute_times_;
};

// Advances `sim` by one fixed step and lets the controller act on any
// heading or time event that the step reached. Used by both the fast-time
// fixed-step runner and the real-time bridge, so they agree exactly.
void StepManeuver(Simulator& sim, ManeuverController& controller);
// After a step of any plant from heading psi_before: acts on the heading or
// time events the step reached (the event check of StepManeuver).
void AfterManeuverStep(ManeuverPlant& plant, ManeuverController& controller, double psi_before);

// Self-propulsion propeller speed (1/s) at which X = 0 in straight motion at
// speed U (rudder amidships). Throws kelvin::ModelError if no positive root.
double SelfPropulsionRps(const MmgModel<double>& model, double U);

}  // namespace kelvin::sim
