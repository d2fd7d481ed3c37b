#include "bridge/pacer.h"

#include <cerrno>
#include <cmath>
#include <ctime>

#include "data/schema/errors.h"

namespace kelvin::bridge {

std::int64_t MonotonicNanoseconds() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

std::int64_t RealtimeMicroseconds() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000LL + ts.tv_nsec / 1000;
}

Pacer::Pacer(double period, double max_lag)
    : period_ns_(period * 1e9), max_lag_ns_(static_cast<std::int64_t>(max_lag * 1e9)) {
  KELVIN_CHECK(std::isfinite(period) && period > 0, "pacer period must be positive");
  KELVIN_CHECK(std::isfinite(max_lag) && max_lag > 0, "pacer max_lag must be positive");
}

void Pacer::Start() {
  anchor_ = MonotonicNanoseconds();
  anchor_tick_ = 0;
  tick_ = 0;
}

std::int64_t Pacer::DeadlineOf(long k) const {
  // From the anchor by multiplication, never by adding periods: no round-off
  // accumulates over millions of ticks.
  return anchor_ + std::llround(static_cast<double>(k - anchor_tick_) * period_ns_);
}

std::int64_t Pacer::WaitNext() {
  ++tick_;
  const std::int64_t due = DeadlineOf(tick_);
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(due / 1000000000LL);
  ts.tv_nsec = static_cast<long>(due % 1000000000LL);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
  const std::int64_t now = MonotonicNanoseconds();
  const std::int64_t late = now > due ? now - due : 0;
  if (late > max_lateness_) max_lateness_ = late;
  if (static_cast<double>(late) > period_ns_) ++late_ticks_;
  if (late > max_lag_ns_) {
    anchor_ = now;
    anchor_tick_ = tick_;
    ++resyncs_;
  }
  return late;
}

}  // namespace kelvin::bridge
