// Safety of the helm input: every helm_command_t that arrives over LCM is
// decoded and checked here before it reaches the simulator. Orders that are
// malformed, not finite, physically meaningless, stale, from the future or
// from an unknown source are rejected; orders slightly beyond the ship's
// limits are clamped. Everything is counted. Decoding and checking never
// allocate and never throw (they run in the LCM callback).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "kelvin/helm_command_t.hpp"

namespace kelvin::bridge {

struct HelmFilterOptions {
  double rudder_max = 35.0 * M_PI / 180.0;  // rad, orders beyond +-rudder_max are clamped to it
  double rudder_reject = M_PI / 2.0;        // rad, orders beyond +-rudder_reject are rejected as out of range
  double rps_min = 0.0;                     // 1/s, orders below are clamped (0: no reverse thrust)
  double rps_max = 20.0;                    // 1/s, orders above are clamped
  double rps_reject = 40.0;                 // 1/s, orders with |n| above are rejected as out of range
  double stale_timeout = 1.0;               // s, orders older than this (by utime) are rejected
  double future_tolerance = 1.0;            // s, orders dated further ahead are rejected
  std::vector<std::int32_t> sources;        // accepted source ids; empty: any source

  void Validate() const;  // throws kelvin::ArgumentError naming the option
};

enum class HelmVerdict {
  kAccepted,
  kClamped,      // accepted after clamping to the ship's limits
  kMalformed,    // does not decode as helm_command_t (wrong type, short, trailing bytes)
  kNotFinite,    // NaN or infinite order
  kOutOfRange,   // beyond rudder_reject or rps_reject
  kStale,        // utime older than stale_timeout
  kFuture,       // utime further ahead than future_tolerance
  kUnknownSource,
};
std::string_view VerdictName(HelmVerdict verdict);

struct HelmCounters {
  long received = 0;
  long accepted = 0;  // includes the clamped ones
  long clamped = 0;
  long malformed = 0;
  long not_finite = 0;
  long out_of_range = 0;
  long stale = 0;
  long future = 0;
  long unknown_source = 0;
  long rejected() const { return malformed + not_finite + out_of_range + stale + future + unknown_source; }
  // Counts one command with this verdict (received, and its class).
  void Count(HelmVerdict verdict);
  // The commands counted with this verdict (kAccepted: accepted unclamped).
  long Of(HelmVerdict verdict) const;
  bool operator==(const HelmCounters&) const = default;
};

class HelmFilter {
 public:
  explicit HelmFilter(const HelmFilterOptions& options);  // validates the options

  // Decodes an encoded helm_command_t (as received from LCM) and checks it
  // against the wall clock `now_utime` (us since the UNIX epoch).
  HelmVerdict Receive(const void* data, std::size_t size, std::int64_t now_utime);
  // Checks a decoded command.
  HelmVerdict Check(const kelvin::helm_command_t& command, std::int64_t now_utime);

  // The latest accepted order (after clamping), if one arrived since the
  // last call; returns false otherwise.
  bool TakeOrder(double* rudder_order, double* rps_order);

  const HelmCounters& counters() const { return counters_; }
  // One line describing the latest rejection or clamp ("" if none yet),
  // kept in a fixed buffer for rate-limited logging.
  std::string_view last_problem() const { return std::string_view(last_problem_, last_problem_length_); }
  const HelmFilterOptions& options() const { return options_; }

 private:
  HelmVerdict Reject(HelmVerdict verdict, const kelvin::helm_command_t& command, const char* what);
  HelmFilterOptions options_;
  HelmCounters counters_;
  kelvin::helm_command_t decoded_{};
  bool has_order_ = false;
  double rudder_order_ = 0;
  double rps_order_ = 0;
  char last_problem_[192] = {};
  std::size_t last_problem_length_ = 0;
};

}  // namespace kelvin::bridge
