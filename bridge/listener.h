// A recording subscriber for the bridge's channels: decodes every
// ship_state_t and maneuver_event_t, keeps them in arrival order and counts
// messages that do not decode or arrive out of sequence. The project's own
// listener for tests and tools (not for the real-time loop: it allocates).
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <string>
#include <vector>

#include "kelvin/maneuver_event_t.hpp"
#include "kelvin/ship_state_t.hpp"

namespace kelvin::bridge {

// True if every number of the state is finite.
bool AllFinite(const kelvin::ship_state_t& s);

class Listener {
 public:
  // Subscribes to <prefix>_STATE and <prefix>_EVENT on `lcm`.
  Listener(lcm::LCM& lcm, const std::string& channel_prefix);
  ~Listener();
  Listener(const Listener&) = delete;
  Listener& operator=(const Listener&) = delete;

  const std::vector<kelvin::ship_state_t>& states() const { return states_; }
  const std::vector<kelvin::maneuver_event_t>& events() const { return events_; }
  long malformed() const { return malformed_; }
  // Messages whose seq was not the previous one + 1 (0 for the first).
  long out_of_sequence() const { return out_of_sequence_; }

 private:
  void OnState(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void OnEvent(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  lcm::LCM& lcm_;
  lcm::Subscription* state_sub_ = nullptr;
  lcm::Subscription* event_sub_ = nullptr;
  std::vector<kelvin::ship_state_t> states_;
  std::vector<kelvin::maneuver_event_t> events_;
  long malformed_ = 0;
  long out_of_sequence_ = 0;
};

}  // namespace kelvin::bridge
