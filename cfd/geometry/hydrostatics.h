// Hydrostatics of a hull surface at its design waterline, in ship axes:
// x forward from the aft perpendicular, z up with the calm waterline at
// z = 0. Integrals use the divergence theorem on the part of the surface
// below z = 0 (the waterplane cap contributes nothing to the z-weighted
// integrals), so they are exact for the triangulated surface.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "cfd/geometry/surface_repair.h"
#include "cfd/geometry/triangle_surface.h"

namespace kelvin::cfd {

struct Hydrostatics {
  double volume = 0;           // m^3, displacement volume
  double wetted_area = 0;      // m^2
  double waterplane_area = 0;  // m^2
  double lcb = 0;              // m, longitudinal centre of buoyancy from AP
  double lcf = 0;              // m, longitudinal centre of flotation from AP
  double draft = 0;            // m, deepest point below the waterline
  double lwl = 0;              // m, waterline length
  double bwl = 0;              // m, waterline beam
  double x_min = 1e300;        // m from AP, aftmost point below the waterline
  double x_max = -1e300;       // m from AP, foremost point below the waterline
  double Cb = 0;               // volume / (Lpp B T)
  double Cm = 0;               // midship section area / (B T)
  double Cwp = 0;              // waterplane area / (Lpp B)
  double Cp = 0;               // volume / (A_M Lpp)
  std::vector<std::pair<double, double>> sectional_areas;  // (x from AP, area below z = 0)

  std::string Report() const;
};

// The immersed polygon (z <= 0) of one triangle, as a fan of triangles.
std::vector<std::array<Eigen::Vector3d, 3>> ClipBelowWaterline(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                                               const Eigen::Vector3d& c);
// Signed underwater volume (positive when the normals point out of the hull).
double UnderwaterVolume(const TriangleSurface& surface);
// Area below z = 0 of the section x = x_section.
double SectionArea(const TriangleSurface& surface, double x_section);

// Hydrostatics with the coefficients based on Lpp, B and T from the ship
// definition and the midship section at Lpp / 2.
Hydrostatics ComputeHydrostatics(const TriangleSurface& surface, double Lpp, double B, double T, int stations = 21);

// Where a ship file's hull surface is and how it maps to ship axes
// (section `geometry` of data/ships/<ship>.yaml). The file's coordinates are
// first multiplied by length_unit; x_ap and waterline_z are in metres after
// that scaling (not in file units). A file point p maps to ship axes as
//   x = s (length_unit p_x - x_ap),  y = s length_unit p_y,
//   z = length_unit p_z - waterline_z,   s = +1 for bow_direction "+x", -1 for "-x".
struct HullPlacement {
  std::filesystem::path file;  // resolved path
  double length_unit = 1.0;    // metres per file unit
  double x_ap = 0.0;           // m: x of the aft perpendicular, file x times length_unit
  double waterline_z = 0.0;    // m: z of the design waterline, file z times length_unit
  bool bow_towards_minus_x = false;
  double Lpp = 0, B = 0, T = 0;  // from `principal`
  double displacement = 0;       // m^3 from `principal` (0: not given)
  double scale = 1;              // model scale ratio
  std::string name;
  bool repair = true;            // geometry.repair: repair CAD defects before the checks
  bool submerged = false;        // geometry.submerged: a closed body entirely below z = 0 is meant
  RepairOptions repair_options;  // geometry.merge_tolerance, geometry.short_edge (m)
};

// Reads the `ship`, `principal` and `geometry` sections of a ship file.
HullPlacement LoadHullPlacement(const std::filesystem::path& ship_file);
// Reads the surface and transforms it to ship axes (x from AP forward, z up
// from the waterline), repairs it (unless placement.repair is false) and
// validates it as a hull.
TriangleSurface LoadHull(const HullPlacement& placement, SurfaceCheck* check = nullptr,
                         RepairReport* repair = nullptr);

// Half-beam of the Wigley hull y = (B/2)(1 - (2x/L - 1)^2)(1 - (z/T)^2) at x
// from AP; 0 outside 0 < x < L. Not limited in z: callers decide the range.
double WigleyHalfBeam(double L, double B, double T, double x, double z);

// The Wigley parabolic hull y = (B/2)(1 - (2x/L)^2)(1 - (z/T)^2), closed by a
// flat deck at z = freeboard, with nx x nz panels per side; x from AP.
TriangleSurface WigleySurface(double L, double B, double T, double freeboard, int nx, int nz);

}  // namespace kelvin::cfd
