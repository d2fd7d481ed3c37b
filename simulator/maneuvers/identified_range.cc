#include "simulator/maneuvers/identified_range.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace kelvin::sim {

MotionExtent TrajectoryExtent(const Trajectory& trajectory, double Lpp) {
  MotionExtent e;
  for (const TrajectorySample& s : trajectory.samples()) {
    const double U = std::hypot(s.u, s.v);
    if (!(U > 0.0)) continue;
    e.drift = std::max(e.drift, std::atan2(std::abs(s.v), s.u));
    e.r_prime = std::max(e.r_prime, std::abs(s.r) * Lpp / U);
  }
  return e;
}

std::string ExtrapolationWarning(const DerivativeSet& set, const Trajectory& trajectory, double Lpp,
                                 const std::string& what) {
  if (!set.range) return "";
  const MotionExtent e = TrajectoryExtent(trajectory, Lpp);
  const IdentifiedRange& r = *set.range;
  const bool drift_beyond = e.drift > (1.0 + kRangeMargin) * r.drift;
  const bool rate_beyond = e.r_prime > (1.0 + kRangeMargin) * r.r_prime;
  if (!drift_beyond && !rate_beyond) return "";
  constexpr double kDeg = 180.0 / std::numbers::pi;
  return fmt::format(
      "WARNING: {} reached drift {:.1f} deg and r' {:.2f}; the derivative set {} was identified up to drift {:.1f} "
      "deg and r' {:.2f} (its captive runs): beyond that its derivatives are extrapolated (add captive runs that "
      "span the maneuver)",
      what, e.drift * kDeg, e.r_prime, set.file, r.drift * kDeg, r.r_prime);
}

}  // namespace kelvin::sim
