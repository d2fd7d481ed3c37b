// kelvin listen: the project's own LCM listener for `kelvin bridge`: records
// every ship_state_t and maneuver_event_t, checks their sequence numbers and
// writes the states as CSV.
#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <string>

#include "bridge/lcm_url.h"
#include "bridge/listener.h"
#include "data/schema/atomic_file.h"
#include "data/schema/errors.h"
#include "tools/kelvin/commands.h"

namespace kelvin::cli {

namespace {

struct ListenArgs {
  std::string lcm_url;
  std::string channel_prefix = "KELVIN";
  long count = 0;             // stop after this many states (0: no limit)
  double idle_timeout = 5.0;  // s without a message after the first one
  double timeout = 0.0;       // s in all (0: no limit)
  std::string output;         // CSV of the states
};

std::atomic<bool> g_stop_listen{false};
extern "C" void StopListen(int /*signal*/) { g_stop_listen.store(true); }

const char* EventName(std::int8_t kind) {
  switch (kind) {
    case kelvin::maneuver_event_t::START: return "START";
    case kelvin::maneuver_event_t::EXECUTE: return "EXECUTE";
    case kelvin::maneuver_event_t::OVERSHOOT: return "OVERSHOOT";
    case kelvin::maneuver_event_t::STOP: return "STOP";
  }
  return "?";
}

void RunListen(const ListenArgs& a) {
  if (a.count < 0) throw ArgumentError(fmt::format("--count {}: expected a number of states >= 0", a.count));
  if (!(a.idle_timeout > 0)) {
    throw ArgumentError(fmt::format("--idle-timeout {}: expected a positive time in s", a.idle_timeout));
  }
  if (!(a.timeout >= 0)) throw ArgumentError(fmt::format("--timeout {}: expected a time >= 0 s", a.timeout));
  const std::string lcm_url = bridge::ResolveLcmUrl(a.lcm_url);
  lcm::LCM lcm(lcm_url);
  if (!lcm.good()) throw ArgumentError(fmt::format("--lcm-url '{}': LCM cannot open this URL", lcm_url));
  bridge::Listener listener(lcm, a.channel_prefix);
  fmt::print("listen: subscribed to {}_STATE and {}_EVENT\n", a.channel_prefix, a.channel_prefix);
  std::fflush(stdout);

  g_stop_listen.store(false);
  struct sigaction sa {};
  sa.sa_handler = StopListen;
  sigemptyset(&sa.sa_mask);
  struct sigaction old_int {}, old_term {};
  sigaction(SIGINT, &sa, &old_int);
  sigaction(SIGTERM, &sa, &old_term);
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto last_message = start;
  std::size_t seen = 0;
  while (!g_stop_listen.load()) {
    lcm.handleTimeout(50);
    const auto now = Clock::now();
    const std::size_t n = listener.states().size() + listener.events().size();
    if (n != seen) {
      seen = n;
      last_message = now;
    }
    if (a.count > 0 && static_cast<long>(listener.states().size()) >= a.count) break;
    if (seen > 0 && std::chrono::duration<double>(now - last_message).count() > a.idle_timeout) break;
    if (a.timeout > 0 && std::chrono::duration<double>(now - start).count() > a.timeout) break;
  }
  sigaction(SIGINT, &old_int, nullptr);
  sigaction(SIGTERM, &old_term, nullptr);

  for (const auto& e : listener.events()) {
    fmt::print("event {} {} at t = {:.3f} s: heading change {:.3f} deg, rudder order {:.1f} deg{}\n",
               EventName(e.kind), e.index, e.t, e.heading_change * 180 / M_PI, e.rudder_order * 180 / M_PI,
               e.kind == kelvin::maneuver_event_t::OVERSHOOT ? fmt::format(", overshoot {:.3f} deg", e.overshoot * 180 / M_PI)
                                                             : std::string());
  }
  const auto& st = listener.states();
  fmt::print("listen: {} states{}, {} events, {} out of sequence, {} malformed\n", st.size(),
             st.empty() ? std::string() : fmt::format(" (seq {}..{}, t {:.3f}..{:.3f} s)", st.front().seq,
                                                      st.back().seq, st.front().t, st.back().t),
             listener.events().size(), listener.out_of_sequence(), listener.malformed());
  if (!a.output.empty()) {
    std::string csv =
        "seq,t,x,y,latitude,longitude,heading,u,v,r,speed_over_ground,course_over_ground,drift_angle,rudder_angle,"
        "rudder_order,propeller_rps,propeller_rps_order,maneuver_phase\n";
    for (const auto& s : st) {
      csv += fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},"
                         "{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{}\n",
                         s.seq, s.t, s.x, s.y, s.latitude, s.longitude, s.heading, s.u, s.v, s.r, s.speed_over_ground,
                         s.course_over_ground, s.drift_angle, s.rudder_angle, s.rudder_order, s.propeller_rps,
                         s.propeller_rps_order, static_cast<int>(s.maneuver_phase));
    }
    data::WriteFileAtomically(a.output, csv);
    fmt::print("  written: {}\n", a.output);
  }
}

}  // namespace

Command AddListenCommand(CLI::App& app) {
  auto args = std::make_shared<ListenArgs>();
  CLI::App* cmd = app.add_subcommand("listen", "Record the state and events that kelvin bridge publishes over LCM");
  cmd->add_option("--lcm-url", args->lcm_url, "LCM URL (default: $LCM_DEFAULT_URL, else udpm://239.255.76.67:7667?ttl=0)");
  cmd->add_option("--channel-prefix", args->channel_prefix, "Channels <prefix>_STATE and <prefix>_EVENT")
      ->capture_default_str();
  cmd->add_option("--count", args->count, "Stop after this many states (0: no limit)")->capture_default_str();
  cmd->add_option("--idle-timeout", args->idle_timeout, "Stop this many s after the last message")
      ->capture_default_str();
  cmd->add_option("--timeout", args->timeout, "Stop after this many s in all (0: no limit)")->capture_default_str();
  cmd->add_option("-o,--output", args->output, "Write the states as CSV");
  return {cmd, [args] { RunListen(*args); }};
}

}  // namespace kelvin::cli
