#include "cfd/turbulence/wall_stats.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace kelvin::cfd {

double WallPatchStats::AreaBeyond(double y_plus) const {
  double share = 0.0;
  for (std::size_t b = 0; b < area_fraction.size(); ++b) {
    if (b > 0 && kYPlusBandEdges[b - 1] >= y_plus) share += area_fraction[b];
  }
  return share;
}

WallPatchStats SummarizeWall(const std::string& patch, std::span<const double> y_plus,
                             std::span<const double> area) {
  WallPatchStats s;
  s.patch = patch;
  s.y_plus_min = y_plus.empty() ? 0.0 : std::numeric_limits<double>::infinity();
  double total = 0.0;
  for (std::size_t f = 0; f < y_plus.size(); ++f) {
    const double yp = y_plus[f];
    s.y_plus_min = std::min(s.y_plus_min, yp);
    s.y_plus_max = std::max(s.y_plus_max, yp);
    s.y_plus_mean += yp * area[f];
    total += area[f];
    const auto band = std::upper_bound(kYPlusBandEdges.begin(), kYPlusBandEdges.end(), yp) - kYPlusBandEdges.begin();
    s.area_fraction[static_cast<std::size_t>(band)] += area[f];
    if (yp > kBufferYPlusLow && yp < kBufferYPlusHigh) s.buffer_fraction += area[f];
  }
  if (total > 0.0) {
    s.y_plus_mean /= total;
    s.buffer_fraction /= total;
    for (double& a : s.area_fraction) a /= total;
  }
  return s;
}

std::string YPlusDistribution(const WallPatchStats& s) {
  std::string out = fmt::format("y+ on {} by area: <{:g} {:.1f}%", s.patch, kYPlusBandEdges[0],
                                100 * s.area_fraction[0]);
  for (std::size_t b = 1; b < kYPlusBandEdges.size(); ++b) {
    out += fmt::format(", {:g}-{:g} {:.1f}%", kYPlusBandEdges[b - 1], kYPlusBandEdges[b], 100 * s.area_fraction[b]);
  }
  return out + fmt::format(", >={:g} {:.1f}%", kYPlusBandEdges.back(), 100 * s.area_fraction.back());
}

namespace {

std::string BufferWarning(const WallPatchStats& s) {
  if (s.buffer_fraction <= kWallAreaBeyondLimit) return "";
  return fmt::format(
      "WARNING: {:.0f}% of the area of '{}' has a first-cell y+ between {:g} and {:g} (mean {:.3g}); in this buffer "
      "layer the wall treatment reaches no steady state on the flat plate and its friction is off by up to 21% "
      "(BENCHMARKS.md flat_plate_peer; allowed: {:.0f}% of the area): move the first cells to y+ 30-100 (wall "
      "functions) or to y+ 1 or below (resolved)",
      100 * s.buffer_fraction, s.patch, kBufferYPlusLow, kBufferYPlusHigh, s.y_plus_mean, 100 * kWallAreaBeyondLimit);
}

std::string BeyondWarning(const WallPatchStats& s) {
  const double beyond = s.AreaBeyond(kWallYPlusLimit);
  if (beyond <= kWallAreaBeyondLimit) return "";
  return fmt::format(
      "WARNING: {:.0f}% of the area of '{}' has a first-cell y+ of {:g} or more (mean {:.3g}, max {:.3g}); beyond "
      "y+ {:g} the first cells lie outside the log layer and the wall treatment is not valid (allowed: {:.0f}% of "
      "the area): the wall shear, the friction and the forces built on them are off; refine the wall cells or add "
      "prism layers",
      100 * beyond, s.patch, kWallYPlusLimit, s.y_plus_mean, s.y_plus_max, kWallYPlusLimit,
      100 * kWallAreaBeyondLimit);
}

}  // namespace

std::string YPlusWarning(const WallPatchStats& s) {
  const std::string beyond = BeyondWarning(s), buffer = BufferWarning(s);
  if (beyond.empty() || buffer.empty()) return beyond + buffer;
  return beyond + "\n" + buffer;
}

}  // namespace kelvin::cfd
