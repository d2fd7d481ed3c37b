// Rudder and propeller actuators: each moves from its current position toward
// its order at a limited rate, so its position is piecewise linear in time.
// The integrators evaluate the position analytically and stop exactly where a
// ramp ends (a kink of the right-hand side). Also the rudder angle limit that
// the simulator and the bridge's helm filter both apply.
#pragma once

#include <algorithm>
#include <limits>

namespace kelvin::sim {

// A rudder angle or order (rad) limited to [-rudder_max, rudder_max].
inline double ClampRudderAngle(double delta, double rudder_max) {
  return std::clamp(delta, -rudder_max, rudder_max);
}

class RateLimitedActuator {
 public:
  // rate <= 0 means the position jumps to the order at once.
  RateLimitedActuator(double position = 0.0, double rate = 0.0) : start_(position), order_(position), rate_(rate) {}

  // Moves toward `order` from the position at time t.
  void SetOrder(double t, double order) {
    start_ = PositionAt(t);
    t0_ = t;
    order_ = order;
    if (rate_ <= 0) start_ = order;
  }
  // Places the actuator at `position` at time t with no motion pending.
  void Reset(double t, double position) {
    t0_ = t;
    start_ = order_ = position;
  }
  double PositionAt(double t) const {
    if (rate_ <= 0 || start_ == order_) return order_;
    const double travel = rate_ * (t - t0_);
    if (order_ > start_) return start_ + travel >= order_ ? order_ : start_ + travel;
    return start_ - travel <= order_ ? order_ : start_ - travel;
  }
  // Time at which the current ramp ends; +inf when already at the order.
  double RampEnd() const {
    if (rate_ <= 0 || start_ == order_) return std::numeric_limits<double>::infinity();
    return t0_ + (order_ > start_ ? order_ - start_ : start_ - order_) / rate_;
  }
  double order() const { return order_; }
  double rate() const { return rate_; }
  void set_rate(double rate) { rate_ = rate; }

 private:
  double t0_ = 0.0;
  double start_ = 0.0;
  double order_ = 0.0;
  double rate_ = 0.0;
};

}  // namespace kelvin::sim
