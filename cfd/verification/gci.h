// Grid convergence index (Celik et al. 2008, "Procedure for estimation and
// reporting of uncertainty due to discretization in CFD applications",
// J. Fluids Eng. 130:078001; ITTC 7.5-03-01-01): apparent order by fixed
// point, Richardson extrapolation, fine- and medium-grid GCI and the
// asymptotic-range check, from a solution value on three grids.
#pragma once

#include <string>

namespace kelvin::cfd {

enum class Convergence { kMonotonic, kOscillatory, kDivergent };

struct GciResult {
  double r21 = 0, r32 = 0;   // refinement ratios h2/h1, h3/h2
  double R = 0;              // eps21 / eps32 (0 < R < 1: monotonic)
  Convergence convergence = Convergence::kMonotonic;
  double p = 0;              // apparent order
  int iterations = 0;        // fixed-point iterations for p
  double phi_ext = 0;        // extrapolated value from grids 1 and 2
  double e_a21 = 0;          // |(phi1 - phi2) / phi1|
  double e_ext21 = 0;        // |(phi_ext - phi1) / phi_ext|
  double gci21 = 0;          // fine-grid GCI (relative)
  double gci32 = 0;          // medium-grid GCI (relative)
  double asymptotic_ratio = 0;  // GCI32 / (r21^p GCI21), close to 1 in the asymptotic range

  std::string Report(const std::string& name) const;
};

// Representative cell size h = (V / N)^(1/3) of a 3D grid.
double RepresentativeCellSize(double volume, double cells);

// phi1 on the finest grid (h1 smallest). Throws kelvin::ArgumentError when
// the sizes are not strictly increasing or a refinement ratio is below 1.1.
// The apparent order is only meaningful for monotonic convergence; for
// oscillatory or divergent sequences the result carries the classification
// and p is computed from |eps32/eps21| as Celik et al. recommend reporting.
GciResult ComputeGci(double h1, double h2, double h3, double phi1, double phi2, double phi3);

}  // namespace kelvin::cfd
