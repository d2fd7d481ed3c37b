// What a maneuver controller (simulator/maneuvers/maneuver.h) reads and
// orders: the MMG simulator in fast or real time, or a free-running CFD run
// (cfd/run/maneuver_pilot.h), so both fly the same maneuver logic.
#pragma once

namespace kelvin::sim {

class ManeuverPlant {
 public:
  virtual ~ManeuverPlant() = default;
  virtual double time() const = 0;         // s
  virtual double heading() const = 0;      // psi (rad), positive to starboard
  virtual double surge_speed() const = 0;  // u (m/s), ship axes
  // Orders take effect from the present time at the plant's rate limits.
  virtual void SetRudderOrder(double delta_order) = 0;  // rad, positive turns to starboard
  virtual void SetRpsOrder(double n_order) = 0;         // 1/s
};

}  // namespace kelvin::sim
