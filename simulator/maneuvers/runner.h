// Runs an IMO maneuver in fast time from a steady approach: the ship starts
// at the approach speed with the self-propulsion propeller speed (X = 0) or a
// given one (a reference run's, for kelvin check), the
// controller executes the maneuver, and the metrics and IMO verdicts are read
// off the recorded trajectory.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "data/report/progress.h"
#include "simulator/maneuvers/maneuver.h"
#include "simulator/maneuvers/metrics.h"

namespace kelvin::sim {

struct RunOptions {
  SimulatorOptions integrator;
  double approach_speed = 0;   // m/s; 0 = the ship's conditions.approach_speed
  double approach_rps = 0;     // 1/s; 0 = self-propulsion (X = 0) at the approach speed
  double output_interval = 0;  // s between recorded samples; 0 = Lpp / U0 / 40
  void Validate() const;
};

struct ManeuverResult {
  ManeuverSpec spec;
  std::string source = "simulator";  // who flew it: simulator, surrogate or cfd (root attribute `source`)
  std::string ship_name;
  double Lpp = 0;
  double scale = 1;
  double approach_speed = 0;
  double approach_rps = 0;
  Trajectory trajectory;
  std::vector<double> execute_times;
  std::optional<TurningMetrics> turning;
  std::optional<ZigZagMetrics> zigzag;
  std::vector<SpiralPoint> spiral;
  std::optional<StoppingMetrics> stopping;
  std::vector<MetricRow> metrics;    // everything above, flattened for tables and files
  std::vector<ImoVerdict> verdicts;  // the IMO criteria that apply to this maneuver
  long integrator_steps = 0;
  double wall_seconds = 0;
};

ManeuverResult RunManeuver(const MmgModel<double>& model, const ManeuverSpec& spec, const RunOptions& options,
                           Progress* progress = nullptr);

// Fills the metrics, the flattened rows and the IMO verdicts of `res` from
// its trajectory and execute times and the controller that flew it (any
// plant: the simulator, or a free-running CFD run); t_end is the time the
// run ended.
void ComputeManeuverMetrics(ManeuverResult& res, const ManeuverController& ctrl, double max_rudder, double t_end);

// Writes the result (trajectory, metrics, verdicts, run attributes) to an
// HDF5 file atomically.
void WriteManeuverResult(const ManeuverResult& result, const std::filesystem::path& path,
                         const std::string& integrator_name);

// A printable table of the metrics and IMO verdicts.
std::string FormatManeuverReport(const ManeuverResult& result);

}  // namespace kelvin::sim
