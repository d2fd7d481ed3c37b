// YAML seeds: the ship, case, mesh case and campaign files under data/, sorted
// by their name, and a derivative set made from the KVLCC2 ship file.
#include <fmt/format.h>

#include "simulator/mmg/ship_parameters.h"
#include "tests/fuzz/seeds/seeds.h"

namespace kelvin::fuzz {
namespace {

namespace fs = std::filesystem;

// The fuzz target a data/ YAML file seeds.
std::string TargetOf(const fs::path& file) {
  const std::string name = file.filename().string();
  if (name.find("campaign") != std::string::npos || name.find("captive") != std::string::npos) return "campaign_yaml";
  if (name.find("mesh") != std::string::npos || file.parent_path().filename() == "mesh") return "mesh_case_yaml";
  if (name.find("ship") != std::string::npos || file.parent_path().filename() == "ships") return "ship_yaml";
  return "case_yaml";
}

std::string DerivativeSet(const sim::ShipParameters& ship) {
  std::string y = fmt::format("derivative_set:\n  name: {}\n  ship: {}\nhull:\n", ship.name, ship.name);
  for (int i = 0; i < sim::HullCoefficients<double>::kCount; ++i) {
    y += fmt::format("  {}: {}\n", sim::HullCoefficients<double>::kNames[i], ship.hull[i]);
  }
  return y + "check:\n  passed: true\n  reference: fuzz seed\n  date: 2024-01-01\n  summary: ok\n";
}

}  // namespace

void WriteYamlSeeds(const fs::path& source_dir, const fs::path& out) {
  for (const auto& e : fs::recursive_directory_iterator(source_dir / "data")) {
    if (e.path().extension() != ".yaml") continue;
    const std::string name = fs::relative(e.path(), source_dir / "data").string();
    std::string flat = name;
    for (char& c : flat) c = c == '/' ? '_' : c;
    WriteSeed(out / TargetOf(e.path()), flat, ReadBytes(e.path()));
  }
  const sim::ShipParameters kvlcc2 = sim::LoadShip(source_dir / "data/ships/kvlcc2.yaml");
  WriteSeed(out / "derivative_set_yaml", "kvlcc2.yaml", DerivativeSet(kvlcc2));
}

}  // namespace kelvin::fuzz
