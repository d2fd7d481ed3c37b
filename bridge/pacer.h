// Wall-clock pacing with absolute deadlines: tick k is due at start + k T on
// CLOCK_MONOTONIC, and WaitNext() sleeps with clock_nanosleep(TIMER_ABSTIME)
// until it. Lateness in one tick does not shift the later deadlines, so no
// lag accumulates (a relative sleep_for(T) after the work drifts by the work
// time every tick). If the loop falls further behind than `max_lag` (the
// machine was suspended, a debugger stopped it), the schedule is re-anchored
// at the current time instead of bursting to catch up, and counted.
#pragma once

#include <cstdint>

namespace kelvin::bridge {

std::int64_t MonotonicNanoseconds();
std::int64_t RealtimeMicroseconds();  // us since the UNIX epoch (LCM utime)

class Pacer {
 public:
  // period in s (> 0), max_lag in s (> 0).
  Pacer(double period, double max_lag);

  // Anchors tick 0 at the current time.
  void Start();
  // Sleeps until tick k+1 is due and returns how late the wake-up was (ns,
  // >= 0). Never allocates or throws.
  std::int64_t WaitNext();

  long tick() const { return tick_; }
  std::int64_t deadline() const { return DeadlineOf(tick_); }  // ns, CLOCK_MONOTONIC
  long late_ticks() const { return late_ticks_; }  // woke more than a period late
  long resyncs() const { return resyncs_; }
  std::int64_t max_lateness() const { return max_lateness_; }  // ns

 private:
  std::int64_t DeadlineOf(long k) const;
  double period_ns_;
  std::int64_t max_lag_ns_;
  std::int64_t anchor_ = 0;
  long anchor_tick_ = 0;
  long tick_ = 0;
  long late_ticks_ = 0;
  long resyncs_ = 0;
  std::int64_t max_lateness_ = 0;
};

}  // namespace kelvin::bridge
