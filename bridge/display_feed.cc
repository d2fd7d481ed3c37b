#include "bridge/display_feed.h"

#include <algorithm>

#include "data/schema/errors.h"

namespace kelvin::bridge {

DisplayFeed::DisplayFeed(double track_interval) : track_interval_(track_interval) {
  KELVIN_CHECK(track_interval > 0, "the display track interval must be positive");
  kelvin::helm_command_t probe{};
  KELVIN_CHECK(probe.getEncodedSize() <= static_cast<int>(inbox_[0].size()),
               "helm_command_t does not fit the display's helm inbox");
}

void DisplayFeed::PublishState(const kelvin::ship_state_t& state, const HelmCounters& helm) {
  std::lock_guard<std::mutex> lock(mutex_);
  snapshot_.has_state = true;
  snapshot_.state = state;
  snapshot_.helm = helm;
  ++version_;
  if (state.t + 1e-9 >= next_track_t_) {
    track_[track_head_] = {state.t, state.x, state.y};
    track_head_ = (track_head_ + 1) % kTrackCapacity;
    track_size_ = std::min(track_size_ + 1, kTrackCapacity);
    next_track_t_ = state.t + track_interval_;
  }
}

void DisplayFeed::PublishEvent(const kelvin::maneuver_event_t& event) {
  std::lock_guard<std::mutex> lock(mutex_);
  auto& s = snapshot_;
  if (s.n_events == static_cast<int>(s.events.size())) {
    std::rotate(s.events.begin(), s.events.begin() + 1, s.events.end());
    --s.n_events;
  }
  s.events[static_cast<std::size_t>(s.n_events++)] = event;
  ++s.events_total;
}

void DisplayFeed::DrainHelm(HelmFilter& filter, std::int64_t now_utime) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (int i = 0; i < n_inbox_; ++i) {
    filter.Receive(inbox_[static_cast<std::size_t>(i)].data(), static_cast<std::size_t>(inbox_size_[i]), now_utime);
  }
  n_inbox_ = 0;
}

DisplaySnapshot DisplayFeed::Snapshot() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return snapshot_;
}

std::vector<TrackPoint> DisplayFeed::Track() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<TrackPoint> out;
  out.reserve(track_size_);
  const std::size_t first = (track_head_ + kTrackCapacity - track_size_) % kTrackCapacity;
  for (std::size_t i = 0; i < track_size_; ++i) out.push_back(track_[(first + i) % kTrackCapacity]);
  return out;
}

bool DisplayFeed::QueueHelm(const kelvin::helm_command_t& command) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (n_inbox_ == kHelmInbox) {
    ++inbox_overflows_;
    return false;
  }
  auto& slot = inbox_[static_cast<std::size_t>(n_inbox_)];
  const int n = command.encode(slot.data(), 0, static_cast<int>(slot.size()));
  if (n < 0) return false;
  inbox_size_[static_cast<std::size_t>(n_inbox_++)] = n;
  return true;
}

long DisplayFeed::helm_inbox_overflows() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return inbox_overflows_;
}

std::int64_t DisplayFeed::version() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return version_;
}

}  // namespace kelvin::bridge
