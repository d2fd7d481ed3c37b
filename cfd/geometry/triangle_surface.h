// Triangulated hull surfaces: reading ASCII and binary STL (optionally
// gzip-compressed) and Wavefront OBJ, welding shared vertices, and the
// topological checks a hull must pass before hydrostatics or meshing.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace kelvin::cfd {

struct TriangleSurface {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside
  std::string source;                         // file name, for messages

  Eigen::Vector3d Normal(std::size_t t) const;  // area-weighted (|n| = 2 area)
  double Area(std::size_t t) const;
  Eigen::Vector3d Min() const;
  Eigen::Vector3d Max() const;
};

// Reads STL (ASCII or binary, detected from the content; .gz compressed
// files are read through zlib) or OBJ (by extension; polygons are fan
// triangulated). Throws kelvin::DataFileError naming the file, the line or
// triangle, the value and what was expected: truncated files, wrong counts,
// non-finite vertices, no triangles.
TriangleSurface ReadSurface(const std::filesystem::path& path);
TriangleSurface ReadStl(const std::filesystem::path& path);
TriangleSurface ReadObj(const std::filesystem::path& path);
// The same from the bytes of a file already in memory (gzip data is
// decompressed); `name` names the file in messages.
TriangleSurface ParseStl(const std::string& bytes, const std::filesystem::path& name);
TriangleSurface ParseObj(const std::string& bytes, const std::filesystem::path& name);

// Welds vertices with identical coordinates (the readers' welding), keeping
// only the vertices triangles use, in order of first use, and dropping the
// triangles that lose a corner to the weld.
void WeldIdenticalVertices(TriangleSurface& surface);

// Writes a binary STL atomically.
void WriteStl(const TriangleSurface& surface, const std::filesystem::path& path);

struct SurfaceCheck {
  std::size_t open_edges = 0;          // edges used by one triangle
  std::size_t open_edges_below = 0;    // ... of which some part lies below the waterline
  std::size_t non_manifold_edges = 0;  // edges used by more than two triangles (e.g. rudder junction)
  std::size_t inconsistent_edges = 0;  // edges traversed twice in the same direction
  std::size_t degenerate_triangles = 0;
  double underwater_volume = 0;        // below the waterline; < 0 if the normals point inward
  bool flipped = false;                // ValidateHull reversed inward-pointing normals
  std::string Summary() const;
};

// Topology and orientation of a surface, with the waterline at z = waterline_z.
SurfaceCheck CheckSurface(const TriangleSurface& surface, double waterline_z);

// Throws DataFileError (naming the file and the first offending edge or
// triangle) if the hull cannot be used: open edges below the waterline,
// inconsistent normals, degenerate triangles, or a hull that does not cross
// the waterline. Non-manifold edges (a rudder joined to the hull) and open
// edges above the waterline are allowed. With `submerged_allowed`, a body
// entirely below the waterline is accepted too, if it is closed (no open
// edge at all); without it such a body is refused (a ship hull placed too
// deep). Flips the surface if its normals point inward. Returns the check
// for reporting.
SurfaceCheck ValidateHull(TriangleSurface& surface, double waterline_z, bool submerged_allowed = false);

}  // namespace kelvin::cfd
