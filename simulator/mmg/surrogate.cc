#include "simulator/mmg/surrogate.h"

namespace kelvin::sim {

ShipParameters SurrogateShip(ShipParameters ship, const std::string& ship_file, const DerivativeSet* set) {
  if (set) {
    ship.hull = set->hull;
    ship.has_hull = true;
    ApplyInteraction(set->interaction, ship);
    ship.Validate(set->file);
  }
  RequireManeuveringModel(ship, ship_file);
  return ship;
}

}  // namespace kelvin::sim
