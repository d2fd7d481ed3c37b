// What the bridge hands to its browser display, across threads: the latest
// state with the helm statistics, the recent maneuver events and a thinned
// track (written by the real-time loop, read by the HTTP threads), and the
// page's helm orders (written by the HTTP threads, drained by the loop into
// the same HelmFilter as the LCM helm commands). Fixed-size buffers: the
// loop's side never allocates, never throws, and holds the lock only to copy
// a few hundred bytes.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <vector>

#include "bridge/helm_filter.h"
#include "kelvin/helm_command_t.hpp"
#include "kelvin/maneuver_event_t.hpp"
#include "kelvin/ship_state_t.hpp"

namespace kelvin::bridge {

struct TrackPoint {
  double t, x, y;  // s, m north, m east
};

// One consistent copy of what the loop published last.
struct DisplaySnapshot {
  bool has_state = false;
  kelvin::ship_state_t state{};
  HelmCounters helm;                   // the filter's statistics (LCM and page together)
  long events_total = 0;               // events published so far
  std::array<kelvin::maneuver_event_t, 16> events{};  // the latest ones, oldest first
  int n_events = 0;
};

class DisplayFeed {
 public:
  static constexpr std::size_t kTrackCapacity = 4096;
  static constexpr int kHelmInbox = 16;

  // The track keeps one point per `track_interval` s of simulation time.
  explicit DisplayFeed(double track_interval = 1.0);

  // Loop side (no allocation).
  void PublishState(const kelvin::ship_state_t& state, const HelmCounters& helm);
  void PublishEvent(const kelvin::maneuver_event_t& event);
  // Feeds the queued page orders to `filter` (stamped with `now_utime`).
  void DrainHelm(HelmFilter& filter, std::int64_t now_utime);

  // HTTP side.
  DisplaySnapshot Snapshot() const;
  std::vector<TrackPoint> Track() const;
  // Queues one page order; false (and counted) if the inbox is full.
  bool QueueHelm(const kelvin::helm_command_t& command);
  long helm_inbox_overflows() const;
  // Increases whenever a new state is published.
  std::int64_t version() const;

 private:
  mutable std::mutex mutex_;
  DisplaySnapshot snapshot_;
  std::int64_t version_ = 0;
  double track_interval_;
  double next_track_t_ = 0;
  std::array<TrackPoint, kTrackCapacity> track_{};
  std::size_t track_size_ = 0, track_head_ = 0;  // ring buffer
  std::array<std::array<std::uint8_t, 64>, kHelmInbox> inbox_{};
  std::array<int, kHelmInbox> inbox_size_{};
  int n_inbox_ = 0;
  long inbox_overflows_ = 0;
};

}  // namespace kelvin::bridge
