// The surrogate check (kelvin check): a derivative set's MMG model, run on
// the maneuvers of reference runs (free-running CFD, or the simulator) from
// the same approach state, compared metric by metric and along the track.
//
// For each reference file (simulator/maneuvers/maneuver_file.h) the
// surrogate (simulator/mmg/surrogate.h: the ship file with the set's hull) runs
// the reference's maneuver from its approach speed and propeller rps. Every
// metric the metrics code gives for that maneuver is tabulated, reference
// against surrogate, with the difference (surrogate - reference), absolute and
// relative to |reference|. Metrics with a tolerance get a verdict; by default
// (the goal of the project's surrogate) the advance and the tactical diameter
// within 5% and the overshoot angles within 2 deg; others are reported
// without one. Along the track, at the reference's samples from the rudder
// execute on: the distance between the two midship positions, each in axes
// of its own position and heading at execute (m and / Lpp), and the
// difference of the heading changes, with their maximum and time-weighted
// RMS.
//
// The check passes when every verdict of every maneuver passes. A metric a
// run never reached (a heading change a short run did not get to) is 0 in
// the metrics code, and so fails a tolerance unless both runs miss it.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "simulator/maneuvers/maneuver_file.h"
#include "simulator/maneuvers/runner.h"
#include "simulator/mmg/derivative_set.h"

namespace kelvin::sim {

struct MetricTolerance {
  enum class Kind { kAbsolute, kRelative, kNone };
  Kind kind = Kind::kNone;
  double value = 0;  // kAbsolute: in `unit`; kRelative: a fraction of |reference|
  std::string unit;  // kAbsolute: the unit given, which must be the metric's
  std::string text;  // as given ("5%", "2deg", "none")
};

// Tolerances by metric name.
using CheckTolerances = std::map<std::string, MetricTolerance>;

// advance 5%, tactical_diameter 5%, first_overshoot and second_overshoot 2 deg.
CheckTolerances DefaultCheckTolerances();

// Parses "advance=5%,tactical_diameter=3%,overshoot=1.5deg,time_to_90=none"
// over `base`: a percentage is relative to the reference value, a number with
// a unit (m, s, deg, deg/s, m/s) is absolute in the metric's unit, a bare
// number is absolute for nondimensional metrics, and "none" drops a verdict.
// "overshoot" stands for first_overshoot and second_overshoot. Throws
// kelvin::ArgumentError naming `option`, the item and the expected form.
// Metric names are checked against the maneuvers when the check runs.
CheckTolerances ParseCheckTolerances(std::string_view text, CheckTolerances base = DefaultCheckTolerances(),
                                     std::string_view option = "--tolerances");

struct MetricComparison {
  enum class Verdict { kNone, kPass, kFail };
  std::string name;
  std::string unit;
  std::string description;
  std::optional<double> reference;
  std::optional<double> surrogate;
  double difference = 0;  // surrogate - reference; NaN when one is missing
  double relative = 0;    // difference / |reference|; NaN when the reference is 0 or missing
  std::optional<MetricTolerance> tolerance;
  double allowed = 0;  // the tolerance in the metric's unit (relative ones times |reference|)
  double used = 0;     // |difference| / allowed (0 / 0 = 0; inf when nothing is allowed or a value is missing)
  Verdict verdict = Verdict::kNone;
};

struct TrackErrors {
  std::vector<double> time;            // s since the rudder execute
  std::vector<double> position_error;  // m, distance between the midship positions
  std::vector<double> heading_error;   // rad, surrogate heading change - reference heading change
  double max_position = 0;             // m
  double rms_position = 0;             // m, time-weighted
  double max_heading = 0;              // rad, of |heading_error|
  double rms_heading = 0;              // rad
};

struct ManeuverCheck {
  ManeuverFile reference;
  ManeuverResult surrogate;
  double self_propulsion_rps = 0;  // the surrogate's own at the reference speed (informative)
  std::vector<MetricComparison> metrics;
  TrackErrors track;
  bool passed = false;
  std::string summary;  // one line: the maneuver, its worst metric, the track error
  // Where the reference or the surrogate went beyond the set's identified
  // range (identified_range.h): one WARNING line each, none when within.
  std::vector<std::string> warnings;
};

struct SurrogateCheckOptions {
  std::filesystem::path derivatives;              // the derivative set (YAML)
  std::filesystem::path ship;                     // the ship file the set's hull goes into
  std::vector<std::filesystem::path> references;  // maneuver result files (HDF5)
  // If given, every reference must be one of these maneuvers (as
  // ManeuverSpec::Parse reads them) and each must have a reference.
  std::vector<std::string> maneuvers;
  CheckTolerances tolerances = DefaultCheckTolerances();
  SimulatorOptions integrator;  // the surrogate's (CVODE by default)
  std::string date;             // of the check; empty: now (UTC, ISO 8601)
};

struct SurrogateCheck {
  std::string derivatives_file;
  std::string ship_file;
  std::string set_name;
  std::string integrator;  // the surrogate's: "cvode" or "fixed"
  std::vector<ManeuverCheck> maneuvers;
  bool passed = false;
  DerivativeCheck section;  // the `check` section for the derivative set
};

// Runs the check; writes nothing. Throws kelvin::ArgumentError,
// kelvin::ConfigError or kelvin::DataFileError naming the file, the key or
// attribute, its value and what was expected: a missing file, a set of
// another ship than the ship file (derivative_set.ship) or than a reference
// (its `ship` attribute), a reference that is not a maneuver result, one at
// another scale (Lpp), one of another maneuver than --maneuver asks, a
// tolerance for a metric none of the maneuvers has, a tolerance in the wrong
// unit, and a maneuver none of whose metrics has a tolerance.
SurrogateCheck RunSurrogateCheck(const SurrogateCheckOptions& options);

// The table printed by kelvin check: per maneuver, the metrics with both
// values, the differences, the tolerances and verdicts, and the track
// errors; then the overall verdict.
std::string FormatCheckTable(const SurrogateCheck& check);

// Writes the report into `dir` (created if needed), each file atomically:
//   check_report.md           the table, as markdown
//   track_errors.h5           per maneuver (group maneuver_<i>): time since
//                             execute, position error (m and / Lpp), heading
//                             error, with the reference and maneuver as
//                             attributes
//   surrogate_<i>_<stem>.h5   the surrogate's run in the maneuver schema
//                             (source = "surrogate"), for
//                             tools/plot_maneuver.py --overlay
void WriteCheckReport(const SurrogateCheck& check, const std::filesystem::path& dir);

// The path WriteCheckReport gives the surrogate run of maneuver `index`.
std::filesystem::path SurrogateRunPath(const SurrogateCheck& check, std::size_t index,
                                       const std::filesystem::path& dir);

}  // namespace kelvin::sim
