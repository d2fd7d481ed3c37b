// Derivative sets: hull derivatives and added masses that replace a ship
// file's hull section (kelvin simulate/bridge --derivatives), and whether
// they passed their check against CFD. `kelvin identify` writes the set
// (identification/derivative_set_io.h); the check against free-running CFD (a
// later stage) adds its `check` section:
//
//   derivative_set: {name: ..., ship: ..., source: ...}
//   hull: {R0_prime: ..., ..., J_z_prime: ...}   # all 20, as in ship files
//   standard_errors: {...}                       # informative, not read here
//   fit: {...}                                   # informative, not read here
//   check: {passed: true|false, reference: ..., date: ..., summary: ...}
//
// The hull section of a published ship file is a reference set: it was not
// checked against this project's CFD.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "simulator/mmg/ship_parameters.h"

namespace kelvin::sim {

struct DerivativeCheck {
  bool passed = false;
  std::string reference;  // what the set was checked against
  std::string date;
  std::string summary;
};

struct DerivativeSet {
  std::string file;
  std::string name;
  HullCoefficients<double> hull;
  std::optional<DerivativeCheck> check;
};

// Loads a derivative file; throws kelvin::ConfigError naming the file, line
// and key for an unknown key, a missing derivative or a non-number.
DerivativeSet LoadDerivativeSet(const std::filesystem::path& path);
// The same from a derivative file already parsed (`path` names it).
DerivativeSet LoadDerivativeSet(const data::ConfigNode& root, const std::filesystem::path& path);

}  // namespace kelvin::sim
