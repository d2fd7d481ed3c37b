// The snappyHexMesh path for hulls the structured generator cannot grid
// (bulbous bows, transoms, appendages) and for bodies entirely below z = 0
// (submarines, towed bodies): writes an OpenFOAM case for the
// double-body domain below z = 0 (blockMesh background box with its top on
// the calm waterline, so the hull is cut there; snappyHexMesh refinement on
// the hull, refinement boxes for the Kelvin wake, prism layers sized from a
// target y+), runs Debian's OpenFOAM tools serially, and reads the polyMesh.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "cfd/geometry/triangle_surface.h"
#include "cfd/mesh/mesh.h"

namespace kelvin::cfd {

// A box refined to `level` throughout (snappyHexMesh refinementRegions,
// mode inside), in the mesh's frame (m): the frame of the hull as placed,
// the one quality.txt and mesh.vtu use. It refines the hull's faces inside
// it as well, so a bulb, a stagnation point or a rudder gets finer cells
// than the rest of the hull.
struct SnappyBox {
  Eigen::Vector3d min = Eigen::Vector3d::Zero();
  Eigen::Vector3d max = Eigen::Vector3d::Zero();
  int level = 0;
};

struct SnappyOptions {
  // Domain extent in hull lengths L, as for the structured grid.
  double upstream = 1.0;
  double downstream = 2.0;
  double half_width = 1.0;
  double depth = 1.0;
  // Background blockMesh cells per hull length (cubes as far as the domain
  // allows).
  int base_cells_per_length = 10;
  // snappyHexMesh refinement level on the hull surface (cell size halves
  // per level) and in the Kelvin wake box; a near-hull box gets the level
  // between them.
  int hull_level = 3;
  int wake_level = 1;
  // Level of the near-hull box; kAutoLevel: (hull_level + wake_level + 1) / 2.
  static constexpr int kAutoLevel = -1;
  int near_level = kAutoLevel;
  // Refinement boxes beyond the hull, near and wake levels (none by
  // default). A family keeps their levels, so their cells coarsen with the
  // base cells like the rest of the grid.
  std::vector<SnappyBox> boxes;
  // Prism layers on the hull, sized relative to the hull cell size
  // (snappyHexMesh relativeSizes, finalLayerThickness = final_layer_ratio):
  // the layers shrink by the expansion ratio from the outermost towards the
  // wall. final_layer_ratio = 0 (from y+): the ratio that makes the first
  // layer the height for the target y_plus (FirstCellHeight). layers = -1
  // (auto): the fewest layers whose outermost reaches half the hull cell
  // size. Relative sizes let snappyHexMesh keep the layers on most of the
  // hull and, with the layer count and ratio of grid 1 kept, make a grid
  // family geometrically similar (the first-layer y+ grows with the cells).
  static constexpr int kAutoLayers = -1;
  int layers = kAutoLayers;
  double final_layer_ratio = 0.0;
  double expansion_ratio = 1.2;
  double y_plus = 60.0;
  double reynolds = 5e6;
  // Waves (0: none): the transverse wavelength lambda = 2 pi U^2 / g (m).
  // The domain then reaches at least kWaveUpstream lambda ahead of the body,
  // kWaveDownstream lambda behind it, kWaveHalfWidth lambda to each side and
  // kWaveDepth lambda deep (the domain options in lengths still hold as
  // minimums), and the free-surface box (the Kelvin wedge from just ahead of
  // the body to the outlet, lambda / 6 deep) is refined until its cells are
  // at most lambda / cells_per_wavelength, whatever wake_level says.
  double wavelength = 0.0;
  double cells_per_wavelength = 16.0;
  static constexpr double kWaveUpstream = 1.0;
  static constexpr double kWaveDownstream = 3.0;
  static constexpr double kWaveHalfWidth = 1.5;
  static constexpr double kWaveDepth = 0.5;
  // Surface features sharper than this angle (degrees) are snapped to.
  double feature_angle = 30.0;
  // OpenFOAM environment script.
  std::string openfoam_bashrc = "/usr/share/openfoam/etc/bashrc";
  // Throws ConfigError naming the option, the value and the valid range.
  void Validate() const;
};

// Timings and logs of a snappy run.
struct SnappyRun {
  double seconds_block_mesh = 0;
  double seconds_features = 0;
  double seconds_snappy = 0;
  double hull_cell = 0;              // m, hull surface cell size
  double first_layer_thickness = 0;  // m, requested (SnappyFirstLayer)
  int layers = 0;                    // requested prism layers
  double final_layer_ratio = 0;      // requested outermost layer / hull cell
  int wake_level = 0;                // of the Kelvin-wedge box (SnappyWakeLevel)
  double wake_cell = 0;              // m, cell size there
  // What snappyHexMesh kept, from the layer table at the end of its log
  // (negative when the log has no table): mean layers per hull face and the
  // kept share of the requested layer thickness (%).
  double layers_kept = -1;
  double thickness_kept_percent = -1;
  // From snappyHexMesh's per-face layer counts (0/nSurfaceLayers; negative
  // when it wrote none): the hull-area-weighted mean count kept, as a share
  // of the requested count (%), and the share of the hull area with no
  // layer at all (%), where the first cell is a snapped background cell.
  double layers_area_percent = -1;
  double area_without_layers_percent = -1;
};

// The number of layers WriteSnappyCase requests for `options` and a hull of
// length `length`.
int SnappyLayerCount(const SnappyOptions& options, double length);

// The refinement level of the Kelvin-wedge (free-surface) box: wake_level,
// raised until the cells there are at most wavelength /
// cells_per_wavelength when options.wavelength > 0.
int SnappyWakeLevel(const SnappyOptions& options, double length);

// The hull surface cell size length / base_cells_per_length / 2^hull_level.
double SnappyHullCell(const SnappyOptions& options, double length);

// The outermost layer thickness relative to the hull cell that
// WriteSnappyCase requests (options.final_layer_ratio, or the ratio that
// makes the first layer FirstCellHeight(y_plus)).
double SnappyFinalLayerRatio(const SnappyOptions& options, double length);

// The requested first layer thickness (m):
// final ratio * hull cell / expansion_ratio^(layers - 1).
double SnappyFirstLayer(const SnappyOptions& options, double length);

// Reads the final layer table of a snappyHexMesh log ("hull <faces> <mean
// layers> <thickness> <percent>"): mean layers kept on `patch` and the kept
// share of the layer thickness in %. Returns false if the log has no table.
bool ReadSnappyLayerTable(const std::filesystem::path& log, const std::string& patch,
                          double* layers, double* thickness_percent);

// Reads the per-face layer counts of `patch` from the nSurfaceLayers field
// snappyHexMesh writes with writeFlags (layerFields) (uniform or
// nonuniform List<scalar>). Returns an empty vector when the file is
// missing; throws DataFileError naming the file when it is malformed.
std::vector<double> ReadSnappyFaceLayers(const std::filesystem::path& field, const std::string& patch,
                                         int faces);

// Writes the case into `case_dir` (created; an existing polyMesh there is
// replaced): constant/triSurface/hull.stl and the system dictionaries. The
// hull is in ship axes (x forward from the aft end, z up from the waterline).
void WriteSnappyCase(const TriangleSurface& hull, const SnappyOptions& options,
                     const std::filesystem::path& case_dir);

// Writes the case, runs blockMesh, surfaceFeatureExtract and snappyHexMesh
// (logs in case_dir/log.*) and reads the polyMesh. Throws DataFileError
// naming the tool, its log and the log's last lines when a tool fails.
Mesh RunSnappy(const TriangleSurface& hull, const SnappyOptions& options,
               const std::filesystem::path& case_dir, SnappyRun* run = nullptr);

}  // namespace kelvin::cfd
