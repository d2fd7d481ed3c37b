// A recorded maneuver: time histories of the state and the actuators, with
// cubic Hermite interpolation (the state derivatives are known exactly), so
// that metrics such as the advance at a 90 deg heading change are read off to
// the integrator's accuracy rather than the sampling interval.
#pragma once

#include <string>
#include <vector>

#include "data/schema/h5_file.h"
#include "simulator/integrators/simulator.h"

namespace kelvin::sim {

struct TrajectorySample {
  double t, x, y, psi, u, v, r, delta, n;
};

class Trajectory {
 public:
  void Record(const Simulator& sim, int phase);
  void Add(const TrajectorySample& s, int phase);
  std::size_t size() const { return samples_.size(); }
  bool empty() const { return samples_.empty(); }
  const TrajectorySample& operator[](std::size_t i) const { return samples_[i]; }
  const std::vector<TrajectorySample>& samples() const { return samples_; }
  const std::vector<int>& phases() const { return phases_; }

  // State at time t by cubic Hermite interpolation between the samples that
  // bracket it (x, y and psi use their exact derivatives; velocities and
  // actuators are interpolated linearly).
  TrajectorySample At(double t) const;
  // First time after t_from at which f(sample) crosses `level` upward
  // (f increasing through it), refined by bisection on the interpolant;
  // negative if never. `f` picks a quantity: psi, u, ...
  double FirstCrossing(double t_from, double level, double TrajectorySample::*field, int direction) const;
  // Path length travelled between t_a and t_b (integral of the speed).
  double PathLength(double t_a, double t_b) const;

  // Writes the series under `group` (time, x, y, psi, u, v, r, rudder, rps,
  // phase) with units.
  void Write(data::H5Writer& out, const std::string& group) const;

 private:
  std::size_t Bracket(double t) const;
  std::vector<TrajectorySample> samples_;
  std::vector<int> phases_;
};

}  // namespace kelvin::sim
