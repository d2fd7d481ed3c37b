#include "simulator/maneuvers/identified_range.h"

#include <fmt/format.h>

#include <numbers>

namespace kelvin::sim {

MotionRange TrajectoryExtent(const Trajectory& trajectory, double Lpp) {
  MotionRange e;
  for (const TrajectorySample& s : trajectory.samples()) e.Include(s.u, s.v, s.r, Lpp);
  return e;
}

std::string ExtrapolationWarning(const DerivativeSet& set, const Trajectory& trajectory, double Lpp,
                                 const std::string& what) {
  if (!set.range) return "";
  const MotionRange e = TrajectoryExtent(trajectory, Lpp);
  const MotionRange& r = *set.range;
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
