#include "bridge/helm_abuse.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "data/schema/errors.h"
#include "simulator/integrators/actuators.h"

namespace kelvin::bridge {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

std::string_view HelmAbuseName(HelmAbuse kind) {
  switch (kind) {
    case HelmAbuse::kValid: return "valid";
    case HelmAbuse::kClamped: return "beyond the ship's limits (clamped)";
    case HelmAbuse::kWrongFingerprint: return "wrong fingerprint";
    case HelmAbuse::kTruncated: return "truncated";
    case HelmAbuse::kTrailingBytes: return "trailing bytes";
    case HelmAbuse::kGarbage: return "garbage bytes";
    case HelmAbuse::kRudderOutOfRange: return "rudder out of range";
    case HelmAbuse::kRpsOutOfRange: return "rps out of range";
    case HelmAbuse::kStale: return "stale";
    case HelmAbuse::kFuture: return "from the future";
    case HelmAbuse::kNaN: return "NaN";
    case HelmAbuse::kPlusInfinity: return "+infinity";
    case HelmAbuse::kMinusInfinity: return "-infinity";
    case HelmAbuse::kUnknownSource: return "unknown source";
  }
  return "?";
}

HelmVerdict ExpectedVerdict(HelmAbuse kind) {
  switch (kind) {
    case HelmAbuse::kValid: return HelmVerdict::kAccepted;
    case HelmAbuse::kClamped: return HelmVerdict::kClamped;
    case HelmAbuse::kWrongFingerprint:
    case HelmAbuse::kTruncated:
    case HelmAbuse::kTrailingBytes:
    case HelmAbuse::kGarbage: return HelmVerdict::kMalformed;
    case HelmAbuse::kRudderOutOfRange:
    case HelmAbuse::kRpsOutOfRange: return HelmVerdict::kOutOfRange;
    case HelmAbuse::kStale: return HelmVerdict::kStale;
    case HelmAbuse::kFuture: return HelmVerdict::kFuture;
    case HelmAbuse::kNaN:
    case HelmAbuse::kPlusInfinity:
    case HelmAbuse::kMinusInfinity: return HelmVerdict::kNotFinite;
    case HelmAbuse::kUnknownSource: return HelmVerdict::kUnknownSource;
  }
  return HelmVerdict::kMalformed;
}

std::vector<HelmAbuse> HelmAbuseKinds(const HelmFilterOptions& limits) {
  std::vector<HelmAbuse> kinds;
  for (int k = 0; k < kHelmAbuseKinds; ++k) {
    const auto kind = static_cast<HelmAbuse>(k);
    if (kind != HelmAbuse::kUnknownSource || !limits.sources.empty()) kinds.push_back(kind);
  }
  return kinds;
}

HelmAbuseMaker::HelmAbuseMaker(const HelmFilterOptions& limits, std::uint64_t seed) : limits_(limits), rng_(seed) {
  limits_.Validate();
  bytes_.reserve(128);
}

double HelmAbuseMaker::Uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }

int HelmAbuseMaker::Integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }

double HelmAbuseMaker::Huge() { return std::pow(10.0, Uniform(0.3, 300)); }

kelvin::helm_command_t HelmAbuseMaker::Fresh(std::int64_t now_utime) {
  kelvin::helm_command_t c{};
  c.utime = now_utime;
  const auto& s = limits_.sources;
  c.source_id = s.empty() ? 1 : s[static_cast<std::size_t>(Integer(0, static_cast<int>(s.size()) - 1))];
  c.rudder_order = Uniform(-limits_.rudder_max, limits_.rudder_max);
  c.rps_order = Uniform(limits_.rps_min, limits_.rps_max);
  return c;
}

// Beyond one of the ship's limits, within the plausible range.
void HelmAbuseMaker::Clamp(kelvin::helm_command_t& c) {
  const double rps_floor = limits_.rps_min - 1e-3;  // rps_reject >= -rps_min: room below rps_min
  const bool room_below = rps_floor > -limits_.rps_reject;
  switch (Integer(0, room_below ? 2 : 1)) {
    case 0: c.rudder_order = (Integer(0, 1) ? 1 : -1) * Uniform(limits_.rudder_max * 1.0001, limits_.rudder_reject); break;
    case 1: c.rps_order = Uniform(limits_.rps_max * 1.0001, limits_.rps_reject); break;
    default: c.rps_order = Uniform(-limits_.rps_reject, rps_floor); break;
  }
}

