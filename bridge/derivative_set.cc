#include "bridge/derivative_set.h"

#include <fmt/format.h>

#include "data/schema/config.h"
#include "data/schema/errors.h"

namespace kelvin::bridge {

DerivativeAssessment AssessDerivatives(const sim::ShipParameters& ship, const std::optional<sim::DerivativeSet>& set,
                                       bool require_checked) {
  DerivativeAssessment a;
  if (!set) {
    a.status = DerivativeStatus::kShipReference;
    a.message = fmt::format(
        "streaming the hull derivatives of the ship file ('{}', {}): a published reference set, not checked "
        "against this project's CFD",
        ship.name, ship.source.empty() ? "no source given" : ship.source);
  } else if (!set->check) {
    a.status = DerivativeStatus::kUnchecked;
    a.message = fmt::format("derivative set {} has no 'check' section: it was never checked against CFD", set->file);
  } else if (!set->check->passed) {
    a.status = DerivativeStatus::kCheckFailed;
    a.message = fmt::format("derivative set {} FAILED its check against CFD ({}{})", set->file,
                            set->check->reference.empty() ? "no reference given" : set->check->reference,
                            set->check->summary.empty() ? "" : ": " + set->check->summary);
  } else {
    a.status = DerivativeStatus::kChecked;
    a.message = fmt::format("derivative set {} passed its check against {}", set->file,
                            set->check->reference.empty() ? "CFD" : set->check->reference);
    return a;
  }
  if (require_checked) {
    throw ArgumentError(fmt::format("--require-checked: refusing to stream: {}", a.message));
  }
  return a;
}

}  // namespace kelvin::bridge
