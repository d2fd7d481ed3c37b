// LCM helm messages: decoding and the filter. The input is the receiver's
// clock (8 bytes, us since the epoch) followed by the message as received.
// Whatever arrives, exactly one verdict is counted and an order that comes
// out is finite and within the ship's limits.
#include <cmath>
#include <cstring>
#include <string>

#include "bridge/helm_filter.h"

namespace {

void Require(bool ok) {
  if (!ok) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::int64_t now = 0;
  if (size >= sizeof now) {
    std::memcpy(&now, data, sizeof now);
    data += sizeof now;
    size -= sizeof now;
  }
  kelvin::bridge::HelmFilter filter({});
  filter.Receive(data, size, now);
  const kelvin::bridge::HelmCounters& c = filter.counters();
  Require(c.received == 1 && c.accepted + c.rejected() == 1);
  const std::string problem(filter.last_problem());
  double rudder = 0, rps = 0;
  if (filter.TakeOrder(&rudder, &rps)) {
    const auto& o = filter.options();
    Require(std::isfinite(rudder) && std::abs(rudder) <= o.rudder_max);
    Require(std::isfinite(rps) && rps >= o.rps_min && rps <= o.rps_max);
  }
  return 0;
}
