// Built-in hull-fitted block-structured hexahedral grid for the double-body
// domain below the calm waterline (z <= 0), both sides of the hull.
//
// Topology (H-H with hull-fitted lines): the domain is a stack of transverse
// stations x = const. Each station is split at the centreplane y = 0 into a
// port and a starboard block. A block's inner boundary is the hull section
// from the waterline down to the keel, continued along the centreplane from
// the keel to the bottom; ahead of the bow and behind the stern it is the
// whole centreplane, where the port and starboard cells simply share their
// faces (an H-grid). Grid lines leave the inner boundary close to the wall
// normal and turn horizontal away from the hull; their tilt is smoothed
// along the girth so that neighbouring lines never cross, which keeps the
// cells at the sharp keel, bow and stern well shaped. The girth lines end on
// the side planes y = +-W. Refinement: wall-normal first spacing from a
// target y+ with geometric growth, clustering at bow and stern and under the
// free surface z = 0.
//
// Patches: hull (wall), freeSurface (z = 0), inlet (x max, ahead of the bow),
// outlet (x min), side (y = +-W), bottom (z = -D).
#pragma once

#include "cfd/turbulence/wall_stats.h"

#include "cfd/grid/hull_sections.h"
#include "cfd/mesh/mesh.h"

namespace kelvin::cfd {

struct HullGridOptions {
  // Domain extent in hull lengths L (= x_fore - x_aft).
  double upstream = 1.0;    // inlet at x_fore + upstream L
  double downstream = 2.0;  // outlet at x_aft - downstream L
  double half_width = 1.0;  // side planes at y = +-half_width L
  double depth = 1.0;       // bottom at z = -depth L
  // Cells.
  int cells_hull = 60;        // along the hull (x)
  int cells_upstream = 15;    // bow to inlet
  int cells_downstream = 30;  // stern to outlet
  int cells_girth = 24;       // each side, waterline to keel
  int cells_below_keel = 16;  // keel to bottom
  int cells_normal = 32;      // hull (or centreplane) to side
  // Spacing at bow and stern relative to the mean L / cells_hull.
  double end_spacing = 0.25;
  // Vertical spacing at z = 0 and at the keel relative to the mean draft / cells_girth.
  double free_surface_spacing = 0.3;
  double keel_spacing = 0.6;
  // Free-surface waves: with wave_froude > 0, the spacing ahead of the bow,
  // behind the stern and from the hull to the sides grows from its first
  // cell only up to the transverse wavelength 2 pi Fn^2 L over
  // cells_per_wave and then stays uniform (CappedGeometricNodes), so the
  // Kelvin pattern is resolved over the whole free surface; the cell counts
  // must then be large enough to cover the domain at that spacing (the
  // error names the count needed). 0: plain geometric growth.
  double wave_froude = 0.0;
  double cells_per_wave = 16.0;
  // First wall-normal cell height from a target y+ at Re = U L / nu (see
  // FirstCellHeight: ITTC-57 friction).
  double y_plus = 1.0;
  double reynolds = 5e6;
  // Throws ConfigError naming the option, the value and the valid range.
  void Validate() const;
  // The options coarsened by `ratio` in every direction: cell counts divided
  // by ratio (rounded, at least 1) and the first wall spacing (so y+)
  // multiplied by it. Relative spacings scale with the cell counts.
  HullGridOptions Coarsened(double ratio) const;
  int CellCount() const;
};

// Mesh information that the report needs beyond Mesh::Quality().
struct HullGridInfo {
  double first_cell_height = 0;  // m, target first wall-normal cell height
  double max_line_tilt_deg = 0;  // largest initial tilt of a girth line
};

// Builds the grid. Throws DataFileError if the hull cannot be gridded by
// this topology (a section that does not reach the waterline, does not
// contain the centreplane, or has flat parts; use the snappyHexMesh path).
Mesh MakeHullGrid(const HullSections& hull, const HullGridOptions& options,
                  HullGridInfo* info = nullptr);

// Volume enclosed by the `hull` patch and the waterplane z = 0 (m^3):
// -sum over the hull faces of z_t S_t,z over the triangles each face is
// split into around its centre (the cap on z = 0 adds nothing).
double HullPatchVolume(const Mesh& mesh);

// y+ of the first cell centres on the `hull` patch (wall distance of the
// owner cell centre, y+ from the ITTC-57 estimate at `reynolds` over
// `length`): min, mean (area weighted), max and the area by y+ band, so the
// wall guard (cfd/turbulence/wall_stats.h) can warn before a run.
struct YPlusEstimate {
  double min = 0, mean = 0, max = 0;
  WallPatchStats stats;
};
YPlusEstimate EstimateYPlus(const Mesh& mesh, double reynolds, double length);

}  // namespace kelvin::cfd
