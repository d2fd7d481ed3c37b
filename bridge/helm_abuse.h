// Helm messages of every kind the helm filter must tell apart, valid and
// abusive, built against the filter's limits: for the helm fuzz and flood
// tests and the flood benchmark (tests/bridge, tools/bench). Each kind has
// the one verdict the filter must give it.
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <span>
#include <string_view>
#include <vector>

#include "bridge/helm_filter.h"
#include "kelvin/helm_command_t.hpp"

namespace kelvin::bridge {

enum class HelmAbuse {
  kValid,             // fresh, within the ship's limits, from an accepted source
  kClamped,           // beyond the ship's rudder or propeller limit, not beyond the plausible range
  kWrongFingerprint,  // a valid encoding with a corrupted type hash
  kTruncated,         // a valid encoding cut short (down to 0 bytes)
  kTrailingBytes,     // a valid encoding with bytes after it
  kGarbage,           // random bytes, 0 to 80 of them
  kRudderOutOfRange,  // |rudder_order| beyond rudder_reject (up to 1e300)
  kRpsOutOfRange,     // |rps_order| beyond rps_reject (up to 1e300)
  kStale,             // utime older than the stale timeout by 1 s or more (down to INT64_MIN)
  kFuture,            // utime ahead by the future tolerance plus 1 s or more (up to INT64_MAX)
  kNaN,               // a NaN rudder or propeller order (either sign bit)
  kPlusInfinity,      // +inf rudder or propeller order
  kMinusInfinity,     // -inf rudder or propeller order
  kUnknownSource,     // a source_id not among the accepted ones (only when they are restricted)
};
constexpr int kHelmAbuseKinds = 14;
std::string_view HelmAbuseName(HelmAbuse kind);
// The verdict the filter must give a message of this kind.
HelmVerdict ExpectedVerdict(HelmAbuse kind);
// Every kind that `limits` can tell apart (kUnknownSource only with restricted sources).
std::vector<HelmAbuse> HelmAbuseKinds(const HelmFilterOptions& limits);

class HelmAbuseMaker {
 public:
  // `limits`: the filter's (Bridge::helm_filter().options()). Copied.
  HelmAbuseMaker(const HelmFilterOptions& limits, std::uint64_t seed);

  // Encodes one message of `kind` dated against `now_utime` (us since the
  // UNIX epoch). The bytes stay valid until the next call.
  std::span<const std::uint8_t> Make(HelmAbuse kind, std::int64_t now_utime);
  // The order the filter puts in force for the last message made (after
  // clamping); meaningful for kValid and kClamped only.
  double order_rudder() const { return order_rudder_; }
  double order_rps() const { return order_rps_; }

 private:
  double Uniform(double lo, double hi);
  int Integer(int lo, int hi);
  double Huge();  // 10^U(0.3, 300)
  kelvin::helm_command_t Fresh(std::int64_t now_utime);
  void Clamp(kelvin::helm_command_t& c);
  void NotFinite(kelvin::helm_command_t& c, double value);
  void Encode(const kelvin::helm_command_t& c);
  void Corrupt(HelmAbuse kind);

  HelmFilterOptions limits_;
  std::mt19937_64 rng_;
  std::vector<std::uint8_t> bytes_;
  double order_rudder_ = 0, order_rps_ = 0;
};

}  // namespace kelvin::bridge
