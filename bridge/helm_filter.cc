#include "bridge/helm_filter.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "data/schema/errors.h"
#include "simulator/integrators/actuators.h"

namespace kelvin::bridge {

namespace {
constexpr double kDeg = M_PI / 180.0;

void Require(bool ok, std::string_view name, double value, std::string_view expected) {
  if (!ok) throw ArgumentError(fmt::format("helm option {} = {}: expected {}", name, value, expected));
}
}  // namespace

void HelmFilterOptions::Validate() const {
  Require(std::isfinite(rudder_max) && rudder_max > 0, "rudder_max", rudder_max, "a positive angle in rad");
  Require(std::isfinite(rudder_reject) && rudder_reject >= rudder_max, "rudder_reject", rudder_reject,
          "an angle in rad not below rudder_max");
  Require(std::isfinite(rps_max) && rps_max > 0, "rps_max", rps_max, "a positive propeller speed in 1/s");
  Require(std::isfinite(rps_min) && rps_min <= rps_max, "rps_min", rps_min, "a propeller speed not above rps_max");
  Require(std::isfinite(rps_reject) && rps_reject >= rps_max && rps_reject >= -rps_min, "rps_reject", rps_reject,
          "a propeller speed not below |rps_min| and rps_max");
  Require(std::isfinite(stale_timeout) && stale_timeout > 0, "stale_timeout", stale_timeout,
          "a positive time in s");
  Require(std::isfinite(future_tolerance) && future_tolerance >= 0, "future_tolerance", future_tolerance,
          "a non-negative time in s");
}

std::string_view VerdictName(HelmVerdict verdict) {
  switch (verdict) {
    case HelmVerdict::kAccepted: return "accepted";
    case HelmVerdict::kClamped: return "clamped";
    case HelmVerdict::kMalformed: return "malformed";
    case HelmVerdict::kNotFinite: return "not finite";
    case HelmVerdict::kOutOfRange: return "out of range";
    case HelmVerdict::kStale: return "stale";
    case HelmVerdict::kFuture: return "from the future";
    case HelmVerdict::kUnknownSource: return "unknown source";
  }
  return "?";
}

void HelmCounters::Count(HelmVerdict verdict) {
  ++received;
  switch (verdict) {
    case HelmVerdict::kAccepted: ++accepted; break;
    case HelmVerdict::kClamped:
      ++accepted;
      ++clamped;
      break;
    case HelmVerdict::kMalformed: ++malformed; break;
    case HelmVerdict::kNotFinite: ++not_finite; break;
    case HelmVerdict::kOutOfRange: ++out_of_range; break;
    case HelmVerdict::kStale: ++stale; break;
    case HelmVerdict::kFuture: ++future; break;
    case HelmVerdict::kUnknownSource: ++unknown_source; break;
  }
}

long HelmCounters::Of(HelmVerdict verdict) const {
  switch (verdict) {
    case HelmVerdict::kAccepted: return accepted - clamped;
    case HelmVerdict::kClamped: return clamped;
    case HelmVerdict::kMalformed: return malformed;
    case HelmVerdict::kNotFinite: return not_finite;
    case HelmVerdict::kOutOfRange: return out_of_range;
    case HelmVerdict::kStale: return stale;
    case HelmVerdict::kFuture: return future;
    case HelmVerdict::kUnknownSource: return unknown_source;
  }
  return 0;
}

HelmFilter::HelmFilter(const HelmFilterOptions& options) : options_(options) { options_.Validate(); }

HelmVerdict HelmFilter::Reject(HelmVerdict verdict, const kelvin::helm_command_t& c, const char* what) {
  counters_.Count(verdict);
  const int n = std::snprintf(last_problem_, sizeof(last_problem_),
                              "helm command from source %d rejected (%.*s): %s (rudder_order %g rad, rps_order %g "
                              "1/s, utime %lld us)",
                              c.source_id, static_cast<int>(VerdictName(verdict).size()), VerdictName(verdict).data(),
                              what, c.rudder_order, c.rps_order, static_cast<long long>(c.utime));
  last_problem_length_ = n < 0 ? 0 : std::min(static_cast<std::size_t>(n), sizeof(last_problem_) - 1);
  return verdict;
}

HelmVerdict HelmFilter::Receive(const void* data, std::size_t size, std::int64_t now_utime) {
  decoded_ = kelvin::helm_command_t{};
  const int max_len = static_cast<int>(std::min<std::size_t>(size, 1 << 20));
  const int used = data ? decoded_.decode(data, 0, max_len) : -1;
  if (used < 0 || static_cast<std::size_t>(used) != size) {
    kelvin::helm_command_t none{};
    char what[96];
    std::snprintf(what, sizeof(what), "%zu bytes do not decode as kelvin.helm_command_t (%d bytes expected)", size,
                  decoded_.getEncodedSize());
    return Reject(HelmVerdict::kMalformed, none, what);
  }
  return Check(decoded_, now_utime);
}

HelmVerdict HelmFilter::Check(const kelvin::helm_command_t& c, std::int64_t now_utime) {
  if (!std::isfinite(c.rudder_order)) return Reject(HelmVerdict::kNotFinite, c, "rudder_order is not finite");
  if (!std::isfinite(c.rps_order)) return Reject(HelmVerdict::kNotFinite, c, "rps_order is not finite");
  if (std::abs(c.rudder_order) > options_.rudder_reject) {
    return Reject(HelmVerdict::kOutOfRange, c, "|rudder_order| exceeds the plausible range");
  }
  if (std::abs(c.rps_order) > options_.rps_reject) {
    return Reject(HelmVerdict::kOutOfRange, c, "|rps_order| exceeds the plausible range");
  }
  // Ages in double seconds: no overflow for any int64 utime.
  const double age = (static_cast<double>(now_utime) - static_cast<double>(c.utime)) * 1e-6;
  if (age > options_.stale_timeout) return Reject(HelmVerdict::kStale, c, "utime is older than the stale timeout");
  if (-age > options_.future_tolerance) return Reject(HelmVerdict::kFuture, c, "utime lies ahead of the clock");
  if (!options_.sources.empty() &&
      std::find(options_.sources.begin(), options_.sources.end(), c.source_id) == options_.sources.end()) {
    return Reject(HelmVerdict::kUnknownSource, c, "source_id is not in the accepted sources");
  }
  const double rudder = sim::ClampRudderAngle(c.rudder_order, options_.rudder_max);
  const double rps = std::clamp(c.rps_order, options_.rps_min, options_.rps_max);
  rudder_order_ = rudder;
  rps_order_ = rps;
  has_order_ = true;
  if (rudder != c.rudder_order || rps != c.rps_order) {
    counters_.Count(HelmVerdict::kClamped);
    const int n = std::snprintf(last_problem_, sizeof(last_problem_),
                                "helm command from source %d clamped to the ship's limits: rudder_order %g -> %g deg, "
                                "rps_order %g -> %g 1/s",
                                c.source_id, c.rudder_order / kDeg, rudder / kDeg, c.rps_order, rps);
    last_problem_length_ = n < 0 ? 0 : std::min(static_cast<std::size_t>(n), sizeof(last_problem_) - 1);
    return HelmVerdict::kClamped;
  }
  counters_.Count(HelmVerdict::kAccepted);
  return HelmVerdict::kAccepted;
}

bool HelmFilter::TakeOrder(double* rudder_order, double* rps_order) {
  if (!has_order_) return false;
  *rudder_order = rudder_order_;
  *rps_order = rps_order_;
  has_order_ = false;
  return true;
}

}  // namespace kelvin::bridge
