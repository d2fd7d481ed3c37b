#include "bridge/bridge.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <cstring>
#include <cmath>
#include <limits>

#include "data/schema/errors.h"
#include "simulator/maneuvers/metrics.h"

namespace kelvin::bridge {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kHelmQueueCapacity = 10000;
constexpr int kDrainAtLeast = 256;  // messages per drain whatever the time

double WrapTwoPi(double a) {
  double w = std::fmod(a, kTwoPi);
  if (w < 0) w += kTwoPi;
  return w;
}

void Require(bool ok, std::string_view option, double value, std::string_view expected) {
  if (!ok) throw ArgumentError(fmt::format("{} {}: expected {}", option, value, expected));
}

bool IsUpperSnake(std::string_view s) {
  if (s.empty() || !(s[0] >= 'A' && s[0] <= 'Z')) return false;
  return std::all_of(s.begin(), s.end(),
                     [](char c) { return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'; });
}

}  // namespace

void BridgeOptions::Validate() const {
  Require(std::isfinite(rate) && rate > 0 && rate <= 1000, "--rate", rate, "a state rate between 0 and 1000 Hz");
  Require(std::isfinite(speedup) && speedup > 0 && speedup <= 10000, "--speedup", speedup,
          "a factor between 0 and 10000 (1 = real time)");
  Require(rate * speedup <= 100000, "--rate x --speedup", rate * speedup,
          "at most 100000 state messages per wall-clock second");
  Require(std::isfinite(duration) && duration >= 0, "--duration", duration,
          "a simulation time >= 0 s (0 = until the script ends)");
  Require(std::isfinite(step) && step >= 0, "--step", step, "an integrator step >= 0 s (0 = automatic)");
  Require(std::isfinite(approach_speed) && approach_speed >= 0, "--speed", approach_speed,
          "an approach speed >= 0 m/s (0 = the ship file's)");
  if (!IsUpperSnake(channel_prefix)) {
    throw ArgumentError(fmt::format("--channel-prefix '{}': expected an UPPER_SNAKE name such as KELVIN or SIM_2",
                                    channel_prefix));
  }
  Require(std::isfinite(nmea_rate) && nmea_rate >= 1 && nmea_rate <= 10, "--nmea-rate", nmea_rate,
          "an NMEA rate between 1 and 10 Hz");
  Require(std::isfinite(nmea_epoch), "NMEA epoch", nmea_epoch, "a finite time in s since the UNIX epoch");
  Require(std::isfinite(max_lag) && max_lag > 0, "max lag", max_lag, "a positive time in s");
  Require(std::isfinite(log_interval) && log_interval > 0, "log interval", log_interval, "a positive time in s");
  Require(realtime_priority >= 0 && realtime_priority <= 99, "--realtime-priority", realtime_priority,
          "a SCHED_FIFO priority between 1 and 99 (0 = normal scheduling)");
  Require(std::isfinite(helm.stale_timeout) && helm.stale_timeout > 0, "--stale-timeout", helm.stale_timeout,
          "a positive time in s");
  helm.Validate();
}

std::optional<sim::ManeuverSpec> ParseScript(const std::string& script) {
  if (script.empty()) return std::nullopt;
  return sim::ManeuverSpec::Parse(script);
}

void Bridge::OnHelm(const lcm_recv_buf_t* rbuf, const char* /*channel*/, void* user) {
  auto* bridge = static_cast<Bridge*>(user);
  bridge->helm_.Receive(rbuf->data, rbuf->data_size, RealtimeMicroseconds());
}

namespace {

HelmFilterOptions HelmLimits(const sim::ShipParameters& ship, HelmFilterOptions helm, double approach_rps) {
  helm.rudder_max = ship.limits.rudder_max;
  helm.rudder_reject = std::max(helm.rudder_reject, helm.rudder_max);
  // Ship files rarely give a maximum propeller speed: then twice the
  // self-propulsion speed at the approach speed.
  helm.rps_max = ship.limits.rps_max.value_or(2.0 * approach_rps);
  helm.rps_min = ship.propeller.reverse_kt ? -helm.rps_max : 0.0;
  helm.rps_reject = 2.0 * helm.rps_max;
  return helm;
}

}  // namespace

Bridge::Bridge(const sim::ShipParameters& ship, const BridgeOptions& options, lcm::LCM& lcm)
    : options_((options.Validate(), options)),
      lcm_(lcm),
      model_(std::make_unique<sim::MmgModel<double>>(ship)),
      approach_speed_(options.approach_speed > 0 ? options.approach_speed : ship.approach_speed),
      approach_rps_(approach_speed_ > 0 ? sim::SelfPropulsionRps(*model_, approach_speed_) : 0.0),
      helm_(HelmLimits(ship, options.helm, approach_rps_)),
      origin_(options.origin) {
  if (!(approach_speed_ > 0)) {
    throw ArgumentError(fmt::format("ship '{}' gives no approach speed (conditions.approach_speed): pass --speed",
                                    ship.name));
  }
  if (!lcm_.good()) throw InputError("LCM is not initialized (bad --lcm-url?)");

  const double period = 1.0 / options_.rate;
  if (options_.step > 0) {
    const long n = std::lround(period / options_.step);
    if (n < 1 || std::abs(static_cast<double>(n) * options_.step - period) > 1e-9) {
      throw ArgumentError(fmt::format("--step {} s: expected a step that divides the state period 1/rate = {} s",
                                      options_.step, period));
    }
    steps_per_state_ = static_cast<int>(n);
    step_ = options_.step;
  } else {
    const double h_max = ship.principal.Lpp / approach_speed_ / 200.0;
    steps_per_state_ = static_cast<int>(std::ceil(period / h_max - 1e-9));
    step_ = period / steps_per_state_;
  }

  sim::SimulatorOptions so;
  so.method = sim::SimulatorOptions::Method::kFixedStep;
  so.fixed_step = step_;
  sim_ = std::make_unique<sim::Simulator>(*model_, so);
  sim_->Reset(0.0, {0, 0, 0, approach_speed_, 0, 0}, 0.0, approach_rps_);
  if (const auto spec = ParseScript(options_.script)) {
    controller_ = std::make_unique<sim::ManeuverController>(*spec, model_->ship(), approach_speed_, approach_rps_);
  }

  state_channel_ = options_.channel_prefix + "_STATE";
  helm_channel_ = options_.channel_prefix + "_HELM";
  event_channel_ = options_.channel_prefix + "_EVENT";
  helm_subscription_ = lcm_subscribe(lcm_.getUnderlyingLCM(), helm_channel_.c_str(), &Bridge::OnHelm, this);
  if (!helm_subscription_) throw InputError(fmt::format("LCM: cannot subscribe to {}", helm_channel_));
  // LCM keeps 30 messages per subscription and drops the rest unseen: under a
  // flood, valid orders with them, and uncounted. Room for a second of
  // 10,000 messages a second instead (a few MB at most).
  lcm_subscription_set_queue_capacity(helm_subscription_, kHelmQueueCapacity);
  drain_budget_ns_ = std::llround(0.25e9 / (options_.rate * options_.speedup));
  if (options_.nmea) nmea_ = std::make_unique<NmeaUdpSender>(*options_.nmea);
  first_overshoot_ = second_overshoot_ = first_overshoot_time_ = second_overshoot_time_ = kNaN;
  summary_.step = step_;
  summary_.steps_per_state = steps_per_state_;
  KELVIN_CHECK(static_cast<int>(state_.getEncodedSize()) <= static_cast<int>(sizeof(buffer_)),
               "ship_state_t does not fit the encoding buffer");
}

Bridge::~Bridge() {
  if (helm_subscription_) lcm_unsubscribe(lcm_.getUnderlyingLCM(), helm_subscription_);
}

void Bridge::Publish(const std::string& channel, const auto& message) {
  const int n = message.encode(buffer_, 0, static_cast<int>(sizeof(buffer_)));
  if (n < 0 || lcm_.publish(channel, buffer_, static_cast<unsigned>(n)) != 0) ++summary_.publish_failures;
}

void Bridge::FillState(std::int64_t seq) {
  const auto& y = sim_->state();
  const double psi = y[sim::kPsi], u = y[sim::kU], v = y[sim::kV];
  const double x_dot = u * std::cos(psi) - v * std::sin(psi);
  const double y_dot = u * std::sin(psi) + v * std::cos(psi);
  const GeoPoint p = origin_.ToGeodetic(y[sim::kX], y[sim::kY]);
  state_.seq = seq;
  state_.t = sim_->time();
  state_.x = y[sim::kX];
  state_.y = y[sim::kY];
  state_.latitude = p.latitude;
  state_.longitude = p.longitude;
  state_.heading = WrapTwoPi(psi);
  state_.u = u;
  state_.v = v;
  state_.r = y[sim::kR];
  state_.speed_over_ground = std::hypot(u, v);
  state_.course_over_ground = WrapTwoPi(std::atan2(y_dot, x_dot));
  state_.drift_angle = std::atan2(-v, u);
  state_.rudder_angle = sim_->rudder();
  state_.rudder_order = sim_->rudder_order();
  state_.propeller_rps = sim_->rps();
  state_.propeller_rps_order = sim_->rps_order();
  if (controller_ && script_active_) {
    state_.maneuver_phase = static_cast<std::int8_t>(controller_->phase());
  } else if (script_finished_) {
    state_.maneuver_phase = kelvin::ship_state_t::PHASE_FINISHED;
  } else if (controller_) {
    state_.maneuver_phase = kelvin::ship_state_t::PHASE_APPROACH;  // before the script starts
  } else {
    state_.maneuver_phase = kelvin::ship_state_t::PHASE_FREE;
  }
}

void Bridge::PublishEvent(std::int8_t kind, int index, double overshoot, double t, double psi) {
  event_.utime = RealtimeMicroseconds();
  event_.seq = event_seq_++;
  event_.t = t;
  event_.kind = kind;
  event_.index = index;
  event_.heading = psi;
  event_.heading_change = psi - controller_->start_heading();
  event_.rudder_order = sim_->rudder_order();
  event_.overshoot = overshoot;
  const bool stop = kind == kelvin::maneuver_event_t::STOP;
  event_.first_overshoot = stop ? first_overshoot_ : kNaN;
  event_.second_overshoot = stop ? second_overshoot_ : kNaN;
  event_.first_overshoot_time = stop ? first_overshoot_time_ : kNaN;
  event_.second_overshoot_time = stop ? second_overshoot_time_ : kNaN;
  const auto& ex = controller_->execute_times();
  event_.period = stop && ex.size() > 3 ? ex[3] - ex[1] : kNaN;
  Publish(event_channel_, event_);
  ++summary_.events_published;
  if (display_) display_->PublishEvent(event_);
}

void Bridge::DrainLcm() {
  // Never blocks: handleTimeout(0) returns 0 at once when nothing is queued.
  // The first 256 messages always; beyond them bounded in time, so a flood
  // of helm messages cannot starve the simulation: what is left waits in
  // LCM's queue for the next period.
  const std::int64_t until = MonotonicNanoseconds() + drain_budget_ns_;
  for (int n = 1; lcm_.handleTimeout(0) > 0; ++n) {
    ++summary_.lcm_messages_handled;
    if (n >= kDrainAtLeast && MonotonicNanoseconds() >= until) {
      ++summary_.helm_drains_cut;
      break;
    }
  }
  if (display_) display_->DrainHelm(helm_, RealtimeMicroseconds());
}

void Bridge::PublishState() {
  state_.utime = RealtimeMicroseconds();
  Publish(state_channel_, state_);
  ++summary_.states_published;
  if (display_) display_->PublishState(state_, helm_.counters());
}

void Bridge::SendNmea() {
  NmeaFix fix;
  fix.mode = options_.nmea_fix;
  fix.utc_seconds = nmea_epoch_ + state_.t;
  fix.position = {state_.latitude, state_.longitude};
  fix.speed_over_ground = state_.speed_over_ground;
  fix.course_over_ground = state_.course_over_ground;
  fix.heading = state_.heading;
  fix.yaw_rate = state_.r;
  fix.rudder_angle = state_.rudder_angle;
  nmea_->Send(fix);
}

void Bridge::LogHelmProblems(std::int64_t now_ns, bool force) {
  if (!force && static_cast<double>(now_ns - last_log_ns_) < options_.log_interval * 1e9) return;
  const HelmCounters& c = helm_.counters();
  if (c.rejected() != logged_counters_.rejected() || c.clamped != logged_counters_.clamped) {
    spdlog::warn(
        "helm: {} rejected ({} malformed, {} not finite, {} out of range, {} stale, {} from the future, {} unknown "
        "source) and {} clamped since the last report; latest: {}",
        c.rejected() - logged_counters_.rejected(), c.malformed - logged_counters_.malformed,
        c.not_finite - logged_counters_.not_finite, c.out_of_range - logged_counters_.out_of_range,
        c.stale - logged_counters_.stale, c.future - logged_counters_.future,
        c.unknown_source - logged_counters_.unknown_source, c.clamped - logged_counters_.clamped,
        helm_.last_problem());
    logged_counters_ = c;
  }
  last_log_ns_ = now_ns;
}

BridgeSummary Bridge::Run() {
  KELVIN_CHECK(!ran_, "Bridge::Run() runs once per Bridge");
  ran_ = true;
  // Real-time scheduling for the loop, undone on return.
  int old_policy = 0;
  sched_param old_param{};
  pthread_getschedparam(pthread_self(), &old_policy, &old_param);
  if (options_.realtime_priority > 0) {
    sched_param p{};
    p.sched_priority = options_.realtime_priority;
    const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &p);
    if (err == 0) {
      summary_.realtime = true;
    } else {
      spdlog::warn("--realtime-priority {}: cannot switch to SCHED_FIFO ({}); running with normal scheduling",
                   options_.realtime_priority, std::strerror(err));
    }
  }
  nmea_epoch_ = options_.nmea_epoch >= 0 ? options_.nmea_epoch : static_cast<double>(RealtimeMicroseconds()) * 1e-6;
  const double wall_rate = options_.rate * options_.speedup;
  nmea_every_ = std::max(1L, std::lround(wall_rate / options_.nmea_rate));
  Pacer pacer(1.0 / wall_rate, options_.max_lag);

  // Pending events of one state period, published after its state.
  struct Pending {
    std::int8_t kind;
    int index;
    double overshoot;
    double t, psi;
  };
  Pending pending[8];
  int n_pending = 0;

  std::int64_t seq = 0;
  FillState(seq);
  pacer.Start();
  last_log_ns_ = MonotonicNanoseconds();
  PublishState();
  if (!publish_log_.empty()) publish_log_[0] = MonotonicNanoseconds();
  if (nmea_) SendNmea();
  if (controller_) {
    controller_->Start(*sim_);
    script_active_ = true;
    PublishEvent(kelvin::maneuver_event_t::START, 1, kNaN, sim_->time(), sim_->state()[sim::kPsi]);
  }

  summary_.status = BridgeStatus::kCompleted;
  while (true) {
    if (stop_.load(std::memory_order_relaxed)) {
      summary_.status = BridgeStatus::kStopped;
      break;
    }
    DrainLcm();
    double rudder_order = 0, rps_order = 0;
    if (helm_.TakeOrder(&rudder_order, &rps_order)) {
      if (script_active_) {
        ++summary_.helm_ignored_scripted;
      } else {
        sim_->SetRudderOrder(rudder_order);
        sim_->SetRpsOrder(rps_order);
      }
    }
    // The integrator steps of one state period.
    n_pending = 0;
    for (int k = 0; k < steps_per_state_; ++k) {
      if (!script_active_) {
        sim_->Step();
        continue;
      }
      const std::optional<double> trigger = controller_->NextHeadingEvent();
      const double psi_a = sim_->state()[sim::kPsi], r_a = sim_->state()[sim::kR], t_a = sim_->time();
      const std::size_t executes_before = controller_->execute_times().size();
      sim::StepManeuver(*sim_, *controller_);
      if (controller_->execute_times().size() > executes_before) {
        ++executes_;
        if (n_pending < 8) {
          pending[n_pending++] = {kelvin::maneuver_event_t::EXECUTE, executes_, kNaN, sim_->time(),
                                  sim_->state()[sim::kPsi]};
        }
        if (trigger) {
          // The ship keeps turning the old way until the yaw rate changes sign.
          overshoot_armed_ = true;
          overshoot_sign_ = *trigger > controller_->start_heading() ? +1 : -1;
        }
      } else if (overshoot_armed_) {
        const double r_b = sim_->state()[sim::kR];
        if (r_b * overshoot_sign_ <= 0.0 && r_a * overshoot_sign_ > 0.0) {
          // The yaw rate, linear over the step, vanishes at tau; the heading
          // gained until then is the area under it, r_a tau / 2.
          const double tau = step_ * r_a / (r_a - r_b);
          const double psi_ext = psi_a + 0.5 * r_a * tau;
          const double overshoot = sim::ZigZagOvershoot(psi_ext, controller_->start_heading(),
                                                        controller_->spec().heading, overshoot_sign_);
          ++overshoots_;
          const double t_rel = t_a + tau - controller_->start_time();
          if (overshoots_ == 1) {
            first_overshoot_ = overshoot;
            first_overshoot_time_ = t_rel;
          } else if (overshoots_ == 2) {
            second_overshoot_ = overshoot;
            second_overshoot_time_ = t_rel;
          }
          if (n_pending < 8) {
            pending[n_pending++] = {kelvin::maneuver_event_t::OVERSHOOT, overshoots_, overshoot, t_a + tau, psi_ext};
          }
          overshoot_armed_ = false;
        }
      }
    }
    ++seq;
    FillState(seq);
    // The state that completes the maneuver still carries its phase; the
    // ones after it are FINISHED (and the helm takes over).
    bool script_stopped = false;
    if (script_active_ && controller_->Finished(*sim_)) {
      script_active_ = false;
      script_finished_ = true;
      script_stopped = true;
    }
    bool finite = true;
    for (double v : sim_->state()) finite = finite && std::isfinite(v);

    // Publish at the wall-clock deadline of this state.
    pacer.WaitNext();
    PublishState();
    if (static_cast<std::size_t>(seq) < publish_log_.size()) {
      publish_log_[static_cast<std::size_t>(seq)] = MonotonicNanoseconds();
    }
    for (int i = 0; i < n_pending; ++i) {
      // Published after the state, stamped with the event's own instant.
      PublishEvent(pending[i].kind, pending[i].index, pending[i].overshoot, pending[i].t, pending[i].psi);
    }
    if (script_stopped) {
      PublishEvent(kelvin::maneuver_event_t::STOP, 1, kNaN, sim_->time(), sim_->state()[sim::kPsi]);
    }
    if (nmea_ && seq % nmea_every_ == 0) SendNmea();
    LogHelmProblems(MonotonicNanoseconds(), false);

    if (!finite) {
      summary_.status = BridgeStatus::kDiverged;
      break;
    }
    if (options_.duration > 0 ? sim_->time() >= options_.duration - 1e-9 : (controller_ && !script_active_)) break;
  }
  if (script_active_ && summary_.status != BridgeStatus::kDiverged) {
    // The run ends (duration, interrupt) before the maneuver does: its STOP
    // carries the metrics known so far.
    script_active_ = false;
    PublishEvent(kelvin::maneuver_event_t::STOP, 1, kNaN, sim_->time(), sim_->state()[sim::kPsi]);
  }
  DrainLcm();  // count what arrived during the last period
  LogHelmProblems(MonotonicNanoseconds(), true);
  if (summary_.realtime) pthread_setschedparam(pthread_self(), old_policy, &old_param);
  summary_.sim_time = sim_->time();
  summary_.helm = helm_.counters();
  summary_.late_ticks = pacer.late_ticks();
  summary_.resyncs = pacer.resyncs();
  summary_.max_lateness = static_cast<double>(pacer.max_lateness()) * 1e-9;
  if (nmea_) {
    summary_.nmea_sentences_sent = nmea_->sentences_sent();
    summary_.nmea_sentences_dropped = nmea_->sentences_dropped();
  }
  return summary_;
}

}  // namespace kelvin::bridge
