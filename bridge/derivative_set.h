// Derivative sets: the hull derivatives the simulator streams, and whether
// they passed their check against CFD. `kelvin identify` writes the set
// (identification/derivative_set_io.h); the check against free-running CFD (a
// later stage) adds its `check` section:
//
//   derivative_set: {name: ..., ship: ..., source: ...}
//   hull: {R0_prime: ..., ..., J_z_prime: ...}   # all 20, as in ship files
//   standard_errors: {...}                       # not read by the bridge
//   fit: {...}                                   # not read by the bridge
//   check: {passed: true|false, reference: ..., date: ..., summary: ...}
//
// The hull section of a published ship file is a reference set: it was not
// checked against this project's CFD.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "simulator/mmg/ship_parameters.h"

namespace kelvin::bridge {

struct DerivativeCheck {
  bool passed = false;
  std::string reference;  // what the set was checked against
  std::string date;
  std::string summary;
};

struct DerivativeSet {
  std::string file;
  std::string name;  // derivative_set.name, if given
  sim::HullCoefficients<double> hull;
  std::optional<DerivativeCheck> check;
};

// Loads a derivative file; throws kelvin::ConfigError naming the file, line
// and key for an unknown key, a missing derivative or a non-number.
DerivativeSet LoadDerivativeSet(const std::filesystem::path& path);

enum class DerivativeStatus { kChecked, kCheckFailed, kUnchecked, kShipReference };

struct DerivativeAssessment {
  DerivativeStatus status = DerivativeStatus::kShipReference;
  std::string message;  // what to tell the user (a warning unless kChecked)
};

// What the bridge streams: the ship file's reference set (no `set`) or a
// derivative set. With `require_checked`, anything but a set with a passing
// check throws kelvin::ArgumentError with the reason.
DerivativeAssessment AssessDerivatives(const sim::ShipParameters& ship, const std::optional<DerivativeSet>& set,
                                       bool require_checked);

}  // namespace kelvin::bridge
