// Shared fixtures for simulator tests: the KVLCC2 ship of the repository.
#pragma once

#include "simulator/mmg/ship_parameters.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::sim::testing {

// KVLCC2 L7 model, Yasukawa & Yoshimura (2015), J. Mar. Sci. Technol.
// 20:37-52, Tables 1-3, as copied into data/ships/kvlcc2.yaml.
inline ShipParameters Kvlcc2() { return LoadShip(kelvin::testing::SourceDir() / "data/ships/kvlcc2.yaml"); }

}  // namespace kelvin::sim::testing
