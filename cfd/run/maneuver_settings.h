// The case's `maneuver:` section as read (cfd/run/maneuver_pilot.h flies it).
#pragma once

#include <filesystem>

#include "simulator/maneuvers/maneuver.h"

namespace kelvin::cfd {

struct ManeuverPilotSettings {
  sim::ManeuverSpec spec;
  double execute_time = 0.0;  // s
  std::filesystem::path output;
};

}  // namespace kelvin::cfd
