// kelvin mesh: builds the grid (or a grid family) of a mesh case file with
// the built-in hull-fitted generator or the snappyHexMesh path, and writes
// polyMesh, .vtu and a quality report per grid.
#include <fmt/format.h>

#include <memory>
#include <string>

#include "cfd/grid/mesh_case.h"
#include "data/schema/errors.h"
#include "tools/kelvin/commands.h"

namespace kelvin::cli {

namespace {

struct MeshArgs {
  std::string case_file;
  int family = 1;
  std::string output;
  std::string hull;
};

void RunMesh(const MeshArgs& a) {
  cfd::MeshCase c = cfd::LoadMeshCase(a.case_file);
  if (!a.hull.empty()) {
    if (c.wigley || c.spheroid) {
      throw ArgumentError(
          fmt::format("--hull {}: the mesh case {} uses the {} formula, not a ship file", a.hull,
                      a.case_file, c.wigley ? "Wigley" : "spheroid"));
    }
    c.hull_file = a.hull;
  }
  const auto grids = cfd::RunMeshCase(c, a.family, a.output);
  for (const auto& g : grids) {
    fmt::print("grid {}: {}\n{}\n", g.level, g.directory.string(), g.report);
  }
  if (grids.size() > 1) {
    fmt::print("family: {} grids, ratio {:.6g}; cells", grids.size(), c.family_ratio);
    for (const auto& g : grids) fmt::print(" {}", g.quality.n_cells);
    fmt::print("\n");
  }
}

}  // namespace

Command AddMeshCommand(CLI::App& app) {
  auto args = std::make_shared<MeshArgs>();
  CLI::App* cmd = app.add_subcommand("mesh",
                                     "Build the double-body grid of a mesh case (built-in "
                                     "hull-fitted generator or snappyHexMesh)");
  cmd->add_option("case", args->case_file, "Mesh case file (YAML with sections mesh and output)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--family", args->family,
                  "Number of grids with the case's refinement ratio (grid 1 finest)")
      ->check(CLI::Range(1, 6))
      ->capture_default_str();
  cmd->add_option("-o,--output", args->output, "Output directory (overrides output.directory)");
  cmd->add_option("--hull", args->hull,
                  "Hull surface (STL/OBJ, gzip) replacing geometry.file of the case's ship file, placed by that "
                  "file's geometry section (e.g. a user-supplied KCS hull)")
      ->check(CLI::ExistingFile);
  return {cmd, [args] { RunMesh(*args); }};
}

}  // namespace kelvin::cli
