#include "cfd/grid/hull_sections.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "cfd/geometry/hydrostatics.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {

WigleySections::WigleySections(double L, double B, double T) : L_(L), B_(B), T_(T) {
  if (!(L > 0) || !(B > 0) || !(T > 0)) {
    throw ConfigError(fmt::format(
        "Wigley hull: L, B and T must be > 0; got L = {} m, B = {} m, T = {} m", L, B, T));
  }
}

std::vector<std::array<double, 2>> WigleySections::Breadths(double x,
                                                            std::span<const double> z) const {
  std::vector<std::array<double, 2>> out(z.size(), {0.0, 0.0});
  for (std::size_t j = 0; j < z.size(); ++j) {
    const double zeta = z[j] / T_;
    if (zeta > 0.0 || zeta < -1.0) continue;
    const double y = WigleyHalfBeam(L_, B_, T_, x, z[j]);
    out[j] = {-y, y};
  }
  return out;
}

std::string WigleySections::name() const {
  return fmt::format("Wigley hull L={} B={} T={}", L_, B_, T_);
}

SurfaceSections::SurfaceSections(TriangleSurface surface) : surface_(std::move(surface)) {
  x_aft_ = std::numeric_limits<double>::infinity();
  x_fore_ = -std::numeric_limits<double>::infinity();
  for (const auto& t : surface_.triangles) {
    for (const auto& tri : ClipBelowWaterline(surface_.vertices[t[0]], surface_.vertices[t[1]],
                                              surface_.vertices[t[2]])) {
      for (const auto& p : tri) {
        x_aft_ = std::min(x_aft_, p.x());
        x_fore_ = std::max(x_fore_, p.x());
      }
    }
  }
  if (!(x_fore_ > x_aft_)) {
    throw DataFileError(
        fmt::format("{}: no part of the hull lies below the waterline z = 0", surface_.source));
  }
}

std::vector<std::array<double, 4>> SurfaceSections::Slice(double x) const {
  std::vector<std::array<double, 4>> segments;
  for (const auto& t : surface_.triangles) {
    const Eigen::Vector3d& a = surface_.vertices[t[0]];
    const Eigen::Vector3d& b = surface_.vertices[t[1]];
    const Eigen::Vector3d& c = surface_.vertices[t[2]];
    if (x < std::min({a.x(), b.x(), c.x()}) || x > std::max({a.x(), b.x(), c.x()})) continue;
    for (const auto& tri : ClipBelowWaterline(a, b, c)) {
      Eigen::Vector3d pts[3];
      int n = 0;
      for (int i = 0; i < 3 && n < 2; ++i) {
        const Eigen::Vector3d& p = tri[i];
        const Eigen::Vector3d& q = tri[(i + 1) % 3];
        const double dp = p.x() - x, dq = q.x() - x;
        if ((dp < 0 && dq >= 0) || (dp >= 0 && dq < 0)) pts[n++] = p + (dp / (dp - dq)) * (q - p);
      }
      if (n == 2) segments.push_back({pts[0].y(), pts[0].z(), pts[1].y(), pts[1].z()});
    }
  }
  return segments;
}

double SurfaceSections::KeelZ(double x) const {
  // The ends may be a single edge; cut just inside them.
  const double eps = 1e-6 * length();
  const double xs = std::clamp(x, x_aft_ + eps, x_fore_ - eps);
  double zmin = 0.0;
  for (const auto& s : Slice(xs)) zmin = std::min({zmin, s[1], s[3]});
  if (!(zmin < 0.0)) {
    throw DataFileError(fmt::format(
        "{}: the section at x = {:.6g} m has no part below the waterline", surface_.source, x));
  }
  return zmin;
}

std::vector<std::array<double, 2>> SurfaceSections::Breadths(double x,
                                                             std::span<const double> z) const {
  const auto segments = Slice(x);
  std::vector<std::array<double, 2>> out(z.size(), {0.0, 0.0});
  for (std::size_t j = 0; j < z.size(); ++j) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto& s : segments) {
      const double z0 = std::min(s[1], s[3]), z1 = std::max(s[1], s[3]);
      if (z[j] < z0 || z[j] > z1) continue;
      double y;
      if (z1 - z0 <= 1e-14 * (1.0 + std::abs(z1))) {
        lo = std::min({lo, s[0], s[2]});
        hi = std::max({hi, s[0], s[2]});
        continue;
      }
      y = s[0] + (z[j] - s[1]) / (s[3] - s[1]) * (s[2] - s[0]);
      lo = std::min(lo, y);
      hi = std::max(hi, y);
    }
    if (lo <= hi) out[j] = {lo, hi};
  }
  return out;
}

}  // namespace kelvin::cfd
