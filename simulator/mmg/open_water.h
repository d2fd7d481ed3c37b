// Open-water characteristics of a propeller in the first quadrant (n > 0,
// ahead): K_T(J) = T / (rho n^2 D^4) and K_Q(J) = Q / (rho n^2 D^5) against
// the advance ratio J = U_A / (n D), from a table.
//
// Interpolation is the monotone piecewise-cubic Hermite interpolant of
// Fritsch & Carlson (1980, SIAM J. Numer. Anal. 17(2):238-246) with the
// node slopes of Fritsch & Butland (1984, SIAM J. Sci. Stat. Comput.
// 5(2):300-304), the rule of MATLAB's and SciPy's `pchip`: at an interior
// node the weighted harmonic mean of the two adjacent secants (0 where they
// differ in sign), at an end the one-sided three-point slope limited to keep
// the shape. It passes through every node, is C1, and is monotone on every
// interval where the data are, so a strictly decreasing K_T table gives a
// strictly decreasing K_T(J) that JFromKT can invert. It never extrapolates:
// outside [J_min, J_max] the calls throw ConfigError naming `origin`, the
// value and the range (the table does not cover the run).
#pragma once

#include <array>
#include <string>
#include <vector>

namespace kelvin::sim {

struct OpenWaterCurve {
  std::vector<double> J;    // advance ratio, strictly increasing
  std::vector<double> K_T;  // thrust coefficient, strictly decreasing in J
  std::vector<double> K_Q;  // torque coefficient, strictly decreasing in J
  // Where the table came from, for the range errors of KT, KQ and JFromKT
  // (e.g. "ship.yaml: propeller.open_water"); Validate names its own.
  std::string origin = "open-water curve";

  // Tabulates K_T = k0 + k1 J + k2 J^2 and K_Q = q0 + q1 J + q2 J^2 at
  // `points` equally spaced J in [0, J_max]; the cubic through the fine
  // table then differs from the quadratics by O(h^4).
  static OpenWaterCurve FromQuadratics(const std::array<double, 3>& k, const std::array<double, 3>& q, double J_max,
                                       int points = 101);

  // Throws ConfigError naming `source` and `key` (the table's key, e.g.
  // "propeller.open_water"; the column is appended: key.J, key.K_T, key.K_Q)
  // with the index and the value: fewer than 3 points, lengths that differ,
  // non-finite values, J not strictly increasing, K_T or K_Q not strictly
  // decreasing.
  void Validate(const std::string& source, const std::string& key) const;

  double J_min() const { return J.front(); }
  double J_max() const { return J.back(); }
  bool Covers(double advance_ratio) const { return advance_ratio >= J_min() && advance_ratio <= J_max(); }
  double KT(double advance_ratio) const;
  double KQ(double advance_ratio) const;
  // The J with KT(J) = thrust_coefficient (the thrust identity); throws ConfigError
  // outside [K_T(J_max), K_T(J_min)].
  double JFromKT(double thrust_coefficient) const;
};

}  // namespace kelvin::sim
