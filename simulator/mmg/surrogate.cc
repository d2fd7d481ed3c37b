#include "simulator/mmg/surrogate.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "data/schema/errors.h"

namespace kelvin::sim {

namespace {

void RequireSetOfShip(const DerivativeSet& set, const ShipParameters& ship, const std::string& ship_file) {
  if (set.ship.empty()) {
    spdlog::warn("derivative set {} names no ship (derivative_set.ship): its ship is not checked against {}", set.file,
                 ship_file);
    return;
  }
  if (set.ship != ship.name) {
    throw ConfigError(fmt::format("{}: key 'derivative_set.ship' = '{}': expected a derivative set of ship '{}', the "
                                  "ship of the ship file {}",
                                  set.ship_where, set.ship, ship.name, ship_file));
  }
}

}  // namespace

ShipParameters SurrogateShip(ShipParameters ship, const std::string& ship_file, const DerivativeSet* set) {
  if (set) {
    RequireSetOfShip(*set, ship, ship_file);
    ship.hull = set->hull;
    ship.has_hull = true;
    ApplyInteraction(set->interaction, ship);
    ship.Validate(set->file);
  }
  RequireManeuveringModel(ship, ship_file);
  return ship;
}

}  // namespace kelvin::sim
