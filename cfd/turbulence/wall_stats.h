// y+ statistics of a wall patch, by area, and the guard that says when the
// first cells leave the range kelvin's wall treatment is valid for.
//
// The treatment (Spalding's law, wall_functions.h) covers the viscous
// sublayer, the buffer layer and the log layer in the momentum equation, but
// the flat plate (Re_L 1e7, BENCHMARKS.md `flat_plate_peer`) shows where the
// friction is right: C_F within 1% of Schoenherr's line at y+ 20-100 and
// within 2% at y+ 0.25-2 (with the sublayer-consistent wall omega,
// wall_functions.h; the point value of OpenFOAM's omegaWallFunction is 4-10%
// low there), and no steady state at y+ 5 and 10 (21% high at 10): the wall
// cell's omega and production switch between the sublayer and the log law
// there. The buffer guard fires when more than 10% of a wall's area has its
// first cell strictly between the nearest first-cell heights measured good
// on either side, y+ 2 and 20. The upper limit is
// the end of the log layer, near 0.1-0.2 of the boundary
// layer thickness in wall units: at the DTC's model Reynolds number (9e6)
// delta+ is about 3000 at mid-length (delta = 0.37 x Re_x^-0.2, u_tau from
// C_F = 0.003), and smaller forward, so a first cell centre beyond y+ = 300
// sits in the outer (wake) layer over much of the hull, where the log law
// underpredicts u+ and the wall shear comes out wrong. The guard fires when
// more than 10% of a wall's area lies beyond that limit.
#pragma once

#include <array>
#include <span>
#include <string>

namespace kelvin::cfd {

inline constexpr std::array<double, 6> kYPlusBandEdges{1, 5, 30, 100, 300, 1000};
inline constexpr double kWallYPlusLimit = 300;
inline constexpr double kWallAreaBeyondLimit = 0.10;
// The buffer layer, where the plate reaches no steady state (open interval).
inline constexpr double kBufferYPlusLow = 2;
inline constexpr double kBufferYPlusHigh = 20;

// y+ and wall shear statistics of one wall patch.
struct WallPatchStats {
  std::string patch;
  double y_plus_min = 0.0;
  double y_plus_mean = 0.0;  // area weighted
  double y_plus_max = 0.0;
  // Share of the patch area in each band [0, 1), [1, 5), ..., [1000, inf).
  std::array<double, kYPlusBandEdges.size() + 1> area_fraction{};
  double AreaBeyond(double y_plus) const;  // share of the area at or above an edge of the bands
  double buffer_fraction = 0.0;  // share of the area with kBufferYPlusLow < y+ < kBufferYPlusHigh
};

// Statistics of a patch from the first-cell y+ and the area of each face.
WallPatchStats SummarizeWall(const std::string& patch, std::span<const double> y_plus,
                             std::span<const double> area);
// "y+ on hull by area: <1 0.0%, 1-5 0.0%, ..., >=1000 2.1%"
std::string YPlusDistribution(const WallPatchStats& s);
// A loud warning when more than kWallAreaBeyondLimit of the area is beyond
// kWallYPlusLimit, another when as much lies in the buffer layer (one line
// each); empty otherwise.
std::string YPlusWarning(const WallPatchStats& s);

}  // namespace kelvin::cfd
