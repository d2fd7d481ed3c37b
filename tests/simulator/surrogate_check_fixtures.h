// Fixtures for the surrogate check: derivative sets written from a ship
// file's hull (optionally with N_r scaled), and reference maneuver files
// produced by the simulator with such a set, as `kelvin simulate
// --derivatives` produces them.
#pragma once

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "simulator/maneuvers/runner.h"
#include "simulator/mmg/derivative_set.h"
#include "simulator/mmg/surrogate.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::sim::testing {

inline std::filesystem::path ShipFile(const std::string& stem) {
  return kelvin::testing::SourceDir() / "data/ships" / (stem + ".yaml");
}

// A derivative set in the layout of kelvin identify, with the hull of the
// ship file `ship_stem` (N_r times `n_r_factor`), written to `path` with the
// shortest round-trip digits so that the set reproduces the ship exactly.
// `set_ship` is its derivative_set.ship (empty: the ship file's name).
inline std::filesystem::path WriteSetFromShip(const std::filesystem::path& path, const std::string& ship_stem,
                                              double n_r_factor = 1.0, std::string set_ship = "",
                                              const std::string& tail = "") {
  const ShipParameters ship = LoadShip(ShipFile(ship_stem));
  if (set_ship.empty()) set_ship = ship.name;
  std::ofstream f(path);
  f << "# kelvin identify: MMG hull derivatives and added masses (a test set)\n";
  f << "derivative_set:\n  name: " << ship.name << " test set\n  ship: " << set_ship << "\n  source: " << ship_stem
    << ".yaml\nhull:\n";
  for (int i = 0; i < HullCoefficients<double>::kCount; ++i) {
    const std::string key(HullCoefficients<double>::kNames[static_cast<std::size_t>(i)]);
    const double v = key == "N_r" ? ship.hull[i] * n_r_factor : ship.hull[i];
    f << "  " << key << ": " << fmt::format("{}", v) << "  # identified\n";
  }
  f << "standard_errors:\n  N_r: 0.0004\nfit:\n  runs: 7\n  converged: true\n  warnings: []\n" << tail;
  return path;
}

// Runs `maneuver` with the surrogate of `set_file` in the ship file and
// writes the result where kelvin simulate would (dir/<ship>_<maneuver>.h5).
inline std::filesystem::path WriteReference(const std::filesystem::path& dir, const std::string& ship_stem,
                                            const std::filesystem::path& set_file, const std::string& maneuver) {
  const DerivativeSet set = LoadDerivativeSet(set_file);
  const ShipParameters ship = SurrogateShip(LoadShip(ShipFile(ship_stem)), ShipFile(ship_stem).string(), &set);
  const MmgModel<double> model(ship);
  const ManeuverResult r = RunManeuver(model, ManeuverSpec::Parse(maneuver), RunOptions{});
  std::string stem = ship.name + "_" + maneuver;
  for (char& c : stem) {
    if (c == ':' || c == '/') c = '_';
  }
  const std::filesystem::path out = dir / (stem + ".h5");
  WriteManeuverResult(r, out, "cvode");
  return out;
}

}  // namespace kelvin::sim::testing
