// What the bridge streams: the ship file's reference set or a derivative
// set (simulator/mmg/derivative_set.h, which documents the file layout), and
// whether it passed its check against CFD. The hull section of a published
// ship file is a reference set: it was not checked against this project's
// CFD.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "simulator/mmg/derivative_set.h"
#include "simulator/mmg/ship_parameters.h"

namespace kelvin::bridge {

enum class DerivativeStatus { kChecked, kCheckFailed, kUnchecked, kShipReference };

struct DerivativeAssessment {
  DerivativeStatus status = DerivativeStatus::kShipReference;
  std::string message;  // what to tell the user (a warning unless kChecked)
};

// What the bridge streams: the ship file's reference set (no `set`) or a
// derivative set. With `require_checked`, anything but a set with a passing
// check throws kelvin::ArgumentError with the reason.
DerivativeAssessment AssessDerivatives(const sim::ShipParameters& ship, const std::optional<sim::DerivativeSet>& set,
                                       bool require_checked);

}  // namespace kelvin::bridge
