// Reading maneuver result files: the HDF5 schema that WriteManeuverResult
// (simulator/maneuvers/runner.h) writes, and that free-running CFD runs
// write too, so that kelvin check can compare any of them with a surrogate.
//
//   /  attributes: kelvin_schema = "maneuver/1", ship, maneuver (as
//      ManeuverSpec::ToString), integrator, Lpp (m), approach_speed (m/s),
//      approach_rps (1/s), and optionally source: "simulator" (the default
//      when absent), "cfd" (a free-running CFD run) or "surrogate" (the
//      surrogate kelvin check ran against a reference)
//   trajectory/{time, x, y, psi, u, v, r, rudder, rps, phase}
//   execute_times            s, the rudder execute times
//   metrics/<name>           one value each, with units and description
//   imo/criterion_<i>        [value, limit, pass], description
//                            "IMO MSC.137(76): <criterion> [value, limit, pass]"
#pragma once

#include <filesystem>
#include <string>

#include "simulator/maneuvers/runner.h"

namespace kelvin::sim {

inline constexpr const char* kManeuverSchema = "maneuver/1";

struct ManeuverFile {
  std::string path;
  std::string source = "simulator";  // root attribute `source`
  std::string integrator;
  // spec, ship_name, Lpp, approach_speed, approach_rps, trajectory,
  // execute_times, metrics and verdicts as written. The per-kind metric
  // structs (turning, zigzag, ...) are not rebuilt: `metrics` holds them.
  ManeuverResult result;
};

// Reads a maneuver result file. Throws kelvin::DataFileError naming the file,
// the attribute or dataset, the value and what was expected: not HDF5, not a
// maneuver result (kelvin_schema), an unparsable maneuver, a trajectory with
// columns of different lengths or times that do not increase.
ManeuverFile ReadManeuverResult(const std::filesystem::path& path);

}  // namespace kelvin::sim
