// The real-time bridge: steps the simulator with the fixed-step integrator,
// paced to the wall clock (or N times faster), publishes ship_state_t over
// LCM at a fixed rate of simulation time, takes helm_command_t orders (or
// plays a scripted IMO maneuver and publishes its maneuver_event_t events),
// and optionally sends NMEA 0183 over UDP.
//
// The loop per state message: compute the next state (drain LCM without
// blocking: 256 messages, more for up to a quarter of the period; apply the latest accepted
// helm order; take the integrator steps),
// sleep until its absolute wall-clock deadline, publish. Nothing in the loop
// allocates or throws; all set-up happens in the constructor.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "bridge/display_feed.h"
#include "bridge/geo.h"
#include "bridge/helm_filter.h"
#include "bridge/nmea.h"
#include "bridge/pacer.h"
#include "kelvin/maneuver_event_t.hpp"
#include "kelvin/ship_state_t.hpp"
#include "simulator/maneuvers/maneuver.h"

namespace kelvin::bridge {

struct BridgeOptions {
  double rate = 20.0;     // Hz: state messages per second of simulation time
  double speedup = 1.0;   // simulation seconds per wall-clock second
  double duration = 0.0;  // s of simulation time; 0: until the script ends (forever without a script)
  std::string script;     // IMO maneuver ("zigzag:20/20:stbd", ...); empty: helm commands steer
  double step = 0.0;      // s, integrator step; 0: 1/rate split into steps of at most Lpp/U0/200
  double approach_speed = 0.0;  // m/s, initial speed; 0: the ship file's conditions.approach_speed
  std::string channel_prefix = "KELVIN";  // channels <prefix>_STATE, <prefix>_HELM, <prefix>_EVENT
  GeoPoint origin{53.5, 3.0};             // deg, where x = y = 0 lies (the southern North Sea)
  HelmFilterOptions helm;  // rudder/rps limits are filled from the ship where left at 0 (see Bridge)
  std::optional<UdpEndpoint> nmea;  // NMEA 0183 output, off when empty
  double nmea_rate = 1.0;           // Hz of wall-clock time, 1 to 10
  // How the NMEA sentences flag the fix (bridge/nmea.h): autonomous, which
  // gpsd and the plotters behind it display, or simulated.
  NmeaFixMode nmea_fix = NmeaFixMode::kAutonomous;
  double nmea_epoch = -1.0;  // s since the UNIX epoch at simulation time 0; < 0: the wall clock at start
  double max_lag = 1.0;      // s behind the schedule before the pacer re-anchors
  double log_interval = 1.0;  // s of wall-clock time between helm problem log lines
  // SCHED_FIFO priority (1-99) of the thread that runs the loop, restored when
  // Run() returns; 0 = normal scheduling. Needs root or CAP_SYS_NICE: without
  // it the bridge warns and runs with normal scheduling.
  int realtime_priority = 0;

  void Validate() const;  // throws kelvin::ArgumentError naming the option, its value and what is expected
};

enum class BridgeStatus { kCompleted, kStopped, kDiverged };

struct BridgeSummary {
  BridgeStatus status = BridgeStatus::kCompleted;
  double sim_time = 0;          // s reached
  long states_published = 0;
  long events_published = 0;
  long publish_failures = 0;
  long lcm_messages_handled = 0;
  long helm_drains_cut = 0;  // LCM drains stopped at their time budget (256 messages, then a quarter of the period)
  HelmCounters helm;
  long helm_ignored_scripted = 0;  // accepted orders that arrived while a script was steering
  long late_ticks = 0;
  long resyncs = 0;
  double max_lateness = 0;  // s
  long nmea_sentences_sent = 0;
  long nmea_sentences_dropped = 0;
  bool realtime = false;    // the loop ran with SCHED_FIFO
  double step = 0;          // s, integrator step used
  int steps_per_state = 0;
};

class Bridge {
 public:
  // `lcm` must be good and outlive the bridge (tests share a memq:// instance
  // between the bridge and their subscribers); `ship` is copied into the
  // bridge's model. Throws kelvin::ArgumentError for bad options or a bad
  // script, kelvin::InputError for an LCM failure.
  Bridge(const sim::ShipParameters& ship, const BridgeOptions& options, lcm::LCM& lcm);
  ~Bridge();
  Bridge(const Bridge&) = delete;
  Bridge& operator=(const Bridge&) = delete;

