// A helm flood for the flood test and benchmark: publishes HelmAbuse
// messages of every kind, in turn, on the bridge's helm channel at a given
// rate (LCM's C API; on udpm:// with ttl=0 it stays on this machine), and
// counts what it sent of each kind and the verdicts the filter owes them.
// Paced to CLOCK_MONOTONIC in 1 ms batches: a generator that falls behind
// catches up in a burst, as a real flood would.
#pragma once

#include <lcm/lcm.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "bridge/helm_abuse.h"
#include "bridge/helm_filter.h"

namespace kelvin::bridge {

struct HelmFloodOptions {
  double rate = 10000;       // messages per second
  double duration = 60;      // s
  std::uint64_t seed = 1;
  bool record_orders = false;  // keep the (rudder, rps) order of every message the filter must accept
};

struct HelmFloodReport {
  std::array<long, kHelmAbuseKinds> sent{};  // published, by kind
  long publish_failures = 0;                 // lcm_publish refused (not sent, not counted above)
  double seconds = 0;                        // from the first message to the last
  HelmCounters owed;                         // the filter's counters if every sent message arrives
  // With record_orders: the orders (after clamping) of the kValid and
  // kClamped messages, in the order sent.
  std::vector<std::pair<double, double>> orders;
  long total() const { return owed.received; }
  double rate() const { return seconds > 0 ? static_cast<double>(total()) / seconds : 0.0; }
};

class HelmFlood {
 public:
  // `lcm` must outlive the flood; `limits` are the bridge's filter options.
  HelmFlood(lcm_t* lcm, std::string channel, const HelmFilterOptions& limits, const HelmFloodOptions& options);

  // Publishes until the duration is over or `stop` becomes true.
  HelmFloodReport Run(const std::atomic<bool>* stop = nullptr);

 private:
  void PublishOne(HelmFloodReport& report);

  lcm_t* lcm_;
  std::string channel_;
  HelmFloodOptions options_;
  std::vector<HelmAbuse> kinds_;
  HelmAbuseMaker maker_;
  std::size_t next_ = 0;
};

}  // namespace kelvin::bridge
