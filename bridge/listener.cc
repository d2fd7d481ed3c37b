#include "bridge/listener.h"

#include <fmt/format.h>

#include <cmath>

#include "data/schema/errors.h"

namespace kelvin::bridge {

bool AllFinite(const kelvin::ship_state_t& s) {
  for (double v : {s.t, s.x, s.y, s.latitude, s.longitude, s.heading, s.u, s.v, s.r, s.speed_over_ground,
                   s.course_over_ground, s.drift_angle, s.rudder_angle, s.rudder_order, s.propeller_rps,
                   s.propeller_rps_order}) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

Listener::Listener(lcm::LCM& lcm, const std::string& channel_prefix) : lcm_(lcm) {
  if (!lcm_.good()) throw InputError("LCM is not initialized (bad LCM URL?)");
  state_sub_ = lcm_.subscribe(channel_prefix + "_STATE", &Listener::OnState, this);
  event_sub_ = lcm_.subscribe(channel_prefix + "_EVENT", &Listener::OnEvent, this);
  if (!state_sub_ || !event_sub_) throw InputError(fmt::format("LCM: cannot subscribe to {}_*", channel_prefix));
}

Listener::~Listener() {
  if (state_sub_) lcm_.unsubscribe(state_sub_);
  if (event_sub_) lcm_.unsubscribe(event_sub_);
}

void Listener::OnState(const lcm::ReceiveBuffer* rbuf, const std::string& /*channel*/) {
  kelvin::ship_state_t m;
  if (m.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) != static_cast<int>(rbuf->data_size)) {
    ++malformed_;
    return;
  }
  const std::int64_t expected = states_.empty() ? 0 : states_.back().seq + 1;
  if (m.seq != expected) ++out_of_sequence_;
  states_.push_back(m);
}

void Listener::OnEvent(const lcm::ReceiveBuffer* rbuf, const std::string& /*channel*/) {
  kelvin::maneuver_event_t m;
  if (m.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) != static_cast<int>(rbuf->data_size)) {
    ++malformed_;
    return;
  }
  const std::int64_t expected = events_.empty() ? 0 : events_.back().seq + 1;
  if (m.seq != expected) ++out_of_sequence_;
  events_.push_back(m);
}

}  // namespace kelvin::bridge
