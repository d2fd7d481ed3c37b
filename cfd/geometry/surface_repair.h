// Repair of the defects CAD exports leave in hull surfaces, before the
// checks of ValidateHull (cfd/grid/README.md, "Bringing your own hull").
// What it changes, and what it refuses:
//
//   near-duplicate vertices   merged when closer than merge_tolerance (a crack
//                             of float round-off between two patches);
//   tiny edges                collapsed when shorter than short_edge (CAD
//                             micrometre edges at patch corners);
//   slivers and caps          zero-area triangles, and triangles with an angle
//                             near 180 degrees lower than short_edge, removed
//                             by edge flips and collapses (CGAL's
//                             Polygon_mesh_processing);
//   duplicate triangles       removed (CGAL repair_polygon_soup);
//   inconsistent orientation  triangles flipped to agree with their
//                             neighbours (CGAL orient_polygon_soup); the
//                             outward sense is then set by ValidateHull from
//                             the sign of the immersed volume;
//   self-intersections        refused when both triangles reach below the
//                             waterline (exact predicates, CGAL); above it
//                             the hull is outside the domain and they are
//                             only counted.
// Open edges below the waterline are left for ValidateHull to refuse: closing
// a hole would invent hull shape. On a surface with non-manifold edges (a
// rudder joined along an edge), orienting and sliver removal treat the parts
// meeting there separately; the whole surface then keeps the sense it had
// (by the sign of its immersed volume), but a part that was inside out on
// its own stays so and shows in the hydrostatics.
#pragma once

#include <cstddef>
#include <string>

#include "cfd/geometry/triangle_surface.h"

namespace kelvin::cfd {

struct RepairOptions {
  // Lengths in the surface's units (metres in ship axes). A value <= 0 takes
  // the default: merge_tolerance 1e-6 and short_edge 1e-5 of the diagonal of
  // the surface's bounding box.
  double merge_tolerance = 0;
  double short_edge = 0;
  double waterline_z = 0;  // self-intersections are refused below this
};

struct RepairReport {
  double merge_tolerance = 0;  // lengths actually used
  double short_edge = 0;
  std::size_t merged_vertices = 0;      // near-duplicates merged into another vertex
  std::size_t collapsed_edges = 0;      // edges shorter than short_edge collapsed
  std::size_t removed_triangles = 0;    // degenerate or duplicate triangles dropped
  std::size_t fixed_slivers = 0;        // slivers and caps removed by edge flips and collapses
  std::size_t reoriented_triangles = 0; // flipped to agree with their neighbours
  std::size_t self_intersections_above = 0;  // pairs above the waterline (allowed)
  bool Changed() const;
  std::string Summary() const;  // one line, "no change" when nothing was done
};

// Returns the repaired surface; throws kelvin::DataFileError naming
// surface.source and the first offending location for self-intersections
// below the waterline.
TriangleSurface RepairSurface(const TriangleSurface& surface, const RepairOptions& options,
                              RepairReport* report = nullptr);

}  // namespace kelvin::cfd
