// The surrogate: a ship file's MMG model with a derivative set's hull
// derivatives and added masses in place of its hull section, and the set's
// identified interaction coefficients (if any) in place of the ship file's.
// kelvin simulate and bridge --derivatives run it, and kelvin check compares
// it with reference runs.
#pragma once

#include <string>

#include "simulator/mmg/derivative_set.h"
#include "simulator/mmg/ship_parameters.h"

namespace kelvin::sim {

// `ship` (loaded from `ship_file`) with the hull and interaction of `set` when there is one
// (validated; a kelvin::ModelError names the set's file), required to be a
// complete maneuvering model (a kelvin::ConfigError names `ship_file`). A set
// of another ship (derivative_set.ship against the ship file's name) is a
// kelvin::ConfigError naming the set's key; a set that names no ship is
// taken with a warning.
ShipParameters SurrogateShip(ShipParameters ship, const std::string& ship_file, const DerivativeSet* set);

}  // namespace kelvin::sim
