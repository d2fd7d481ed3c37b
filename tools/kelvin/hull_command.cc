// kelvin hull: checks a ship's hull surface and prints its hydrostatics at
// the design waterline (a first sanity check before meshing).
#include <fmt/format.h>

#include <memory>
#include <string>

#include "cfd/geometry/hull_intake.h"
#include "data/schema/h5_file.h"
#include "tools/kelvin/commands.h"

namespace kelvin::cli {

namespace {

struct HullArgs {
  std::string ship_file;
  std::string hull_file;
  int stations = 21;
  std::string output;
  bool no_repair = false;
};

void RunHull(const HullArgs& a) {
  cfd::HullPlacement placement = cfd::LoadHullPlacement(a.ship_file);
  if (!a.hull_file.empty()) placement.file = a.hull_file;
  if (a.no_repair) placement.repair = false;
  const cfd::HullIntake in = cfd::TakeInHull(placement, a.stations);
  const cfd::Hydrostatics& h = in.hydrostatics;
  fmt::print("{}: {}\n{}{}", placement.name, placement.file.string(), in.Report(), h.Report());
  for (const auto& w : in.warnings) fmt::print(stderr, "kelvin hull: WARNING: {}\n", w);
  if (!a.output.empty()) {
    data::H5Writer out(a.output);
    out.SetAttribute("/", "kelvin_schema", "hydrostatics/1");
    out.SetAttribute("/", "ship", placement.name);
    const std::pair<const char*, std::pair<double, const char*>> scalars[] = {
        {"volume", {h.volume, "m^3"}},        {"wetted_area", {h.wetted_area, "m^2"}},
        {"waterplane_area", {h.waterplane_area, "m^2"}}, {"lcb", {h.lcb, "m"}},
        {"lcf", {h.lcf, "m"}},                {"draft", {h.draft, "m"}},
        {"Cb", {h.Cb, "1"}},                  {"Cm", {h.Cm, "1"}},
        {"Cwp", {h.Cwp, "1"}},                {"Cp", {h.Cp, "1"}}};
    for (const auto& [name, value] : scalars) {
      out.WriteArray(name, std::vector<double>{value.first}, {1}, value.second, name);
    }
    std::vector<double> x, area;
    for (const auto& [xi, ai] : h.sectional_areas) {
      x.push_back(xi);
      area.push_back(ai);
    }
    out.WriteArray("sections/x", x, {x.size()}, "m", "station x from AP");
    out.WriteArray("sections/area", area, {area.size()}, "m^2", "sectional area below the waterline");
    out.Commit();
    fmt::print("  written: {}\n", a.output);
  }
}

}  // namespace

Command AddHullCommand(CLI::App& app) {
  auto args = std::make_shared<HullArgs>();
  CLI::App* cmd = app.add_subcommand("hull", "Check a ship's hull surface and print its hydrostatics");
  cmd->add_option("ship", args->ship_file, "Ship file with a geometry section (data/ships/<ship>.yaml)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--hull", args->hull_file,
                  "Check this surface (STL, STL.gz or OBJ) instead of the ship file's geometry.file, placed by "
                  "the ship file's geometry keys")
      ->check(CLI::ExistingFile);
  cmd->add_flag("--no-repair", args->no_repair,
                "Refuse CAD defects instead of repairing them (as geometry.repair: false)");
  cmd->add_option("--stations", args->stations, "Stations of the sectional area curve")
      ->check(CLI::Range(3, 1000))
      ->capture_default_str();
  cmd->add_option("-o,--output", args->output, "Write the hydrostatics to this HDF5 file");
  return {cmd, [args] { RunHull(*args); }};
}

}  // namespace kelvin::cli