void HelmAbuseMaker::NotFinite(kelvin::helm_command_t& c, double value) {
  (Integer(0, 1) ? c.rudder_order : c.rps_order) = value;
}

void HelmAbuseMaker::Encode(const kelvin::helm_command_t& c) {
  bytes_.resize(static_cast<std::size_t>(c.getEncodedSize()));
  const int n = c.encode(bytes_.data(), 0, static_cast<int>(bytes_.size()));
  KELVIN_CHECK(n == static_cast<int>(bytes_.size()), "helm_command_t did not encode");
}

// Spoils the encoding in bytes_ as `kind` says.
void HelmAbuseMaker::Corrupt(HelmAbuse kind) {
  switch (kind) {
    case HelmAbuse::kWrongFingerprint:
      bytes_[static_cast<std::size_t>(Integer(0, 7))] ^= static_cast<std::uint8_t>(Integer(1, 255));
      break;
    case HelmAbuse::kTruncated:
      bytes_.resize(static_cast<std::size_t>(Integer(0, static_cast<int>(bytes_.size()) - 1)));
      break;
    case HelmAbuse::kTrailingBytes:
      bytes_.resize(bytes_.size() + static_cast<std::size_t>(Integer(1, 16)), 0xAB);
      break;
    case HelmAbuse::kGarbage:
      bytes_.resize(static_cast<std::size_t>(Integer(0, 80)));
      for (auto& b : bytes_) b = static_cast<std::uint8_t>(Integer(0, 255));
      break;
    default: break;
  }
}

std::span<const std::uint8_t> HelmAbuseMaker::Make(HelmAbuse kind, std::int64_t now_utime) {
  kelvin::helm_command_t c = Fresh(now_utime);
  const std::int64_t stale_us = std::llround(limits_.stale_timeout * 1e6);
  const std::int64_t future_us = std::llround(limits_.future_tolerance * 1e6);
  switch (kind) {
    case HelmAbuse::kClamped: Clamp(c); break;
    case HelmAbuse::kRudderOutOfRange:
      c.rudder_order = (Integer(0, 1) ? 1 : -1) * std::max(Huge(), limits_.rudder_reject * 1.0001);
      break;
    case HelmAbuse::kRpsOutOfRange:
      c.rps_order = (Integer(0, 1) ? 1 : -1) * std::max(Huge(), limits_.rps_reject * 1.0001);
      break;
    case HelmAbuse::kStale:
      c.utime = Integer(0, 9) == 0 ? std::numeric_limits<std::int64_t>::min()
                                   : now_utime - stale_us - static_cast<std::int64_t>(Uniform(1e6, 1e15));
      break;
    case HelmAbuse::kFuture:
      c.utime = Integer(0, 9) == 0 ? std::numeric_limits<std::int64_t>::max()
                                   : now_utime + future_us + static_cast<std::int64_t>(Uniform(1e6, 1e15));
      break;
    case HelmAbuse::kNaN: NotFinite(c, Integer(0, 1) ? kNaN : -kNaN); break;
    case HelmAbuse::kPlusInfinity: NotFinite(c, kInf); break;
    case HelmAbuse::kMinusInfinity: NotFinite(c, -kInf); break;
    case HelmAbuse::kUnknownSource: {
      const auto& s = limits_.sources;
      KELVIN_CHECK(!s.empty(), "an unknown source needs restricted sources");
      do {
        c.source_id = Integer(std::numeric_limits<int>::min(), std::numeric_limits<int>::max());
      } while (std::find(s.begin(), s.end(), c.source_id) != s.end());
      break;
    }
    default: break;
  }
  order_rudder_ = sim::ClampRudderAngle(c.rudder_order, limits_.rudder_max);
  order_rps_ = std::clamp(c.rps_order, limits_.rps_min, limits_.rps_max);
  Encode(c);
  Corrupt(kind);
  return bytes_;
}

}  // namespace kelvin::bridge
