#include "bridge/helm_flood.h"

#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cmath>

#include "bridge/pacer.h"
#include "data/schema/errors.h"

namespace kelvin::bridge {

namespace {

void SleepUntil(std::int64_t ns) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(ns / 1000000000LL);
  ts.tv_nsec = static_cast<long>(ns % 1000000000LL);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

}  // namespace

HelmFlood::HelmFlood(lcm_t* lcm, std::string channel, const HelmFilterOptions& limits,
                     const HelmFloodOptions& options)
    : lcm_(lcm), channel_(std::move(channel)), options_(options), kinds_(HelmAbuseKinds(limits)),
      maker_(limits, options.seed) {
  KELVIN_CHECK(lcm_ != nullptr, "the helm flood needs an LCM instance");
  KELVIN_CHECK(std::isfinite(options_.rate) && options_.rate > 0, "the flood rate must be positive");
  KELVIN_CHECK(std::isfinite(options_.duration) && options_.duration > 0, "the flood duration must be positive");
}

void HelmFlood::PublishOne(HelmFloodReport& report) {
  const HelmAbuse kind = kinds_[next_];
  next_ = (next_ + 1) % kinds_.size();
  const auto bytes = maker_.Make(kind, RealtimeMicroseconds());
  if (lcm_publish(lcm_, channel_.c_str(), bytes.data(), static_cast<unsigned>(bytes.size())) != 0) {
    ++report.publish_failures;
    return;
  }
  ++report.sent[static_cast<std::size_t>(kind)];
  const HelmVerdict verdict = ExpectedVerdict(kind);
  report.owed.Count(verdict);
  if (options_.record_orders && (verdict == HelmVerdict::kAccepted || verdict == HelmVerdict::kClamped)) {
    report.orders.emplace_back(maker_.order_rudder(), maker_.order_rps());
  }
}

HelmFloodReport HelmFlood::Run(const std::atomic<bool>* stop) {
  HelmFloodReport report;
  const long total = std::lround(options_.rate * options_.duration);
  const std::int64_t start = MonotonicNanoseconds();
  long attempted = 0;
  for (long tick = 1; attempted < total; ++tick) {
    if (stop && stop->load(std::memory_order_relaxed)) break;
    const double elapsed = static_cast<double>(MonotonicNanoseconds() - start) * 1e-9;
    const long due = std::min(total, std::lround(elapsed * options_.rate));
    for (; attempted < due; ++attempted) PublishOne(report);
    SleepUntil(start + tick * 1000000LL);
  }
  report.seconds = static_cast<double>(MonotonicNanoseconds() - start) * 1e-9;
  return report;
}

}  // namespace kelvin::bridge
