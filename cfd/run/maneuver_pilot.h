// A maneuver flown in free-running CFD by the simulator's own controller
// (simulator/maneuvers/maneuver.h, shared code): the pilot is the
// controller's plant. After each step it reads the body's time, heading and
// surge speed, acts on the maneuver's events (the execute, the zig-zag
// reversals at the same heading crossings as the fixed-step simulator) by
// ordering the rudder actuator, and records the trajectory in the
// simulator's schema. When the maneuver has what its metrics need, the run
// ends as completed and the result (trajectory, metrics and IMO verdicts,
// computed by the simulator's code) is written to the output directory.
//
//   maneuver:
//     kind: turning:35:stbd   # as kelvin simulate: zigzag:10/10:port, spiral:25:5
//     execute_time: 4.0       # s: the approach runs straight with the rudder at its order until then
//     output: maneuver.h5     # in output.directory
//
// The approach is the free body's initial speed with the propeller's fixed
// rate (propeller.rate.n); a crash stop is refused (the body-force disk has
// no reverse-thrust curve). The controller's state and the trajectory are in
// the checkpoint, so a maneuver resumes bit for bit.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cfd/run/case_loader.h"
#include "cfd/run/maneuver_settings.h"
#include "cfd/run/monitor.h"
#include "cfd/run/rudder_actuator.h"
#include "simulator/maneuvers/maneuver.h"
#include "simulator/maneuvers/trajectory.h"

namespace kelvin::cfd {

class PropellerActuator;

// Reads the case's `maneuver:` section; nullopt without one. A non-empty
// `kind_override` (kelvin run -m) replaces its kind and needs the section.
// Throws ConfigError for a maneuver the case cannot fly (no rudder: section,
// a crash stop, an execute before the body is released) or a bad key, and
// ArgumentError for an override the case has no maneuver: section for.
// Throws the ArgumentError above when `kind_override` is non-empty and the
// case (`root`) has no maneuver: section.
void RequireManeuverSection(const data::ConfigNode& root, const std::string& kind_override);

std::optional<ManeuverPilotSettings> LoadManeuverPilot(const data::ConfigNode& root, const Case& c,
                                                       const std::filesystem::path& output_directory,
                                                       const std::string& kind_override = {});

class ManeuverPilot final : public Monitor, public sim::ManeuverPlant {
 public:
  ManeuverPilot(const Case& c, ManeuverPilotSettings settings);

  // ManeuverPlant: the body after the last step.
  double time() const override { return t_; }
  double heading() const override;
  double surge_speed() const override;
  void SetRudderOrder(double delta_order) override;
  void SetRpsOrder(double n_order) override;

  // Monitor.
  void AfterStep(const PimpleSolver& solver, const StepRecord& record, History& history) override;
  bool Done() const override;
  void AddCheckpointScalars(CheckpointScalars& scalars) const override;
  void AddCheckpointArrays(CheckpointArrays& arrays) const override;
  void RestoreScalars(const CheckpointScalars& scalars) override;
  void RestoreArrays(const CheckpointArrays& arrays) override;
  std::vector<std::string> Finish(const PimpleSolver& solver) override;

  const sim::Trajectory& trajectory() const { return trajectory_; }

 private:
  void Record();

  ManeuverPilotSettings settings_;
  std::shared_ptr<FreeBody> body_;
  RudderActuator* rudder_ = nullptr;
  const PropellerActuator* propeller_ = nullptr;
  sim::ShipParameters ship_;
  double approach_speed_ = 0.0, approach_rps_ = 0.0;
  sim::ManeuverController controller_;
  sim::Trajectory trajectory_;
  double t_ = 0.0;
  double psi_before_ = 0.0;
  bool started_ = false;
};

}  // namespace kelvin::cfd
