// One-dimensional node distributions for structured grids, and the first
// wall-normal spacing for a target y+.
#pragma once

#include <vector>

namespace kelvin::cfd {

// Nodes 0 = s_0 < s_1 < ... < s_n = length growing geometrically from the
// first spacing h1: s_{i+1} - s_i = h1 q^i, with the ratio q solved so that
// the nodes end exactly at `length` (q < 1 if h1 n > length). Throws
// ConfigError if n < 1, h1 <= 0 or length <= 0.
std::vector<double> GeometricNodes(int n, double length, double h1);

// GeometricNodes with the spacing capped at h_max: s_{i+1} - s_i =
// min(h1 q^i, h_max), q > 1 solved so that the nodes end at `length` (the
// grid grows away from a wall and then stays uniform, e.g. at the spacing
// that resolves the free-surface waves). Falls back to GeometricNodes when
// h_max <= 0 or when the uncapped spacing never exceeds h_max. Throws
// ConfigError when n cells at most h_max wide cannot cover the length.
std::vector<double> CappedGeometricNodes(int n, double length, double h1, double h_max);

// The growth ratio q of GeometricNodes.
double GeometricRatio(int n, double length, double h1);

// Nodes over [0, length] whose spacing varies smoothly from h0 at s = 0 to
// h1 at s = length: the spacing profile h(xi) = h0 + (h1 - h0) xi + c sin(pi xi)
// (xi = i / n) with c chosen so the nodes end at `length`. The spacing of the
// end cells equals h0 and h1 to O(1/n). Throws ConfigError when the profile
// would not stay positive (h0 + h1 much larger than 2 length / n).
std::vector<double> TwoSidedNodes(int n, double length, double h0, double h1);

// First wall-normal cell height (m) that puts the first cell centre at
// `y_plus`: the wall shear velocity is u_tau = U sqrt(C_F / 2) with the
// ITTC-57 C_F at Re = U L / nu (data::Ittc57FrictionCoefficient, which
// throws kelvin::ModelError for Re <= 100), and the first cell centre sits
// at half the height, so h = 2 y+ nu / u_tau = 2 y+ L / (Re sqrt(C_F / 2)).
double FirstCellHeight(double y_plus, double reynolds, double length);

// y+ of a first cell centre at wall distance y, with the same estimate.
double YPlusAt(double wall_distance, double reynolds, double length);

}  // namespace kelvin::cfd
