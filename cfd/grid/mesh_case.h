// Mesh case files (YAML) and the `kelvin mesh` job: builds the structured
// hull-fitted grid or runs the snappyHexMesh path, for one grid or a family
// with a constant refinement ratio, and writes each grid as an OpenFOAM
// polyMesh, a .vtu and a quality report.
//
//   mesh:
//     method: structured        # structured | snappy
//     hull:                     # exactly one of
//       wigley: {length: 2.5, beam: 0.25, draft: 0.15625}
//       ship: ../ships/dtc.yaml  # a ship file with a geometry section
//       spheroid: {length: 1.0, diameter: 0.2, depth: 0.25}  # submerged; snappy only
//     flow:                     # for the wall spacing: reynolds, or speed (+ viscosity)
//       reynolds: 5.0e6
//     y_plus: 1.0
//     domain: {upstream: 1, downstream: 2, half_width: 1, depth: 1}   # hull lengths
//     structured: {cells_hull: 60, ...}   # HullGridOptions
//     snappy: {base_cells_per_length: 10, hull_level: 3, ...}   # SnappyOptions
//     waves: {froude: 0.316, cells_per_wavelength: 16}   # optional; Fn on the hull length
//     family: {ratio: 1.41421356, layers: similar}   # or first_layer (snappy)
//   output:
//     directory: grids/wigley   # relative to the case file
//     vtu: true
//
// Paths are relative to the case file. Unknown keys are errors that list the
// valid ones.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cfd/geometry/spheroid_surface.h"
#include "cfd/geometry/triangle_surface.h"
#include "cfd/grid/hull_grid.h"
#include "cfd/grid/snappy_mesher.h"

namespace kelvin::cfd {

enum class MeshMethod { kStructured, kSnappy };
enum class FamilyLayers { kSimilar, kSameFirstLayer };

struct MeshCase {
  std::string source;  // case file, for messages
  MeshMethod method = MeshMethod::kStructured;
  // Hull: the Wigley formula, a submerged spheroid, or a ship file (surface
  // placed by LoadHull).
  bool wigley = false;
  double wigley_length = 0, wigley_beam = 0, wigley_draft = 0;  // m
  bool spheroid = false;
  SpheroidShape spheroid_shape;
  std::filesystem::path ship_file;
  // Replaces the ship file's geometry.file when set (`kelvin mesh --hull`):
  // hulls the project cannot ship, such as the KCS, come from the user.
  std::filesystem::path hull_file;
  double reynolds = 0;
  double y_plus = 1.0;
  HullGridOptions structured;  // domain, reynolds and y_plus filled in
  SnappyOptions snappy;        // domain, reynolds and y_plus filled in
  double family_ratio = 1.4142135623730951;
  // snappy families: kSimilar keeps grid 1's layer count and thickness
  // relative to the cells (the first-layer y+ grows with the cells);
  // kSameFirstLayer sizes each grid's layers from y_plus as grid 1's (the
  // same first-layer height on every grid, more layers on the coarser
  // ones); the y+ still rises on the coarser grids where snappyHexMesh
  // keeps fewer of the layers.
  FamilyLayers family_layers = FamilyLayers::kSimilar;
  std::filesystem::path output_directory;
  bool write_vtu = true;
};

// The hull length the case's Reynolds and Froude numbers are based on: the
// Wigley's or spheroid's length, or the ship file's Lpp.
double HullLength(const MeshCase& mesh_case);

// Reads and checks a case file. Throws ConfigError naming the file, the line,
// the key, the value and what was expected.
MeshCase LoadMeshCase(const std::filesystem::path& path);
MeshCase ParseMeshCase(const std::string& yaml_text, const std::string& source,
                       const std::filesystem::path& base_dir);

// One written grid of a family (grid 1 is the finest).
struct GridSummary {
  int level = 1;
  std::filesystem::path directory;
  MeshQuality quality;
  double hull_volume = 0;  // m^3, enclosed by the hull patch and z = 0
  YPlusEstimate y_plus;
  double seconds = 0;  // meshing time (grid generation or OpenFOAM tools)
  SnappyRun snappy;    // per-tool times of the snappy path
  double h = 0;        // (V / N)^(1/3), m
  std::string report;  // the text of quality.txt
};

// Builds `family` grids (1 = just the case's grid; grid g is coarsened by
// ratio^(g-1)) and writes them to the output directory (grid<g>/ subfolders
// when family > 1) with quality.txt and, if asked, mesh.vtu. Returns their
// summaries; writes family.txt for a family.
std::vector<GridSummary> RunMeshCase(const MeshCase& mesh_case, int family,
                                     const std::filesystem::path& output_override = {});

}  // namespace kelvin::cfd
