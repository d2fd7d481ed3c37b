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
//   interaction: {t_P: ..., epsilon: ..., ...}    # optional: identified MMG
//                                                # interaction coefficients
//   interaction_fit: {...}                       # informative, not read here
//   check: {passed: true|false, reference: ..., date: ..., summary: ...}
//
// The interaction section (identification/interaction_fit.h) replaces the
// ship file's values of the keys it has: t_P, w_P0 (propeller), epsilon,
// kappa, gamma_R_minus, gamma_R_plus, l_R_prime, t_R, a_H, x_H_prime, f_alpha (rudder).
//
// The hull section of a published ship file is a reference set: it was not
// checked against this project's CFD.
#pragma once

#include <array>
#include <filesystem>
#include <map>
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

// The largest |drift angle| atan2(|v|, u) and |r'| = |r| Lpp / U of a set of
// motions: those a set was identified over (fit.range, written by kelvin
// identify from its captive runs; a maneuver beyond them flies the
// derivatives extrapolated), or those a maneuver reached.
struct MotionRange {
  double drift = 0.0;    // rad
  double r_prime = 0.0;  // r Lpp / U
  // Widens the range to the motion (u, v, r) of a ship of length Lpp; a
  // motion at rest is skipped.
  void Include(double u, double v, double r, double Lpp);
};

struct DerivativeSet {
  std::string file;
  std::string name;
  std::string ship;        // derivative_set.ship: the ship it was identified for ("" if the set names none)
  std::string ship_where;  // "file:line" of that key, for messages
  HullCoefficients<double> hull;
  std::map<std::string, double> interaction;  // the keys above
  std::optional<DerivativeCheck> check;
  std::optional<MotionRange> range;  // fit.range; sets written before it existed have none
};

// The interaction keys a set may carry, in ship-file order.
inline constexpr std::array<const char*, 11> kInteractionKeys = {
    "t_P", "w_P0", "epsilon", "kappa", "gamma_R_minus", "gamma_R_plus", "l_R_prime", "t_R", "a_H", "x_H_prime",
    "f_alpha"};
// The propeller's and rudder's fields of kInteractionKeys, in that order.
std::array<double*, kInteractionKeys.size()> InteractionFields(PropellerParameters& propeller,
                                                               RudderParameters& rudder);
// Replaces the ship's values of the keys in `interaction` (each one of kInteractionKeys).
void ApplyInteraction(const std::map<std::string, double>& interaction, ShipParameters& ship);

// Loads a derivative file; throws kelvin::ConfigError naming the file, line
// and key for an unknown key, a missing derivative or a non-number.
DerivativeSet LoadDerivativeSet(const std::filesystem::path& path);
// The same from a derivative file already parsed (`path` names it).
DerivativeSet LoadDerivativeSet(const data::ConfigNode& root, const std::filesystem::path& path);

}  // namespace kelvin::sim