  // Runs until the duration or the script ends, RequestStop() is called or
  // the state diverges. Once per Bridge.
  BridgeSummary Run();
  // Safe from a signal handler or another thread.
  void RequestStop() { stop_.store(true, std::memory_order_relaxed); }

  // Records the CLOCK_MONOTONIC time (ns) of every state publication into
  // `log` while it has room (for the pacing benchmark).
  void SetPublishLog(std::span<std::int64_t> log) { publish_log_ = log; }
  // Hands every state, event and the helm statistics to `feed` (the browser
  // display), and drains the page's helm orders from it into the helm filter
  // with the LCM ones. Call before Run(); `feed` must outlive the run.
  void SetDisplay(DisplayFeed* feed) { display_ = feed; }

  const std::string& state_channel() const { return state_channel_; }
  const std::string& helm_channel() const { return helm_channel_; }
  const std::string& event_channel() const { return event_channel_; }
  double step() const { return step_; }
  int steps_per_state() const { return steps_per_state_; }
  double approach_speed() const { return approach_speed_; }
  double approach_rps() const { return approach_rps_; }
  const sim::Simulator& simulator() const { return *sim_; }
  const HelmFilter& helm_filter() const { return helm_; }

 private:
  // The helm callback, on LCM's C API: the C++ wrapper builds a std::string
  // of the channel name for every message (an allocation for long names).
  static void OnHelm(const lcm_recv_buf_t* rbuf, const char* channel, void* user);
  void DrainLcm();
  void ComputeNextState();
  void FillState(std::int64_t seq);
  void PublishState();  // stamps, publishes and hands state_ to the display
  void Publish(const std::string& channel, const auto& message);
  void PublishEvent(std::int8_t kind, int index, double overshoot, double t, double psi);
  void SendNmea();
  // Logs the helm problems since the last report, at most once per
  // log_interval unless forced (at the end of the run).
  void LogHelmProblems(std::int64_t now_ns, bool force);

  BridgeOptions options_;
  lcm::LCM& lcm_;
  // Owns the ship parameters (model_->ship()); sim_, declared after it, refers to it.
  std::unique_ptr<sim::MmgModel<double>> model_;
  double approach_speed_ = 0;
  double approach_rps_ = 0;
  std::unique_ptr<sim::Simulator> sim_;
  std::unique_ptr<sim::ManeuverController> controller_;
  bool script_active_ = false;
  bool script_finished_ = false;
  bool ran_ = false;
  HelmFilter helm_;
  lcm_subscription_t* helm_subscription_ = nullptr;
  std::int64_t drain_budget_ns_ = 0;  // per DrainLcm(): a quarter of the wall-clock state period
  LocalOrigin origin_;
  std::unique_ptr<NmeaUdpSender> nmea_;
  std::string state_channel_, helm_channel_, event_channel_;
  double step_ = 0;
  int steps_per_state_ = 1;
  std::atomic<bool> stop_{false};
  std::span<std::int64_t> publish_log_;
  DisplayFeed* display_ = nullptr;
  // Preallocated messages and encoding buffer.
  kelvin::ship_state_t state_{};
  kelvin::maneuver_event_t event_{};
  std::uint8_t buffer_[512] = {};
  BridgeSummary summary_;
  // Zig-zag overshoot tracking between a reversal and the heading extremum.
  bool overshoot_armed_ = false;
  int overshoot_sign_ = 0;  // +1 while turning to starboard toward the extremum, -1 to port
  double first_overshoot_, second_overshoot_, first_overshoot_time_, second_overshoot_time_;
  int overshoots_ = 0;
  int executes_ = 0;
  long event_seq_ = 0;
  double nmea_epoch_ = 0;
  long nmea_every_ = 1;
  HelmCounters logged_counters_;
  std::int64_t last_log_ns_ = 0;
};

// "zigzag:20/20:stbd" -> the ManeuverSpec; "" -> nullopt.
std::optional<sim::ManeuverSpec> ParseScript(const std::string& script);

}  // namespace kelvin::bridge
