#include "simulator/mmg/open_water.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "data/schema/errors.h"

namespace kelvin::sim {

namespace {

[[noreturn]] void BadTable(const std::string& source, const std::string& key, const std::string& what) {
  throw ConfigError(fmt::format("{}: {}: {}", source, key, what));
}

void CheckColumn(const std::string& source, const std::string& key, const std::vector<double>& v, bool increasing) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) BadTable(source, key, fmt::format("[{}] = {}: expected a finite value", i, v[i]));
    if (i == 0) continue;
    const bool ok = increasing ? v[i] > v[i - 1] : v[i] < v[i - 1];
    if (!ok) {
      BadTable(source, key,
               fmt::format("[{}] = {} after [{}] = {}: expected strictly {} in J", i, v[i], i - 1, v[i - 1],
                           increasing ? "increasing" : "decreasing"));
    }
  }
}

// Fritsch-Butland slope at an interior node from the secants d0, d1 over
// the intervals h0, h1: the weighted harmonic mean, 0 at a local extremum.
double InteriorSlope(double h0, double h1, double d0, double d1) {
  if (d0 * d1 <= 0.0) return 0.0;
  const double w1 = 2.0 * h1 + h0;
  const double w2 = h1 + 2.0 * h0;
  return (w1 + w2) / (w1 / d0 + w2 / d1);
}

// One-sided three-point slope at an end node (h0, d0 the end interval),
// limited so that the end interval stays monotone (pchip's rule).
double EndSlope(double h0, double h1, double d0, double d1) {
  double m = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
  if (m * d0 <= 0.0) return 0.0;
  if (d0 * d1 <= 0.0 && std::abs(m) > std::abs(3.0 * d0)) m = 3.0 * d0;
  return m;
}

// Slope of the interpolant at node i of (x, y).
double NodeSlope(const std::vector<double>& x, const std::vector<double>& y, std::size_t i) {
  const std::size_t n = x.size();
  auto h = [&](std::size_t k) { return x[k + 1] - x[k]; };
  auto d = [&](std::size_t k) { return (y[k + 1] - y[k]) / h(k); };
  if (i == 0) return EndSlope(h(0), h(1), d(0), d(1));
  if (i == n - 1) return EndSlope(h(n - 2), h(n - 3), d(n - 2), d(n - 3));
  return InteriorSlope(h(i - 1), h(i), d(i - 1), d(i));
}

// The monotone cubic Hermite interpolant of (x, y) at xi in [x0, xn].
double Pchip(const std::vector<double>& x, const std::vector<double>& y, double xi) {
  const auto upper = std::upper_bound(x.begin(), x.end(), xi);
  const std::size_t i = std::min<std::size_t>(std::max<std::ptrdiff_t>(upper - x.begin(), 1) - 1, x.size() - 2);
  const double h = x[i + 1] - x[i];
  const double t = (xi - x[i]) / h;
  const double t2 = t * t, t3 = t2 * t;
  const double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2, h11 = t3 - t2;
  return h00 * y[i] + h10 * h * NodeSlope(x, y, i) + h01 * y[i + 1] + h11 * h * NodeSlope(x, y, i + 1);
}

}  // namespace

OpenWaterCurve OpenWaterCurve::FromQuadratics(const std::array<double, 3>& k, const std::array<double, 3>& q,
                                              double J_max, int points) {
  if (!(J_max > 0) || !std::isfinite(J_max)) {
    throw ConfigError(fmt::format("open-water quadratics: J_max = {}: expected a positive finite value", J_max));
  }
  if (points < 3) throw ConfigError(fmt::format("open-water quadratics: points = {}: expected >= 3", points));
  OpenWaterCurve c;
  c.origin = "open-water quadratics";
  for (int i = 0; i < points; ++i) {
    const double j = J_max * i / (points - 1);
    c.J.push_back(j);
    c.K_T.push_back(k[0] + k[1] * j + k[2] * j * j);
    c.K_Q.push_back(q[0] + q[1] * j + q[2] * j * j);
  }
  return c;
}

void OpenWaterCurve::Validate(const std::string& source, const std::string& key) const {
  if (J.size() < 3) {
    BadTable(source, key + ".J", fmt::format("{} points: expected at least 3", J.size()));
  }
  if (K_T.size() != J.size() || K_Q.size() != J.size()) {
    BadTable(source, key,
             fmt::format("J has {} values, K_T {} and K_Q {}: expected the same number in each", J.size(),
                         K_T.size(), K_Q.size()));
  }
  CheckColumn(source, key + ".J", J, true);
  CheckColumn(source, key + ".K_T", K_T, false);
  CheckColumn(source, key + ".K_Q", K_Q, false);
}

double OpenWaterCurve::KT(double advance_ratio) const {
  if (!Covers(advance_ratio)) {
    throw ConfigError(fmt::format("{}: J = {} is outside the table's range [{}, {}]", origin, advance_ratio, J_min(),
                                  J_max()));
  }
  return Pchip(J, K_T, advance_ratio);
}

double OpenWaterCurve::KQ(double advance_ratio) const {
  if (!Covers(advance_ratio)) {
    throw ConfigError(fmt::format("{}: J = {} is outside the table's range [{}, {}]", origin, advance_ratio, J_min(),
                                  J_max()));
  }
  return Pchip(J, K_Q, advance_ratio);
}

double OpenWaterCurve::JFromKT(double thrust_coefficient) const {
  if (!(thrust_coefficient <= K_T.front() && thrust_coefficient >= K_T.back())) {
    throw ConfigError(fmt::format("{}: K_T = {} is outside the table's range [{}, {}] (J in [{}, {}])", origin,
                                  thrust_coefficient, K_T.back(), K_T.front(), J_min(), J_max()));
  }
  // The table's interval, then bisection on the strictly decreasing cubic.
  const auto it = std::lower_bound(K_T.rbegin(), K_T.rend(), thrust_coefficient);
  const std::size_t hi_node = std::min<std::size_t>(K_T.size() - 1, K_T.size() - 1 - (it - K_T.rbegin()) + 1);
  double lo = J[hi_node == 0 ? 0 : hi_node - 1], hi = J[hi_node];
  for (int iter = 0; iter < 200 && hi - lo > 1e-15 * std::max(1.0, std::abs(hi)); ++iter) {
    const double mid = 0.5 * (lo + hi);
    (Pchip(J, K_T, mid) > thrust_coefficient ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace kelvin::sim
