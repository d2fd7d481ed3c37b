// kelvin bridge: the simulator in real time over LCM, helm commands in,
// ship state, maneuver events and NMEA 0183 out.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "bridge/bridge.h"
#include "bridge/derivative_set.h"
#include "bridge/display_feed.h"
#include "bridge/http_display.h"
#include "bridge/lcm_url.h"
#include "data/schema/errors.h"
#include "simulator/mmg/ship_parameters.h"
#include "simulator/mmg/surrogate.h"
#include "tools/kelvin/commands.h"

namespace kelvin::cli {

namespace {

struct BridgeArgs {
  std::string ship_file;
  std::string derivatives;
  bool require_checked = false;
  bridge::BridgeOptions options;
  std::string lcm_url;
  std::string nmea;
  std::string nmea_fix = "autonomous";
  std::string origin;
  std::string http;  // empty: no display
  std::vector<int> helm_sources;
};

std::atomic<bridge::Bridge*> g_running_bridge{nullptr};

extern "C" void StopBridge(int /*signal*/) {
  if (bridge::Bridge* b = g_running_bridge.load()) b->RequestStop();
}

bridge::GeoPoint ParseOrigin(const std::string& text) {
  const std::size_t comma = text.find(',');
  bridge::GeoPoint p;
  try {
    if (comma == std::string::npos) throw std::invalid_argument("no comma");
    std::size_t used_lat = 0, used_lon = 0;
    const std::string lat = text.substr(0, comma), lon = text.substr(comma + 1);
    p.latitude = std::stod(lat, &used_lat);
    p.longitude = std::stod(lon, &used_lon);
    if (used_lat != lat.size() || used_lon != lon.size()) throw std::invalid_argument("trailing text");
  } catch (const std::exception&) {
    throw ArgumentError(fmt::format("--origin '{}': expected <latitude>,<longitude> in degrees, e.g. 53.5,3.0", text));
  }
  return p;
}

const char* StatusName(bridge::BridgeStatus s) {
  switch (s) {
    case bridge::BridgeStatus::kCompleted: return "completed";
    case bridge::BridgeStatus::kStopped: return "stopped";
    case bridge::BridgeStatus::kDiverged: return "DIVERGED (non-finite state)";
  }
  return "?";
}

// The browser display, if --http was given.
std::unique_ptr<bridge::HttpDisplay> StartDisplay(const BridgeArgs& a, const sim::ShipParameters& ship,
                                                  const bridge::DerivativeAssessment& assessment,
                                                  bridge::DisplayFeed& feed) {
  if (a.http.empty()) return nullptr;
  const bridge::HttpDisplayOptions options = bridge::HttpDisplayOptions::Parse(a.http);
  bridge::DisplayInfo info;
  info.ship = ship.name;
  info.script = a.options.script;
  info.derivatives_checked = assessment.status == bridge::DerivativeStatus::kChecked;
  info.derivatives = assessment.message;
  info.origin_latitude = a.options.origin.latitude;
  info.origin_longitude = a.options.origin.longitude;
  info.helm_source = bridge::kPageHelmSource;
  const auto& sources = a.options.helm.sources;
  if (!sources.empty() && std::find(sources.begin(), sources.end(), bridge::kPageHelmSource) == sources.end()) {
    spdlog::warn("--http: the page's helm orders (source_id {}) will be rejected: add --helm-source {}",
                 bridge::kPageHelmSource, bridge::kPageHelmSource);
  }
  auto display = std::make_unique<bridge::HttpDisplay>(feed, info, options);
  spdlog::info("display: open {} in a browser", display->url());
  return display;
}

// Where the multicast group is joined on a network interface, other
// machines there reach the helm channel (TTL 0 only keeps what is sent here).
void WarnIfOtherMachinesCanSend(const std::string& lcm_url, const std::string& helm_channel) {
  const std::optional<std::string> group = bridge::UdpmGroup(lcm_url);
  if (!group) return;
  std::ifstream igmp("/proc/net/igmp");
  std::stringstream text;
  text << igmp.rdbuf();
  std::vector<std::string> outside;
  for (const std::string& device : bridge::MulticastMembers(text.str(), *group)) {
    if (device != "lo") outside.push_back(device);
  }
  if (outside.empty()) return;
  spdlog::warn("LCM {}: the multicast group {} is joined on {}: other machines on that network can send to {} (the "
               "helm filter and --helm-source still apply); 'ip route add 224.0.0.0/4 dev lo' keeps it on this machine",
               lcm_url, *group, fmt::join(outside, ", "), helm_channel);
}

void PrintPageCounters(const bridge::PageCounters& p) {
  fmt::print("  display: {} page helm orders queued; dropped: {} without the helm, {} malformed, {} oversized, {} bad "
             "requests, {} while the inbox was full; {} streams refused\n",
             p.helm_queued, p.not_holder, p.malformed, p.oversized, p.bad_requests, p.inbox_full, p.streams_refused);
}

void RunBridge(BridgeArgs& a) {
  sim::ShipParameters ship = sim::LoadShip(a.ship_file);
  std::optional<sim::DerivativeSet> set;
  if (!a.derivatives.empty()) set = sim::LoadDerivativeSet(a.derivatives);
  ship = sim::SurrogateShip(std::move(ship), a.ship_file, set ? &*set : nullptr);
  const bridge::DerivativeAssessment assessment = bridge::AssessDerivatives(ship, set, a.require_checked);
  if (assessment.status == bridge::DerivativeStatus::kChecked) {
    spdlog::info("{}", assessment.message);
  } else {
    spdlog::warn("*** UNCHECKED HULL DERIVATIVES *** {}", assessment.message);
    spdlog::warn("*** the streamed motion is not validated against CFD; --require-checked refuses such a set ***");
  }

  bridge::BridgeOptions& o = a.options;
  if (!a.nmea.empty()) o.nmea = bridge::UdpEndpoint::Parse(a.nmea, "--nmea");
  o.nmea_fix = bridge::ParseNmeaFixMode(a.nmea_fix, "--nmea-fix");
  if (!a.origin.empty()) o.origin = ParseOrigin(a.origin);
  o.helm.sources.assign(a.helm_sources.begin(), a.helm_sources.end());
  o.Validate();

  const std::string lcm_url = bridge::ResolveLcmUrl(a.lcm_url);
  lcm::LCM lcm(lcm_url);
  if (!lcm.good()) {
    throw ArgumentError(fmt::format("--lcm-url '{}': LCM cannot open this URL (expected e.g. udpm://239.255.76.67:7667?ttl=0 "
                                    "or memq://)",
                                    lcm_url));
  }
  if (const auto ttl = bridge::UdpmTtl(lcm_url); ttl && *ttl > 0) {
    spdlog::warn("LCM {}: multicast TTL {} sends the states beyond this machine (ttl=0 keeps them on it)", lcm_url,
                 *ttl);
  }
  bridge::Bridge bridge(ship, o, lcm);
  WarnIfOtherMachinesCanSend(lcm_url, bridge.helm_channel());
  bridge::DisplayFeed feed;
  const std::unique_ptr<bridge::HttpDisplay> display = StartDisplay(a, ship, assessment, feed);
  if (display) bridge.SetDisplay(&feed);
  spdlog::info("bridge: {} at {} Hz (step {} s x {}), speedup {}, {}; LCM {}, channels {}, {}, {}{}", ship.name,
               o.rate, bridge.step(), bridge.steps_per_state(), o.speedup,
               o.script.empty() ? std::string("helm commands steer") : "script " + o.script, lcm_url,
               bridge.state_channel(),
               bridge.helm_channel(), bridge.event_channel(),
               o.nmea ? fmt::format(", NMEA 0183 to {} at {} Hz ({} fixes)", o.nmea->ToString(), o.nmea_rate,
                                    bridge::NmeaFixModeName(o.nmea_fix))
                      : std::string());

  g_running_bridge.store(&bridge);
  struct sigaction sa {};
  sa.sa_handler = StopBridge;
  sigemptyset(&sa.sa_mask);
  struct sigaction old_int {}, old_term {};
  sigaction(SIGINT, &sa, &old_int);
  sigaction(SIGTERM, &sa, &old_term);
  const bridge::BridgeSummary s = bridge.Run();
  sigaction(SIGINT, &old_int, nullptr);
  sigaction(SIGTERM, &old_term, nullptr);
  g_running_bridge.store(nullptr);

  const auto& h = s.helm;
  fmt::print("bridge {}: t = {:.3f} s, {} states, {} events published ({} failed)\n", StatusName(s.status), s.sim_time,
             s.states_published, s.events_published, s.publish_failures);
  fmt::print("  lcm: {} messages handled; the drain stopped at its time budget in {} state periods\n",
             s.lcm_messages_handled, s.helm_drains_cut);
  fmt::print("  helm: {} received, {} accepted ({} clamped), {} rejected: {} malformed, {} not finite, {} out of range, "
             "{} stale, {} from the future, {} unknown source; {} ignored while scripted\n",
             h.received, h.accepted, h.clamped, h.rejected(), h.malformed, h.not_finite, h.out_of_range, h.stale,
             h.future, h.unknown_source, s.helm_ignored_scripted);
  fmt::print("  pacing{}: {} late ticks, {} resyncs, max lateness {:.3f} ms\n", s.realtime ? " (SCHED_FIFO)" : "",
             s.late_ticks, s.resyncs, s.max_lateness * 1e3);
  if (o.nmea) fmt::print("  nmea: {} sentences sent, {} dropped\n", s.nmea_sentences_sent, s.nmea_sentences_dropped);
  if (display) PrintPageCounters(display->counters());
  if (s.status == bridge::BridgeStatus::kDiverged) {
    throw std::runtime_error(fmt::format("simulation diverged at t = {} s", s.sim_time));
  }
}

}  // namespace

Command AddBridgeCommand(CLI::App& app) {
  auto args = std::make_shared<BridgeArgs>();
  CLI::App* cmd = app.add_subcommand("bridge", "Stream the simulator in real time over LCM (helm in, state/NMEA out)");
  cmd->add_option("ship", args->ship_file, "Ship file (data/ships/<ship>.yaml)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--derivatives", args->derivatives, "Derivative set replacing the ship file's hull section")
      ->check(CLI::ExistingFile);
  cmd->add_flag("--require-checked", args->require_checked,
                "Refuse to stream hull derivatives without a passing check against CFD");
  auto& o = args->options;
  cmd->add_option("--rate", o.rate, "State messages per second of simulation time (Hz)")->capture_default_str();
  cmd->add_option("--speedup", o.speedup, "Simulation seconds per wall-clock second")->capture_default_str();
  cmd->add_option("--script", o.script,
                  "Play an IMO maneuver: turning:<deg>:stbd|port, zigzag:<deg>/<deg>:stbd|port, spiral:<max>:<step>");
  cmd->add_option("--duration", o.duration, "Simulation time in s (0: until the script ends, or until Ctrl-C)")
      ->capture_default_str();
  cmd->add_option("--step", o.step, "Integrator step in s dividing 1/rate (default: at most Lpp/U0/200)");
  cmd->add_option("--speed", o.approach_speed, "Initial speed in m/s (default: the ship file's approach speed)");
  cmd->add_option("--lcm-url", args->lcm_url, "LCM URL (default: $LCM_DEFAULT_URL, else udpm://239.255.76.67:7667?ttl=0: loopback only)");
  cmd->add_option("--channel-prefix", o.channel_prefix, "Channels <prefix>_STATE, <prefix>_HELM, <prefix>_EVENT")
      ->capture_default_str();
  cmd->add_option("--nmea", args->nmea, "Send NMEA 0183 over UDP to host:port (without a value: 127.0.0.1:10110)")
      ->expected(0, 1)
      ->default_str("127.0.0.1:10110");
  cmd->add_option("--http", args->http,
                  "Serve the browser display at host:port (without a value: 127.0.0.1:8080; loopback unless you name "
                  "another address)")
      ->expected(0, 1)
      ->default_str("127.0.0.1:8080");
  cmd->add_option("--nmea-fix", args->nmea_fix,
                  "How NMEA flags the fix: autonomous (FAA mode A, GGA quality 1; shown by plotters and gpsd) or "
                  "simulated (FAA mode S, GGA quality 8)")
      ->capture_default_str();
  cmd->add_option("--nmea-rate", o.nmea_rate, "NMEA fixes per wall-clock second, 1 to 10")->capture_default_str();
  cmd->add_option("--origin", args->origin, "Latitude,longitude in deg of the start position (default 53.5,3.0)");
  cmd->add_option("--stale-timeout", o.helm.stale_timeout, "Reject helm commands older than this (s)")
      ->capture_default_str();
  cmd->add_option("--realtime-priority", o.realtime_priority,
                  "Run the loop with SCHED_FIFO at this priority, 1-99 (needs root or CAP_SYS_NICE)");
  cmd->add_option("--helm-source", args->helm_sources, "Accept helm commands only from this source_id (repeatable)");
  return {cmd, [args] { RunBridge(*args); }};
}

}  // namespace kelvin::cli
