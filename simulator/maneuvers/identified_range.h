// Whether a maneuver stayed within the motions its derivative set was
// identified over (DerivativeSet::range, the largest |drift| and |r'| of the
// captive runs): beyond them the MMG polynomials are extrapolated, and
// kelvin check and kelvin simulate say so.
#pragma once

#include <string>

#include "simulator/maneuvers/trajectory.h"
#include "simulator/mmg/derivative_set.h"

namespace kelvin::sim {

// The range of a trajectory's motions (MotionRange::Include of each sample).
MotionRange TrajectoryExtent(const Trajectory& trajectory, double Lpp);

// A maneuver is beyond the range when its drift or r' exceeds the set's by
// more than kRangeMargin of it (the polynomials are smooth; a few per cent
// past the last run is not yet a different flow).
inline constexpr double kRangeMargin = 0.05;

// "" when the trajectory stays within the set's range or the set has none;
// otherwise one line starting "WARNING: " that names `what` (e.g. "the CFD
// reference of turning:35:port"), how far it went and the set's range.
std::string ExtrapolationWarning(const DerivativeSet& set, const Trajectory& trajectory, double Lpp,
                                 const std::string& what);

}  // namespace kelvin::sim
