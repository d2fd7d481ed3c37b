#include "cfd/grid/spacing.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "data/reference/friction_lines.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {

double GeometricRatio(int n, double length, double h1) {
  if (n < 1 || !(h1 > 0) || !(length > 0)) {
    throw ConfigError(
        fmt::format("geometric spacing: need n >= 1, first spacing > 0 and length > 0; got n = {}, "
                    "first spacing = {} m, length = {} m",
                    n, h1, length));
  }
  // Sum of the spacings for ratio q; monotone increasing in q.
  auto total = [&](double q) {
    if (std::abs(q - 1.0) < 1e-12) return h1 * n;
    return h1 * (std::pow(q, n) - 1.0) / (q - 1.0);
  };
  double lo = 1e-6, hi = 1.0;
  while (total(hi) < length) {
    hi *= 2.0;
    if (hi > 1e6)
      throw ConfigError(fmt::format(
          "geometric spacing: first spacing {} m is too small to cover {} m in {} cells", h1,
          length, n));
  }
  if (total(lo) > length) {
    throw ConfigError(fmt::format(
        "geometric spacing: first spacing {} m is larger than the length {} m", h1, length));
  }
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (total(mid) < length ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::vector<double> GeometricNodes(int n, double length, double h1) {
  const double q = GeometricRatio(n, length, h1);
  std::vector<double> s(n + 1, 0.0);
  double h = h1;
  for (int i = 1; i <= n; ++i) {
    s[i] = s[i - 1] + h;
    h *= q;
  }
  // Remove the bisection round-off so the last node is exact.
  const double scale = length / s[n];
  for (double& v : s) v *= scale;
  s[n] = length;
  return s;
}

std::vector<double> CappedGeometricNodes(int n, double length, double h1, double h_max) {
  if (!(h_max > 0.0)) return GeometricNodes(n, length, h1);
  const double q_free = GeometricRatio(n, length, h1);
  if (q_free <= 1.0 || h1 * std::pow(q_free, n - 1) <= h_max) return GeometricNodes(n, length, h1);
  if (h1 + (n - 1) * h_max < length * (1.0 - 1e-12)) {
    throw ConfigError(fmt::format(
        "capped spacing: {} cells of at most {} m cannot cover {} m (at least {} cells are needed)", n, h_max,
        length, 1 + static_cast<int>(std::ceil((length - h1) / h_max))));
  }
  // Sum of the capped spacings for ratio q >= q_free > 1; monotone in q.
  auto total = [&](double q) {
    double sum = 0.0, h = h1;
    for (int i = 0; i < n; ++i) {
      sum += std::min(h, h_max);
      h *= q;
    }
    return sum;
  };
  double lo = q_free, hi = q_free;
  while (total(hi) < length) {
    hi = 1.0 + 2.0 * (hi - 1.0);
    if (hi > 1e6) break;  // the cap alone covers the length: the limit q -> infinity
  }
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (total(mid) < length ? lo : hi) = mid;
  }
  const double q = 0.5 * (lo + hi);
  std::vector<double> s(n + 1, 0.0);
  double h = h1;
  for (int i = 1; i <= n; ++i) {
    s[i] = s[i - 1] + std::min(h, h_max);
    h *= q;
  }
  const double scale = length / s[n];
  for (double& v : s) v *= scale;
  s[n] = length;
  return s;
}

std::vector<double> TwoSidedNodes(int n, double length, double h0, double h1) {
  if (n < 1 || !(h0 > 0) || !(h1 > 0) || !(length > 0)) {
    throw ConfigError(
        fmt::format("two-sided spacing: need n >= 1, end spacings > 0 and length > 0; got n = {}, "
                    "spacings {} m and {} m, length = {} m",
                    n, h0, h1, length));
  }
  const double pi = std::numbers::pi;
  // Mean spacing length / n = (h0 + h1) / 2 + 2 c / pi.
  const double c = 0.5 * pi * (length / n - 0.5 * (h0 + h1));
  // h(xi) is positive when its minimum over [0, 1] is positive; with c < 0
  // the minimum lies at an interior point, check on a fine sample.
  for (int k = 0; k <= 200; ++k) {
    const double xi = k / 200.0;
    if (h0 + (h1 - h0) * xi + c * std::sin(pi * xi) <= 0.05 * std::min(h0, h1)) {
      throw ConfigError(fmt::format(
          "two-sided spacing: end spacings {} m and {} m are too large for {} cells over {} m", h0,
          h1, n, length));
    }
  }
  std::vector<double> s(n + 1);
  for (int i = 0; i <= n; ++i) {
    const double xi = static_cast<double>(i) / n;
    s[i] = n * (h0 * xi + 0.5 * (h1 - h0) * xi * xi + c * (1.0 - std::cos(pi * xi)) / pi);
  }
  s[0] = 0.0;
  s[n] = length;
  return s;
}

double FirstCellHeight(double y_plus, double reynolds, double length) {
  return 2.0 * y_plus * length / (reynolds * std::sqrt(0.5 * data::Ittc57FrictionCoefficient(reynolds)));
}

double YPlusAt(double wall_distance, double reynolds, double length) {
  return wall_distance * reynolds * std::sqrt(0.5 * data::Ittc57FrictionCoefficient(reynolds)) / length;
}

}  // namespace kelvin::cfd
